// SPDX-License-Identifier: GPL-3.0-or-later
// The control points of a model, read from its JSON (the source of truth)
// and linked so that a model stays valid when one is moved (issue 29).
//
// A control point is a point of a net (coons-model(5): "points" of curves,
// surfaces and volumes, "corners" of bilinear patches and body0), where the
// model places it: through every reference's transform, so a definition
// referenced twice gives two points. Tangents, twists and cross curves are
// vectors, not points, and are not listed. Points at the same place (within
// 1e-9 of the model's size, the loader's consistency tolerance) are one
// control point: shared corners, edges of neighbouring faces, body 1 corners,
// network end nodes, faces of lattice cells shared by equal corner points or
// nets. The keys of a morph are separate shapes: a point of one key is not
// linked to a point of another key at the same place.
//
// Moving a control point writes the new place into every JSON location of
// that point (through the inverse of its transform); a location reached
// through a definition that is referenced again moves that other instance
// too, and whatever sits at the other instance's old place follows it.
(function (root) {
  'use strict';
  const SKIP = new Set(['cross', 'tangents', 'twist', 'weights', 'knots', 'transform', 'degree',
                        'at', 's_nodes', 't_nodes', 'type', 'name', 'blend', 'path', 'ref',
                        'reverse', 'swap', 'flip_s', 'flip_t', 'thickness', 'side', 't',
                        'closed']);
  const IDENTITY = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]];

  function apply(A, x) {
    const z = x.length > 2 ? x[2] : 0;
    return [0, 1, 2].map((r) => A[r][0] * x[0] + A[r][1] * x[1] + A[r][2] * z + A[r][3]);
  }
  function compose(A, B) { // x -> A(B(x))
    return [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) =>
      A[r][0] * B[0][c] + A[r][1] * B[1][c] + A[r][2] * B[2][c] + (c === 3 ? A[r][3] : 0)));
  }
  function invertApply(A, y) { // the x with A(x) = y
    const m = A, b = [y[0] - m[0][3], y[1] - m[1][3], y[2] - m[2][3]];
    const det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    const col = (k) => {
      const n = m.map((row, r) => row.slice(0, 3).map((v, c) => (c === k ? b[r] : v)));
      return (n[0][0] * (n[1][1] * n[2][2] - n[1][2] * n[2][1]) -
              n[0][1] * (n[1][0] * n[2][2] - n[1][2] * n[2][0]) +
              n[0][2] * (n[1][0] * n[2][1] - n[1][1] * n[2][0])) / det;
    };
    if (A === IDENTITY || isIdentity(A)) return y.slice();
    return [col(0), col(1), col(2)];
  }
  function isIdentity(A) {
    return A.every((row, r) => row.every((v, c) => v === (r === c ? 1 : 0)));
  }
  function isPoint(v) {
    return Array.isArray(v) && (v.length === 2 || v.length === 3) &&
           v.every((x) => typeof x === 'number');
  }

  // Every control point as placed: {path, A, world, ctx, body} in the order
  // of the bodies.
  function leaves(doc) {
    const out = [];
    const defs = doc.define || {};
    function net(v, path, A, ctx, body) {
      if (isPoint(v)) out.push({ path, A, world: apply(A, v), ctx, body });
      else if (Array.isArray(v)) v.forEach((w, i) => net(w, path.concat(i), A, ctx, body));
    }
    function walk(node, path, A, ctx, body, depth) {
      if (!node || typeof node !== 'object' || depth > 40) return;
      if (Array.isArray(node)) {
        node.forEach((v, i) => walk(v, path.concat(i), A, ctx, body, depth + 1));
        return;
      }
      if (typeof node.ref === 'string' && defs[node.ref]) {
        const B = Array.isArray(node.transform) ? compose(A, node.transform) : A;
        walk(defs[node.ref], ['define', node.ref], B, ctx, body, depth + 1);
        return;
      }
      for (const key of Object.keys(node)) {
        if (SKIP.has(key)) continue;
        const v = node[key];
        if (key === 'points' || key === 'corners') net(v, path.concat(key), A, ctx, body);
        else if (key === 'keys' && Array.isArray(v))
          v.forEach((k, i) => walk(k, path.concat(key, i), A,
                                   Object.assign({}, ctx, { [path.join('/')]: i }), body, depth + 1));
        else walk(v, path.concat(key), A, ctx, body, depth + 1);
      }
    }
    (doc.bodies || []).forEach((b, i) => walk(b, ['bodies', i], IDENTITY, {}, i, 0));
    return out;
  }

  function compatible(a, b) {
    for (const k in a) if (k in b && a[k] !== b[k]) return false;
    return true;
  }

  // The control points: {points: [{id, body, xyz, members}], lo, hi}; a
  // member is one placed JSON location {path, A}.
  function controlPoints(doc) {
    const L = leaves(doc);
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const l of L) for (let d = 0; d < 3; d++) {
      lo[d] = Math.min(lo[d], l.world[d]);
      hi[d] = Math.max(hi[d], l.world[d]);
    }
    const eps = 1e-9 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    // coincident leaves (sweep along x), union-find
    const parent = L.map((_, i) => i);
    const find = (i) => { while (parent[i] !== i) i = parent[i] = parent[parent[i]]; return i; };
    const order = L.map((_, i) => i).sort((a, b) => L[a].world[0] - L[b].world[0]);
    for (let a = 0; a < order.length; a++) {
      const p = L[order[a]];
      for (let b = a + 1; b < order.length; b++) {
        const q = L[order[b]];
        if (q.world[0] - p.world[0] > eps) break;
        if (Math.hypot(q.world[0] - p.world[0], q.world[1] - p.world[1],
                       q.world[2] - p.world[2]) <= eps && compatible(p.ctx, q.ctx)) {
          const ra = find(order[a]), rb = find(order[b]);
          if (ra !== rb) parent[Math.max(ra, rb)] = Math.min(ra, rb);
        }
      }
    }
    const byRoot = new Map(), points = [];
    L.forEach((l, i) => {
      const r = find(i);
      if (!byRoot.has(r)) {
        byRoot.set(r, points.length);
        points.push({ id: points.length, body: l.body, xyz: l.world.slice(), members: [] });
      }
      points[byRoot.get(r)].members.push({ path: l.path, A: l.A });
    });
    return { points, lo, hi };
  }

  function diagonal(cps) {
    return Math.hypot(cps.hi[0] - cps.lo[0], cps.hi[1] - cps.lo[1], cps.hi[2] - cps.lo[2]);
  }
  function get(doc, path) { return path.reduce((o, k) => o[k], doc); }
  function set(doc, path, x) {
    const parent = get(doc, path.slice(0, -1)), old = parent[path[path.length - 1]];
    parent[path[path.length - 1]] = old.length === 2 && x[2] === 0 ? [x[0], x[1]] : x.slice();
  }
  function worldAt(doc, loc) { return apply(loc.A, get(doc, loc.path)); }

  // ---- curves as linear maps of their points (for network nodes) ----
  // The weights phi_k(t) with c(t) = sum phi_k(t) P_k + (terms that do not
  // depend on the points: Hermite tangents), coons-model(5)'s definitions.
  function bsplineBasis(p, knots, n1, t) { // n1 points; t in [0,1]
    const k = knots || (() => {
      const m = n1 - 1, inner = m - p, out = [];
      for (let i = 0; i <= p; i++) out.push(0);
      for (let i = 1; i <= inner; i++) out.push(i / (inner + 1));
      for (let i = 0; i <= p; i++) out.push(1);
      return out;
    })();
    const lo = k[p], hi = k[n1];
    const x = lo + t * (hi - lo);
    let span = p;
    for (let i = p; i < n1; i++) if (k[i] < k[i + 1] && x >= k[i]) span = i; // last non-empty span at or left of x
    const N = [1], left = [], right = [];
    for (let j = 1; j <= p; j++) {
      left[j] = x - k[span + 1 - j];
      right[j] = k[span + j] - x;
      let saved = 0;
      for (let r = 0; r < j; r++) {
        const tmp = N[r] / (right[r + 1] + left[j - r]);
        N[r] = saved + right[r + 1] * tmp;
        saved = left[j - r] * tmp;
      }
      N[j] = saved;
    }
    const phi = new Array(n1).fill(0);
    for (let j = 0; j <= p; j++) phi[span - p + j] = N[j];
    return phi;
  }
  function curveBasis(c, t) {
    const n1 = c.points.length, phi = new Array(n1).fill(0);
    switch (c.type) {
      case 'line': return [1 - t, t];
      case 'hermite': return [1 - 3 * t * t + 2 * t * t * t, 3 * t * t - 2 * t * t * t];
      case 'polyline': {
        const n = n1 - 1, i = Math.min(Math.floor(t * n), n - 1), u = t * n - i;
        phi[i] = 1 - u;
        phi[i + 1] = u;
        return phi;
      }
      case 'bezier': {
        const n = n1 - 1;
        let b = 1;
        for (let i = 0; i <= n; i++) {
          phi[i] = b * Math.pow(t, i) * Math.pow(1 - t, n - i);
          b = b * (n - i) / (i + 1);
        }
        return phi;
      }
      case 'coons-cubic': {
        const closed = c.closed === true, segs = closed ? n1 : n1 - 3;
        const s = Math.min(Math.floor(t * segs), segs - 1), u = t * segs - s;
        const C = [(1 - u) ** 3 / 6, (3 * u ** 3 - 6 * u * u + 4) / 6, (-3 * u ** 3 + 3 * u * u + 3 * u + 1) / 6, u ** 3 / 6];
        for (let k = 0; k < 4; k++) phi[(s + k) % n1] += C[k];
        return phi;
      }
      case 'clamped-cubic': {
        const n = n1 - 1, k = [0, 0, 0, 0];
        for (let i = 1; i <= n - 3; i++) k.push(i);
        k.push(n - 2, n - 2, n - 2, n - 2);
        return bsplineBasis(3, k, n1, t);
      }
      case 'bspline': {
        const N = bsplineBasis(c.degree, c.knots, n1, t);
        if (!c.weights) return N;
        const den = N.reduce((a, v, i) => a + v * c.weights[i], 0);
        return N.map((v, i) => v * c.weights[i] / den);
      }
      default: return null;
    }
  }
  // d phi_k / dt for the curve types whose ends the cross curves of
  // hermite-coons patches follow (line, bezier, hermite); null otherwise
  function curveDerivBasis(c, t) {
    const n1 = c.points.length;
    if (c.type === 'line') return [-1, 1];
    if (c.type === 'hermite') return [-6 * t + 6 * t * t, 6 * t - 6 * t * t];
    if (c.type !== 'bezier') return null;
    const n = n1 - 1, phi = new Array(n1).fill(0);
    const b = (i, m) => { // Bernstein i of degree m
      if (i < 0 || i > m) return 0;
      let c0 = 1;
      for (let k = 0; k < i; k++) c0 = c0 * (m - k) / (k + 1);
      return c0 * Math.pow(t, i) * Math.pow(1 - t, m - i);
    };
    for (let i = 0; i <= n; i++) phi[i] = n * (b(i - 1, n - 1) - b(i, n - 1));
    return phi;
  }
  function curveDerivDelta(c, co, t) {
    if (!c || !co || !Array.isArray(c.points) || !Array.isArray(co.points)) return [0, 0, 0];
    const phi = curveDerivBasis(c, t), d = [0, 0, 0];
    if (!phi) return null;
    phi.forEach((f, k) => {
      if (!f) return;
      for (let a = 0; a < 3; a++) d[a] += f * ((c.points[k][a] || 0) - (co.points[k][a] || 0));
    });
    return d;
  }
  // the change of curve c (old: co) at t, from the change of its points
  function curveDelta(c, co, t) {
    if (!c || !co || !Array.isArray(c.points) || !Array.isArray(co.points)) return [0, 0, 0];
    const phi = curveBasis(c, t), d = [0, 0, 0];
    if (!phi) return d;
    phi.forEach((f, k) => {
      if (!f) return;
      for (let a = 0; a < 3; a++) d[a] += f * ((c.points[k][a] || 0) - (co.points[k][a] || 0));
    });
    return d;
  }
  // Solves (Phi Phi^T) y = r (Gauss, partial pivoting); null if singular.
  function solve(G, r) {
    const n = G.length, M = G.map((row, i) => row.concat([r[i]]));
    for (let c = 0; c < n; c++) {
      let piv = c;
      for (let i = c + 1; i < n; i++) if (Math.abs(M[i][c]) > Math.abs(M[piv][c])) piv = i;
      if (Math.abs(M[piv][c]) < 1e-13) return null;
      [M[c], M[piv]] = [M[piv], M[c]];
      for (let i = 0; i < n; i++) if (i !== c) {
        const f = M[i][c] / M[c][c];
        for (let j = c; j <= n; j++) M[i][j] -= f * M[c][j];
      }
    }
    return M.map((row, i) => row[n] / row[i]);
  }
  // The smallest change of the points of curve c (at JSON path cpath) not
  // yet moved that changes c(params[b]) by r[b] for every b; the paths
  // written go to fixes.
  // Points linked to other places are left alone when the others suffice
  // (moving one would move its links and undo another curve's fit).
  function adjustCurve(c, cpath, params, r, changed, fixes, shared) {
    if (r.every((v) => v.every((x) => Math.abs(x) === 0))) return;
    const base = cpath.join('/') + '/points/';
    if (shared && adjustCurve1(c, cpath, params, r, changed, fixes, (k) => !shared.has(base + k))) return;
    adjustCurve1(c, cpath, params, r, changed, fixes, () => true);
  }
  function adjustCurve1(c, cpath, params, r, changed, fixes, allowed) {
    const base = cpath.join('/') + '/points/';
    const free = c.points.map((_, k) => k).filter((k) => !changed.has(base + k) && allowed(k));
    if (!free.length) return false;
    const Phi = params.map((u) => { const phi = curveBasis(c, u); return phi ? free.map((k) => phi[k]) : null; });
    if (Phi.some((row) => !row)) return false;
    // only the nodes some free point reaches take part; a node none reaches
    // must need no change
    const rows = Phi.map((row, b) => b).filter((b) => Phi[b].some((x) => Math.abs(x) > 1e-14));
    if (Phi.some((row, b) => !rows.includes(b) && r[b].some((x) => x !== 0))) return false;
    const G = rows.map((b) => rows.map((e) => Phi[b].reduce((acc, x, k) => acc + x * Phi[e][k], 0)));
    const delta = [[], [], []];
    for (let d = 0; d < 3; d++) {
      const y = solve(G, rows.map((b) => r[b][d]));
      if (!y) return false;
      delta[d] = free.map((_, k) => rows.reduce((acc, b, i) => acc + Phi[b][k] * y[i], 0));
    }
    free.forEach((k, i) => {
      const dx = [delta[0][i], delta[1][i], delta[2][i]];
      if (dx.every((x) => x === 0)) return;
      const p = c.points[k];
      const z = (p.length > 2 ? p[2] : 0) + dx[2];
      c.points[k] = p.length === 2 && z === 0 ? [p[0] + dx[0], p[1] + dx[1]] : [p[0] + dx[0], p[1] + dx[1], z];
      fixes.push(cpath.concat('points', k));
    });
    return true;
  }
  // Curves that must meet at shared ends (the 12 edges of a body1 at its
  // 8 corners, the 4 boundary curves of a coons or hermite-coons patch):
  // where one that moved changed its end, the others' ends follow, their
  // other ends staying where they are (or following a moved curve there).
  function repairCorners(list, changed, fixes, shared) {
    const isChanged = (p) => { const pre = p.join('/') + '/'; for (const k of changed) if (k.startsWith(pre)) return true; return false; };
    const target = new Map();
    for (const e of list) {
      if (!isChanged(e.path)) continue;
      for (const [t, corner] of e.ends)
        if (!target.has(corner)) target.set(corner, { owner: e, delta: curveDelta(e.c, e.co, t) });
    }
    if (!target.size) return;
    // every curve but the one that sets a corner follows it there (with
    // its points not yet moved: a moved curve adjusts its other points)
    for (const e of list) {
      if (!Array.isArray(e.c.points)) continue;
      const r = e.ends.map(([t, corner]) => {
        const tg = target.get(corner), have = curveDelta(e.c, e.co, t);
        const want = !tg ? [0, 0, 0] : tg.owner === e ? have : tg.delta;
        return [want[0] - have[0], want[1] - have[1], want[2] - have[2]];
      });
      adjustCurve(e.c, e.path, e.ends.map(([t]) => t), r, changed, fixes, shared);
    }
  }
  // Networks whose rows or columns changed: the other family is corrected
  // by the smallest change of its points (those not already moved) that
  // makes rows[j](s_i) = columns[i](t_j) again at every node. Returns the
  // JSON paths written.
  function repairNetworks(before, doc, changed, shared) {
    const fixes = [];
    const isChanged = (prefix) => { for (const k of changed) if (k.startsWith(prefix + '/')) return true; return false; };
    function visit(node, path) {
      if (!node || typeof node !== 'object') return;
      if (Array.isArray(node)) { node.forEach((v, i) => visit(v, path.concat(i))); return; }
      if (node.type === 'network' && Array.isArray(node.rows) && Array.isArray(node.columns)) fix(node, path);
      const old = () => get(before, path);
      if (node.type === 'body1' && node.edges) {
        const list = [];
        for (const e of Object.keys(node.edges)) {
          const f = e[0], d1 = +e[1], d2 = +e[2];
          const corner = (a) => (f === 'u' ? [a, d1, d2] : f === 'v' ? [d1, a, d2] : [d1, d2, a]).join('');
          list.push({ c: node.edges[e], co: old().edges[e], path: path.concat('edges', e), ends: [[0, corner(0)], [1, corner(1)]] });
        }
        repairCorners(list, changed, fixes, shared);
      }
      if ((node.type === 'coons' || node.type === 'hermite-coons') && node.boundary) {
        const ends = { t0: [[0, '00'], [1, '10']], t1: [[0, '01'], [1, '11']], s0: [[0, '00'], [1, '01']], s1: [[0, '10'], [1, '11']] };
        const list = Object.keys(ends).filter((k) => node.boundary[k])
          .map((k) => ({ c: node.boundary[k], co: old().boundary[k], path: path.concat('boundary', k), ends: ends[k] }));
        repairCorners(list, changed, fixes, shared);
        if (node.type === 'hermite-coons' && node.cross) repairCross(node, path, old());
      }
      for (const k of Object.keys(node)) if (!SKIP.has(k) || k === 'cross') visit(node[k], path.concat(k));
    }
    // cross curves follow the corner tangents of the boundary they must
    // agree with (coons-model(5), hermite-coons)
    function repairCross(node, path, old) {
      const pairs = { t0: [['s0', 0], ['s1', 0]], t1: [['s0', 1], ['s1', 1]],
                      s0: [['t0', 0], ['t1', 0]], s1: [['t0', 1], ['t1', 1]] };
      for (const k of Object.keys(pairs)) {
        const c = node.cross[k], co = old.cross && old.cross[k];
        if (!c || !co || !Array.isArray(c.points)) continue;
        const r = [];
        for (const [end, [b, bEnd]] of pairs[k].entries()) {
          const want = curveDerivDelta(node.boundary[b], old.boundary[b], bEnd);
          if (!want) return;
          const have = curveDelta(c, co, end);
          r.push([want[0] - have[0], want[1] - have[1], want[2] - have[2]]);
        }
        adjustCurve(c, path.concat('cross', k), [0, 1], r, changed, fixes, shared);
      }
    }
    function fix(net, path) {
      const old = get(before, path);
      const np = path.join('/');
      const rowsCh = isChanged(np + '/rows'), colsCh = isChanged(np + '/columns');
      if (!rowsCh && !colsCh) return;
      const m = net.columns.length - 1, n = net.rows.length - 1;
      const sN = net.s_nodes || Array.from({ length: m + 1 }, (_, i) => i / m);
      const tN = net.t_nodes || Array.from({ length: n + 1 }, (_, j) => j / n);
      const adjust = rowsCh ? 'columns' : 'rows', other = rowsCh ? 'rows' : 'columns';
      const params = adjust === 'columns' ? tN : sN; // along the adjusted curves
      const at = adjust === 'columns' ? sN : tN;     // where the other family meets them
      net[adjust].forEach((c, a) => {
        const co = old[adjust][a];
        if (!Array.isArray(c.points) || !co || !Array.isArray(co.points)) return;
        const r = params.map((u, b) => {
          const want = curveDelta(net[other][b], old[other][b], at[a]);
          const have = curveDelta(c, co, u);
          return [want[0] - have[0], want[1] - have[1], want[2] - have[2]];
        });
        adjustCurve(c, path.concat(adjust, a), params, r, changed, fixes, shared);
      });
    }
    visit(doc, []);
    return fixes;
  }

  // Moves control point `id` of `doc` (changed in place) to `xyz`, with
  // everything linked to it, and corrects the networks whose nodes the move
  // separated (their corrected points carry their links along too).
  // Returns {locations}: the JSON locations set to xyz, and {changed}:
  // every JSON path written.
  function move(doc, id, xyz) {
    const before = JSON.parse(JSON.stringify(doc));
    const cps = controlPoints(doc);
    const start = cps.points[id];
    if (!start) throw new Error('no control point ' + id);
    const key = (p) => p.join('/');
    const owner = new Map(); // path -> the points that hold it
    cps.points.forEach((p) => p.members.forEach((m) => {
      const k = key(m.path);
      if (!owner.has(k)) owner.set(k, []);
      owner.get(k).push({ point: p, A: m.A });
    }));
    const changed = new Set(), done = new Set();
    function propagate(queue) {
      while (queue.length) {
        const [p, to] = queue.shift();
        if (done.has(p.id)) continue;
        done.add(p.id);
        for (const m of p.members) {
          const k = key(m.path);
          if (changed.has(k)) continue;
          changed.add(k);
          set(doc, m.path, invertApply(m.A, to));
          // other placements of this location move, and what sits there follows
          for (const o of owner.get(k))
            if (!done.has(o.point.id)) queue.push([o.point, apply(o.A, get(doc, m.path))]);
        }
      }
    }
    propagate([[start, xyz]]);
    const shared = new Set();
    cps.points.forEach((p) => { if (p.members.length > 1) p.members.forEach((m) => shared.add(key(m.path))); });
    for (let round = 0; round < 4; round++) {
      const fixes = repairNetworks(before, doc, changed, shared);
      if (!fixes.length) break;
      const queue = [];
      for (const path of fixes) {
        const k = key(path);
        changed.add(k);
        for (const o of owner.get(k) || [])
          if (!done.has(o.point.id)) queue.push([o.point, apply(o.A, get(doc, path))]);
      }
      propagate(queue);
    }
    return { locations: start.members, changed: [...changed] };
  }

  const api = { controlPoints, move, diagonal, worldAt, leaves, curveBasis };
  if (typeof module !== 'undefined' && module.exports) module.exports = api;
  else root.CoonsLinks = api;
})(typeof self !== 'undefined' ? self : this);
