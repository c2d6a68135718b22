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

  // Moves control point `id` of `doc` (changed in place) to `xyz`, with
  // everything linked to it. Returns {locations}: the JSON locations set to
  // xyz, and {changed}: every JSON path written.
  function move(doc, id, xyz) {
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
    const queue = [[start, xyz]];
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
    return { locations: start.members, changed: [...changed] };
  }

  const api = { controlPoints, move, diagonal, worldAt, leaves };
  if (typeof module !== 'undefined' && module.exports) module.exports = api;
  else root.CoonsLinks = api;
})(typeof self !== 'undefined' ? self : this);
