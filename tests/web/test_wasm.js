// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 29: every example through the WebAssembly build (build-web/coons.js)
// against the native C-only coons2stl, which writes each output to a file
// (binary STL, OFF, SCAD, VTU, MSH, INP, default options): the bytes must be
// equal, and what coons2stl refuses (the unions, which need CGAL) the module
// refuses with the same message. Also the page's control-point links
// (web/links.js): moving a point of every example moves all JSON locations
// linked to it and the moved model still loads.
//   node tests/web/test_wasm.js BUILD_WEB COONS2STL EXAMPLES_DIR OUT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const { execFile } = require('child_process');

const [buildWeb, coons2stl, examplesDir, outDir] = process.argv.slice(2);
if (!outDir) {
  console.error('usage: test_wasm.js BUILD_WEB COONS2STL EXAMPLES_DIR OUT_DIR');
  process.exit(2);
}
const FORMATS = ['stl', 'off', 'scad', 'vtu', 'msh', 'inp'];
const KNOWN_REFUSED = new Set(['curve-coons-cubic-closed.json']);
let passed = 0, failed = 0;
function check(ok, what) {
  if (ok) passed++;
  else { failed++; console.log('FAIL ' + what); }
}

function runNative(input, output) {
  return new Promise((resolve) => {
    execFile(coons2stl, ['-q', '-o', output, input], { maxBuffer: 1 << 24 },
      (err, stdout, stderr) => resolve({ code: err ? err.code : 0, stderr }));
  });
}

async function pool(tasks, n) {
  const results = new Array(tasks.length);
  let next = 0;
  async function worker() {
    while (next < tasks.length) { const i = next++; results[i] = await tasks[i](); }
  }
  await Promise.all(Array.from({ length: n }, worker));
  return results;
}

async function main() {
  const createCoons = require(path.resolve(buildWeb, 'coons.js'));
  const M = await createCoons({ wasmBinary: fs.readFileSync(path.join(buildWeb, 'coons.wasm')) });
  const api = require(path.resolve(buildWeb, 'coons-api.js')).wrap(M);
  const links = require(path.resolve(buildWeb, 'links.js'));
  const names = fs.readdirSync(examplesDir).filter((f) => f.endsWith('.json')).sort();
  const nat = path.join(outDir, 'native');
  fs.mkdirSync(nat, { recursive: true });

  let t = Date.now();
  const jobs = [];
  for (const f of names)
    for (const fmt of FORMATS) {
      const base = f.replace(/\.json$/, '');
      jobs.push(() => runNative(path.join(examplesDir, f), path.join(nat, base + '.' + fmt))
        .then((r) => ({ f, fmt, base, ...r })));
    }
  const native = await pool(jobs, Number(process.env.COONS_JOBS || 2));
  const tNative = (Date.now() - t) / 1000;

  t = Date.now();
  let same = 0, refused = 0;
  for (const r of native) {
    const text = fs.readFileSync(path.join(examplesDir, r.f), 'utf8');
    const model = api.load(text, r.f);
    let bytes = null, error = null;
    try { bytes = api.write(model, r.fmt, r.base); } catch (e) { error = e; }
    model.free();
    const what = `${r.f} -> ${r.fmt}`;
    if (r.code === 0) {
      const want = fs.readFileSync(path.join(nat, r.base + '.' + r.fmt));
      const ok = bytes !== null && Buffer.compare(Buffer.from(bytes), want) === 0;
      check(ok, `${what}: ${error ? 'refused: ' + error.message
                                 : `differs (${bytes.length} vs ${want.length} bytes)`}`);
      if (ok) same++;
    } else {
      // refused alike: the module's message is the one coons2stl printed
      const ok = error !== null && r.stderr.includes(error.message);
      check(ok, `${what}: coons2stl refused (${r.stderr.trim()}), the module ` +
                (error ? `said '${error.message}'` : 'wrote it'));
      if (ok) refused++;
    }
  }
  const tWasm = (Date.now() - t) / 1000;

  // A broken model: the loader's error carries the file, line, column and path.
  try {
    api.load('{"coons": 1,\n "bodies": [{"type": "body0", "corners": [[0,0,0]]}]}', 'bad.json');
    check(false, 'a body0 with one corner loaded');
  } catch (e) {
    check(e.path === '/bodies/0/corners' && e.line === 2 && e.column > 1 &&
          e.message.startsWith('bad.json:2:'), `load error: ${e.message} (${e.path})`);
  }

  // Control-point links: for every example, move one point of each link
  // group (the first few groups) and check that every linked location
  // moved with it, and that the moved model still loads.
  let moved = 0, reloaded = 0;
  for (const f of names) {
    const doc = JSON.parse(fs.readFileSync(path.join(examplesDir, f), 'utf8'));
    const cps = links.controlPoints(doc);
    check(cps.points.length > 0, `${f}: no control points`);
    const diag = links.diagonal(cps);
    // three points; every point of a model with references (a definition
    // placed twice moves at both places, and what sits there follows)
    const picks = doc.define ? cps.points.map((p) => p.id)
                             : [0, Math.floor(cps.points.length / 2), cps.points.length - 1];
    for (const k of picks) {
      const p = cps.points[k];
      const target = [p.xyz[0] + 0.01 * diag, p.xyz[1] - 0.005 * diag, p.xyz[2] + 0.003 * diag];
      const doc2 = JSON.parse(JSON.stringify(doc));
      const res = links.move(doc2, p.id, target);
      const after = links.controlPoints(doc2);
      const q = after.points.find((x) => x.id === p.id);
      const d = Math.hypot(q.xyz[0] - target[0], q.xyz[1] - target[1], q.xyz[2] - target[2]);
      check(d <= 1e-9 * diag, `${f}: point ${p.id} is ${d} from where it was moved`);
      // every location of the group holds the same world point
      for (const loc of res.locations) {
        const w = links.worldAt(doc2, loc);
        const e = Math.hypot(w[0] - target[0], w[1] - target[1], w[2] - target[2]);
        check(e <= 1e-9 * diag, `${f}: linked location ${loc.path.join('/')} is ${e} away`);
      }
      moved++;
      try {
        api.load(JSON.stringify(doc2), f).free();
        reloaded++;
      } catch (e) {
        // Every moved model loads, but where a body 1's closed Coons-cubic
        // edge (whose ends are one point, not a control point) must follow
        // two corners at once (a limitation of links.js): there the move
        // is refused with a path, never crashes.
        const known = KNOWN_REFUSED.has(f);
        check(known && typeof e.path === 'string' && e.line > 0,
              `${f}: moving ${p.id} gives a model that does not load: ${e.message}`);
        if (known) console.log(`note ${f}: moving ${p.id} is refused: ${e.message}`);
      }
    }
  }
  // The interior: a body0 parallelepiped with edges a, b, c has det J =
  // a . (b x c) everywhere, and its surface u = 1/4 lies in the plane
  // through a/4 spanned by b and c.
  {
    const a = [10, 0, 0], b = [3, 20, 0], c = [1, 2, 30];
    const corners = [];
    for (let i = 0; i < 2; i++) for (let j = 0; j < 2; j++) for (let k = 0; k < 2; k++)
      corners.push([0, 1, 2].map((d) => i * a[d] + j * b[d] + k * c[d]));
    const m = api.load(JSON.stringify({ coons: 1, bodies: [{ type: 'body0', corners }] }), 'p.json');
    const r = api.iso(m, 0, [0.25], 0);
    m.free();
    const n = [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]];
    const det = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    check(r.detj.length > 0 && r.detj.every((d) => Math.abs(d - det) <= 1e-12 * det),
          `det J of the parallelepiped is not ${det}: ${r.detj.slice(0, 3)}`);
    check(r.parts.length === 2 && r.parts[0].boundary && !r.parts[1].boundary, 'iso parts: boundary, u=0.25');
    const want = 0.25 * (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]);
    let worst = 0;
    for (let t = r.parts[1].first; t < r.parts[1].first + r.parts[1].count; t++)
      for (let e = 0; e < 3; e++) {
        const v = r.indices[3 * t + e], x = r.positions.subarray(3 * v, 3 * v + 3);
        worst = Math.max(worst, Math.abs(n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - want) / Math.hypot(...n));
      }
    check(r.parts[1].count > 0 && worst < 1e-5, `the surface u = 1/4 is ${worst} off its plane`); // float32 positions
  }
  // det J varying through the body: F(u, v, w) = (u (10 + 10 v), 20 v, 30 w)
  // (a body0 with those corners) has det J = 600 (10 + 10 v), v = y / 20.
  {
    const corners = [];
    for (let i = 0; i < 2; i++) for (let j = 0; j < 2; j++) for (let k = 0; k < 2; k++)
      corners.push([i * (10 + 10 * j), 20 * j, 30 * k]);
    const m = api.load(JSON.stringify({ coons: 1, bodies: [{ type: 'body0', corners }] }), 't.json');
    const r = api.iso(m, 2, [0.5], 0);
    m.free();
    let worst = 0;
    r.detj.forEach((d, v) => {
      const want = 600 * (10 + 10 * r.positions[3 * v + 1] / 20);
      worst = Math.max(worst, Math.abs(d - want) / want);
    });
    check(r.detj.length > 0 && worst < 1e-6, `det J of the tapered body is ${worst} off 600 (10 + 10 v)`);
  }
  // The cells of a lattice (api.cells: every body's 12 boundary edges at
  // n + 1 points of coons_body_eval()). lattice-ffd.json's bodies are body0
  // (trilinear): each edge is the straight segment between two of the
  // body's JSON corners (corner 4i + 2j + k at (u, v, w) = (i, j, k)), its
  // point s at s / n of the way. Every lattice example: 12 (n + 1) points
  // per body, and the edges' ends meet in each body's 8 corners.
  {
    const n = 16;
    const doc = JSON.parse(fs.readFileSync(path.join(examplesDir, 'lattice-ffd.json'), 'utf8'));
    const m = api.load(JSON.stringify(doc), 'lattice-ffd.json');
    const r = api.cells(m, n);
    m.free();
    check(doc.bodies.every((b) => b.type === 'body0') && r.positions.length === 3 * doc.bodies.length * 12 * (n + 1),
          `lattice-ffd cells: ${r.positions.length / 3} points for ${doc.bodies.length} bodies`);
    let worst = 0;
    doc.bodies.forEach((b, bi) => {
      for (let e = 0; e < 12; e++) {
        const dir = Math.floor(e / 4), a = e & 1, c = (e >> 1) & 1;
        const corner = (t) => {
          const q = [0, 0, 0];
          q[dir] = t;
          q[dir === 0 ? 1 : 0] = a;
          q[dir === 2 ? 1 : 2] = c;
          return b.corners[4 * q[0] + 2 * q[1] + q[2]];
        };
        const A = corner(0), B = corner(1);
        for (let s = 0; s <= n; s++) {
          const t = s / n, o = 3 * ((12 * bi + e) * (n + 1) + s);
          for (let d = 0; d < 3; d++)
            worst = Math.max(worst, Math.abs(r.positions[o + d] - ((1 - t) * A[d] + t * B[d])));
        }
      }
    });
    check(worst <= 1e-12 * 40, `lattice-ffd cells are ${worst} off the segments between the JSON corners`);
    for (const f of ['chair-lattice.json', 'lattice-ffd.json', 'lattice-l-bracket.json', 'lattice-ring.json',
                     'lattice-instanced.json']) {
      const mm = api.load(fs.readFileSync(path.join(examplesDir, f), 'utf8'), f);
      const nb = mm.bodies(), x = api.cells(mm, n).positions;
      mm.free();
      check(x.length === 3 * nb * 12 * (n + 1), `${f}: ${x.length / 3} cell points for ${nb} bodies`);
      let gap = 0, span = 0;
      for (let bi = 0; bi < nb; bi++) {
        // corner (i, j, k) as the end of its edges along u, v, w
        const end = (e, t) => x.subarray(3 * ((12 * bi + e) * (n + 1) + t * n), 3 * ((12 * bi + e) * (n + 1) + t * n) + 3);
        for (let i = 0; i < 2; i++) for (let j = 0; j < 2; j++) for (let k = 0; k < 2; k++) {
          const pu = end(0 + j + 2 * k, i), pv = end(4 + i + 2 * k, j), pw = end(8 + i + 2 * j, k);
          for (let d = 0; d < 3; d++) {
            gap = Math.max(gap, Math.abs(pu[d] - pv[d]), Math.abs(pu[d] - pw[d]));
            span = Math.max(span, Math.abs(pu[d]));
          }
        }
      }
      check(gap <= 1e-12 * span, `${f}: the cells' edges meet ${gap} apart at the corners`);
    }
  }
  // A definition placed twice, the second place shared with a third body:
  // moving the first place's corner moves the definition, so the second
  // place moves too, and the third body's corner there must follow it.
  {
    const cube = (x) => [[x, 0, 0], [x, 0, 10], [x, 10, 0], [x, 10, 10],
                         [x + 10, 0, 0], [x + 10, 0, 10], [x + 10, 10, 0], [x + 10, 10, 10]];
    const doc = { coons: 1, define: { c: { type: 'body0', corners: cube(0) } },
                  bodies: [{ ref: 'c', name: 'a' },
                           { ref: 'c', name: 'b', transform: [[1, 0, 0, 20], [0, 1, 0, 0], [0, 0, 1, 0]] },
                           { type: 'body0', name: 'c3', corners: cube(30) }] };
    const cps = links.controlPoints(doc);
    const at = (x) => cps.points.find((p) => p.xyz[0] === x[0] && p.xyz[1] === x[1] && p.xyz[2] === x[2]);
    links.move(doc, at([10, 0, 0]).id, [11, -1, 0.5]);
    check(JSON.stringify(doc.define.c.corners[4]) === '[11,-1,0.5]', 'the definition\'s corner moved');
    check(JSON.stringify(doc.bodies[2].corners[0]) === '[31,-1,0.5]',
          `the third body follows the second place: ${JSON.stringify(doc.bodies[2].corners[0])}`);
  }
  console.log(`wasm vs native: ${same} outputs equal, ${refused} refused alike, over ` +
              `${names.length} examples x ${FORMATS.length} formats; native ${tNative.toFixed(1)} s, ` +
              `wasm ${tWasm.toFixed(1)} s; control points: ${moved} moves, ${reloaded} reload`);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}
main().catch((e) => { console.error(e); process.exit(1); });
