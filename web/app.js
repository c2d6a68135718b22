// SPDX-License-Identifier: GPL-3.0-or-later
// The page (issue 29): a model's solid, control points and nets in three.js;
// dragging a control point moves every point linked to it (links.js) in the
// model JSON, which stays the source of truth, and remeshes at a coarse
// preview tolerance, then at the model's own when the drag ends. The
// WebAssembly module (coons.js, coons-api.js) loads, meshes and exports
// exactly what coons2stl writes. window.coons is the tests' contract.
import * as THREE from 'three';
import { OrbitControls } from './three/OrbitControls.js';

const $ = (id) => document.getElementById(id);
// The preview during a drag (issue 29: a drag remeshes within 50 ms), chosen
// per model when it is loaded, by timing it (previewPlan()): the adaptive
// sampler at a coarse tolerance, PREVIEW_MIN model tolerances or more (x2
// while the full-tolerance mesh's time predicts more than PREVIEW_MS); when
// that takes more than PREVIEW_MS / 2, a fixed lattice of 2, 4 or 8
// intervals per direction, unmeasured, is timed too, and taken when the
// adaptive preview is over PREVIEW_MS and the lattice twice as fast. The
// adaptive sampler measures its deviation, which costs 10-90 ms even at 256
// tolerances for the morphs (every evaluation evaluates their keys) and for
// the lattices of many bodies. A preview that still takes longer than
// PREVIEW_MS makes the next ones coarser: the lattice when it was timed at
// less than half that preview's time, else tolerance x2 (up to 256) or
// lattice /2 (down to 2). The model's own tolerance (in the worker) when a
// drag ends.
// PREVIEW_MS: a third of the 50 ms, as a preview's time varies by 2-3 times
// from one pointer move to the next on a busy machine.
const PREVIEW_MS = 15, PREVIEW_MIN = 8, PREVIEW_MAX = 256;
const PICK_PX = 12;
// the samples per edge of the cells (coons_body_eval() at 33 points)
const CELL_SAMPLES = 32;

const state = {
  text: '', doc: null, name: 'model', model: null, cps: null, tol: 0, diag: 1,
  undo: [], redo: [], selected: -1, time: null, stats: { remesh: [] }, meshSeq: 0, note: '',
  preview: { factor: PREVIEW_MIN, resolution: 0 },
};
let api = null;

// ---------- three.js ----------
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
camera.add(sun);
sun.position.set(0.5, 1, 1);
scene.add(camera);
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', requestRender);

const solidMat = new THREE.MeshStandardMaterial({
  color: 0x8fb3d9, flatShading: true, side: THREE.DoubleSide, roughness: 0.6, metalness: 0.05,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
const solid = new THREE.Mesh(new THREE.BufferGeometry(), solidMat);
const wire = new THREE.LineSegments(new THREE.BufferGeometry(),
  new THREE.LineBasicMaterial({ color: 0x34495e, transparent: true, opacity: 0.35 }));
const nets = new THREE.LineSegments(new THREE.BufferGeometry(),
  new THREE.LineBasicMaterial({ color: 0x555555 }));
const points = new THREE.Points(new THREE.BufferGeometry(),
  new THREE.PointsMaterial({ color: 0xd03020, size: 7, sizeAttenuation: false }));
const chosen = new THREE.Points(new THREE.BufferGeometry(),
  new THREE.PointsMaterial({ color: 0xffa000, size: 12, sizeAttenuation: false, depthTest: false }));
chosen.renderOrder = 2;
points.renderOrder = 1;
// the interior: isoparametric surfaces and each body's boundary (see-through),
// coloured by det J on request
const boundaryMat = new THREE.MeshStandardMaterial({ color: 0x8fb3d9, transparent: true, opacity: 0.18,
  depthWrite: false, side: THREE.DoubleSide, flatShading: true });
const isoMat = new THREE.MeshStandardMaterial({ color: 0xe0a040, side: THREE.DoubleSide, flatShading: true });
const isoColourMat = new THREE.MeshStandardMaterial({ vertexColors: true, side: THREE.DoubleSide, flatShading: true });
const interior = new THREE.Mesh(new THREE.BufferGeometry(), [boundaryMat, isoMat]);
interior.visible = false;
// the cells: every body's 12 boundary edges, seen through the solid
const cellLines = new THREE.LineSegments(new THREE.BufferGeometry(),
  new THREE.LineBasicMaterial({ color: 0x0a7d3b, depthTest: false, transparent: true, opacity: 0.85 }));
cellLines.renderOrder = 1;
cellLines.visible = false;
scene.add(solid, wire, nets, points, chosen, interior, cellLines);

let renderPending = false;
function requestRender() {
  if (renderPending) return;
  renderPending = true;
  requestAnimationFrame(() => { renderPending = false; renderer.render(scene, camera); });
}
function resize() {
  const r = $('stage').getBoundingClientRect();
  renderer.setSize(Math.max(1, r.width), Math.max(1, r.height), false);
  camera.aspect = Math.max(1, r.width) / Math.max(1, r.height);
  camera.updateProjectionMatrix();
  requestRender();
}
new ResizeObserver(resize).observe($('stage'));

function fitCamera() {
  const { lo, hi } = state.cps;
  const c = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  const d = state.diag || 1;
  const dist = 0.62 * d / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2));
  camera.position.copy(c).add(new THREE.Vector3(0.9, -1.5, 0.9).normalize().multiplyScalar(dist));
  camera.near = dist / 100;
  camera.far = dist * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(c);
  controls.update();
}

// ---------- the model ----------
// JSON text with number arrays on one line (a point per line, readable)
function format(v, ind = '') {
  if (Array.isArray(v)) {
    if (v.every((x) => typeof x !== 'object' || x === null)) return '[' + v.map((x) => JSON.stringify(x)).join(', ') + ']';
    const inner = ind + '  ';
    return '[\n' + v.map((x) => inner + format(x, inner)).join(',\n') + '\n' + ind + ']';
  }
  if (v && typeof v === 'object') {
    const inner = ind + '  ';
    const keys = Object.keys(v);
    if (!keys.length) return '{}';
    return '{\n' + keys.map((k) => inner + JSON.stringify(k) + ': ' + format(v[k], inner)).join(',\n') + '\n' + ind + '}';
  }
  return JSON.stringify(v);
}

function showError(e) {
  const box = $('error');
  if (!e) { box.hidden = true; box.textContent = ''; return; }
  box.hidden = false;
  box.textContent = (e.path !== undefined && e.path !== '' ? 'at ' + e.path + '\n' : '') + e.message;
}
function status(s) { $('status').textContent = s; }

function setMesh(tol, resolution = 0) {
  const t0 = performance.now();
  const m = api.mesh(state.model, tol, resolution);
  const ms = performance.now() - t0;
  state.meshSeq++;
  showMesh(m);
  return ms;
}

// The full tolerance after a drag: in a Web Worker (worker.js) when there
// is one, so that the page stays responsive; the result replaces the
// preview unless the model changed meanwhile.
let worker = null;
try {
  worker = new Worker('worker.js');
  worker.onmessage = (ev) => {
    const r = ev.data;
    if (r.seq === state.workerSeq && state.idle) { state.idle(); state.idle = null; }
    if (r.seq !== state.meshSeq) return; // a newer mesh is shown already
    if (r.error) { showError({ message: r.error }); return; }
    showMesh(r);
    state.stats.lastFull = r.ms;
    status(`${state.name}: ${state.triangles} triangles (tolerance ${state.tol.toPrecision(3)}), ` +
           `${r.ms.toFixed(0)} ms in the worker` + state.note);
  };
} catch (_) { worker = null; }
function fullMesh() {
  if (!worker) {
    state.stats.lastFull = setMesh(state.tol);
    return;
  }
  const seq = ++state.meshSeq;
  state.workerSeq = seq;
  if (!state.busy) state.busy = new Promise((res) => { state.idle = () => { state.busy = null; res(); }; });
  worker.postMessage({ seq, text: state.text, name: state.name + '.json', time: state.time, tol: state.tol });
}

function showMesh(m) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(m.positions, 3));
  g.setIndex(new THREE.BufferAttribute(m.indices, 1));
  solid.geometry.dispose();
  solid.geometry = g;
  updateWire();
  state.triangles = m.indices.length / 3;
  state.note = m.united ? '' : ` (shown unmerged: ${m.note})`;
  requestRender();
}

// the triangles' edges, made only while shown
function updateWire() {
  wire.geometry.dispose();
  wire.geometry = wire.visible ? new THREE.WireframeGeometry(solid.geometry) : new THREE.BufferGeometry();
}

// The cells of a lattice: each body's 12 boundary edges (u, v, w at the
// corners of the unit cube), CELL_SAMPLES segments each, evaluated by the
// module (cw_cells: coons_body_eval), made only while shown.
function updateCells() {
  cellLines.visible = $('show-cells').checked;
  if (!cellLines.visible || !state.model) { requestRender(); return; }
  const n = CELL_SAMPLES;
  let r;
  try { r = api.cells(state.model, n); } catch (e) { showError(e); return; }
  const x = r.positions, np = x.length / 3, seg = new Float32Array(6 * (np / (n + 1)) * n);
  let o = 0;
  for (let e = 0; e < np; e += n + 1)
    for (let s = 0; s < n; s++) {
      for (let d = 0; d < 6; d++) seg[o++] = x[3 * (e + s) + d];
    }
  cellLines.geometry.dispose();
  cellLines.geometry = new THREE.BufferGeometry();
  cellLines.geometry.setAttribute('position', new THREE.BufferAttribute(seg, 3));
  requestRender();
}

// Isoparametric surfaces (seed 000, Fig. 2-6) and det J as colour, from the
// module (cw_iso): shown instead of the solid while asked for.
function updateInterior(tol) {
  const dir = $('iso-dir').value, detj = $('detj').checked;
  $('detj-legend').hidden = !detj;
  interior.visible = !!(dir || detj);
  solid.visible = $('show-solid').checked && !interior.visible;
  if (!interior.visible || !state.model) { requestRender(); return; }
  const n = dir ? Number($('iso-n').value) : 0;
  const values = Array.from({ length: n }, (_, k) => (k + 1) / (n + 1));
  let r;
  try { r = api.iso(state.model, dir ? Number(dir) : 0, values, tol); } catch (e) { showError(e); return; }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(r.positions, 3));
  g.setIndex(new THREE.BufferAttribute(r.indices, 1));
  for (const p of r.parts) g.addGroup(3 * p.first, 3 * p.count, p.boundary && dir ? 0 : 1);
  if (detj) {
    let lo = Infinity, hi = -Infinity;
    for (const d of r.detj) { lo = Math.min(lo, d); hi = Math.max(hi, d); }
    const col = new Float32Array(3 * r.detj.length), c = new THREE.Color();
    const top = Math.max(Math.abs(hi), 1e-300);
    r.detj.forEach((d, i) => {
      if (d <= 0) c.setRGB(0.35, 0, 0.35); // folded: det J <= 0
      else c.setHSL(0.66 * (1 - d / top), 0.9, 0.5);
      col.set([c.r, c.g, c.b], 3 * i);
    });
    g.setAttribute('color', new THREE.BufferAttribute(col, 3));
    $('detj-range').textContent = `${lo.toPrecision(3)} .. ${hi.toPrecision(3)}`;
  }
  interior.material = [boundaryMat, detj ? isoColourMat : isoMat];
  interior.geometry.dispose();
  interior.geometry = g;
  requestRender();
}

// the nets: consecutive points of each curve, surface and volume net, the
// edges of bilinear and body0 corners
function buildNets() {
  const L = CoonsLinks.leaves(state.doc);
  const groups = new Map();
  for (const l of L) {
    let k = l.path.lastIndexOf('points');
    if (k < 0) k = l.path.lastIndexOf('corners');
    const key = l.path.slice(0, k + 1).join('/');
    if (!groups.has(l.A)) groups.set(l.A, new Map());
    const g = groups.get(l.A);
    if (!g.has(key)) g.set(key, { corners: l.path[k] === 'corners', pts: new Map() });
    g.get(key).pts.set(l.path.slice(k + 1).join(','), l.world);
  }
  const seg = [];
  const push = (a, b) => { if (a && b) seg.push(...a, ...b); };
  for (const g of groups.values()) for (const net of g.values()) {
    const P = net.pts;
    if (net.corners) {
      const c = (i) => P.get(String(i));
      const pairs = P.size === 8 ? [[0, 4], [2, 6], [1, 5], [3, 7], [0, 2], [4, 6], [1, 3], [5, 7], [0, 1], [2, 3], [4, 5], [6, 7]]
                                 : [[0, 1], [0, 2], [1, 3], [2, 3]];
      for (const [a, b] of pairs) push(c(a), c(b));
      continue;
    }
    for (const [k, x] of P) {
      const idx = k.split(',').map(Number);
      for (let d = 0; d < idx.length; d++) {
        const n = idx.slice();
        n[d]++;
        push(x, P.get(n.join(',')));
      }
    }
  }
  nets.geometry.dispose();
  nets.geometry = new THREE.BufferGeometry();
  nets.geometry.setAttribute('position', new THREE.Float32BufferAttribute(seg, 3));
}

function updatePoints() {
  state.cps = CoonsLinks.controlPoints(state.doc);
  state.diag = CoonsLinks.diagonal(state.cps) || 1;
  const xyz = state.cps.points.flatMap((p) => p.xyz);
  points.geometry.dispose();
  points.geometry = new THREE.BufferGeometry();
  points.geometry.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
  buildNets();
  updateSelected();
}

function updateSelected() {
  const p = state.cps && state.cps.points[state.selected];
  chosen.geometry.dispose();
  chosen.geometry = new THREE.BufferGeometry();
  chosen.geometry.setAttribute('position', new THREE.Float32BufferAttribute(p ? p.xyz : [], 3));
  $('selected').hidden = !p;
  if (p) {
    $('sel-id').textContent = p.id + ' (body ' + p.body + ', ' + p.members.length + ' location' + (p.members.length > 1 ? 's' : '') + ')';
    ['x', 'y', 'z'].forEach((a, i) => { if (document.activeElement !== $('sel-' + a)) $('sel-' + a).value = p.xyz[i]; });
  }
  requestRender();
}

// Makes `text` the model (it loads, else throws the loader's error and
// nothing changes); tol: the mesh tolerance, 0 for the model's.
function commit(text, doc, { tol = 0, resolution = 0, fit = false, keepText = false } = {}) {
  const model = api.load(text, state.name + '.json');
  if (state.model) state.model.free();
  state.model = model;
  state.text = text;
  state.doc = doc;
  state.tol = model.tolerance();
  const morphs = model.morphs();
  $('morph-row').hidden = !morphs;
  if (morphs && state.time !== null) model.setTime(state.time);
  if (!keepText) $('json').value = text;
  updatePoints();
  if (fit) fitCamera();
  const ms = setMesh(tol > 0 ? tol : state.tol, resolution);
  updateInterior(tol > 0 ? tol : state.tol);
  updateCells();
  showError(null);
  const how = resolution ? `preview lattice ${resolution}` : `${tol > 0 ? 'preview ' : ''}tolerance ${(tol > 0 ? tol : state.tol).toPrecision(3)}`;
  status(`${state.name}: ${model.bodies()} bod${model.bodies() === 1 ? 'y' : 'ies'}, ` +
         `${state.cps.points.length} control points, ${state.triangles} triangles (${how}), ${ms.toFixed(0)} ms` +
         state.note);
  return ms;
}

// The preview of the model just loaded, whose full-tolerance mesh took
// fullMs (see PREVIEW_MS), timed: {factor (model tolerances), resolution
// (> 0: the lattice's, now; 0: adaptive), lattice (the lattice timed, 0:
// none), ta and tr (the times of both at load)}.
function previewPlan(fullMs) {
  let factor = PREVIEW_MIN;
  while (factor < PREVIEW_MAX && fullMs / factor > PREVIEW_MS) factor *= 2;
  const time = (tol, resolution) => {
    const t0 = performance.now();
    api.mesh(state.model, tol, resolution);
    return performance.now() - t0;
  };
  const plan = { factor, resolution: 0, lattice: 0, ta: 0, tr: Infinity };
  try {
    plan.ta = time(factor * state.tol, 0);
    if (plan.ta <= PREVIEW_MS / 2) return plan;
    // the lattice: 4 intervals, 8 when that is cheap, 2 when 4 is slow
    let r = 4, tr = time(state.tol, r);
    if (tr <= PREVIEW_MS / 3) {
      const t8 = time(state.tol, 8);
      if (t8 <= PREVIEW_MS) { r = 8; tr = t8; }
    } else if (tr > PREVIEW_MS) {
      r = 2;
      tr = time(state.tol, r);
    }
    plan.lattice = r;
    plan.tr = tr;
    // the adaptive sampler (the better shape) unless it is slow and the
    // lattice twice as fast
    if (plan.ta > PREVIEW_MS && 2 * tr <= plan.ta) plan.resolution = r;
  } catch (_) { /* the adaptive plan */ }
  return plan;
}
// after a preview of ms: coarser when it took longer than PREVIEW_MS
// (to the lattice when it was timed faster than this preview)
function previewAdapt(ms) {
  const p = state.preview;
  if (ms <= PREVIEW_MS) return;
  if (p.resolution) p.resolution = Math.max(2, p.resolution >> 1);
  else if (p.lattice && p.tr < ms / 2) p.resolution = p.lattice;
  else p.factor = Math.min(PREVIEW_MAX, 2 * p.factor);
}

function pushUndo(text) {
  if (text && text !== state.text) { state.undo.push(text); state.redo.length = 0; }
}

function loadText(text, name) {
  if (name) state.name = name.replace(/^.*\//, '').replace(/\.json$/i, '') || 'model';
  $('name').textContent = state.name + '.json';
  let doc;
  try { doc = JSON.parse(text); } catch (_) { doc = null; }
  try {
    const before = state.text;
    state.time = null;
    $('time').value = 0;
    const ms = commit(text, doc, { fit: true });
    state.preview = previewPlan(ms);
    pushUndo(before);
    state.selected = -1;
    updateSelected();
  } catch (e) {
    $('json').value = text;
    showError(e);
    selectInText(e);
    throw e;
  }
}

function selectInText(e) {
  if (!e.line) return;
  const lines = $('json').value.split(/\r\n|\r|\n/);
  let off = 0;
  for (let i = 0; i < e.line - 1 && i < lines.length; i++) off += lines[i].length + 1;
  off += Math.max(0, e.column - 1);
  $('json').setSelectionRange(off, off + 1);
}

// Moves control point id to xyz with its links; tol: preview tolerance or 0.
// Returns the remesh time; throws (and changes nothing) when the moved model
// does not load.
// resolution: > 0 for a preview on a fixed lattice (tol then is the model's).
function moveTo(id, xyz, tol, resolution = 0) {
  const doc = structuredClone(state.doc);
  CoonsLinks.move(doc, id, xyz);
  const ms = commit(format(doc), doc, { tol, resolution });
  return ms;
}

// ---------- picking and dragging ----------
function toScreen(xyz) {
  const r = canvas.getBoundingClientRect();
  const v = new THREE.Vector3(...xyz).project(camera);
  return { x: r.left + (v.x + 1) / 2 * r.width, y: r.top + (1 - v.y) / 2 * r.height, z: v.z };
}
function pick(ev) {
  let best = -1, bd = PICK_PX;
  for (const p of state.cps ? state.cps.points : []) {
    const s = toScreen(p.xyz);
    if (s.z > 1) continue;
    const d = Math.hypot(s.x - ev.clientX, s.y - ev.clientY);
    if (d < bd) { bd = d; best = p.id; }
  }
  return best;
}
function rayAt(ev) {
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2((ev.clientX - r.left) / r.width * 2 - 1, -(ev.clientY - r.top) / r.height * 2 + 1);
  const rc = new THREE.Raycaster();
  rc.setFromCamera(ndc, camera);
  return rc.ray;
}
// where the pointer puts the dragged point under the constraint
function dragTarget(ev, start) {
  const ray = rayAt(ev), s = new THREE.Vector3(...start), c = $('constraint').value;
  const axes = { x: new THREE.Vector3(1, 0, 0), y: new THREE.Vector3(0, 1, 0), z: new THREE.Vector3(0, 0, 1) };
  if (c.length === 1) { // along an axis: the point of the axis line nearest the ray
    const a = axes[c], out = new THREE.Vector3();
    ray.distanceSqToSegment(s.clone().addScaledVector(a, -1e3 * state.diag), s.clone().addScaledVector(a, 1e3 * state.diag), null, out);
    return out.toArray();
  }
  let n;
  if (c === 'free') n = camera.getWorldDirection(new THREE.Vector3());
  else n = axes[{ xy: 'z', yz: 'x', xz: 'y' }[c]];
  const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(n, s);
  const hit = ray.intersectPlane(plane, new THREE.Vector3());
  return hit ? hit.toArray() : start;
}

let drag = null;
canvas.addEventListener('pointerdown', (ev) => {
  if (ev.button !== 0 || !state.cps) return;
  const id = pick(ev);
  if (id < 0) return;
  ev.preventDefault();
  ev.stopImmediatePropagation();
  controls.enabled = false;
  canvas.setPointerCapture(ev.pointerId);
  state.selected = id;
  updateSelected();
  drag = { id, start: state.cps.points[id].xyz.slice(), text: state.text, pending: null, busy: false, moved: false };
}, { capture: true });
canvas.addEventListener('pointermove', (ev) => {
  if (!drag) return;
  drag.pending = dragTarget(ev, drag.start);
  if (!drag.busy) {
    drag.busy = true;
    requestAnimationFrame(stepDrag);
  }
});
function stepDrag() {
  if (!drag) return;
  drag.busy = false;
  const to = drag.pending;
  if (!to) return;
  drag.pending = null;
  try {
    const p = state.preview;
    const ms = moveTo(drag.id, to, p.resolution ? state.tol : p.factor * state.tol, p.resolution);
    state.stats.remesh.push(ms);
    previewAdapt(ms);
    drag.moved = true;
    drag.id = nearest(to);
    state.selected = drag.id;
    updateSelected();
  } catch (e) {
    showError(e); // the point stays where the model was last valid
  }
}
function nearest(xyz) {
  let best = 0, bd = Infinity;
  state.cps.points.forEach((p) => {
    const d = Math.hypot(p.xyz[0] - xyz[0], p.xyz[1] - xyz[1], p.xyz[2] - xyz[2]);
    if (d < bd) { bd = d; best = p.id; }
  });
  return best;
}
function endDrag(ev) {
  if (!drag) return;
  if (drag.pending) stepDrag();
  const d = drag;
  drag = null;
  controls.enabled = true;
  try { canvas.releasePointerCapture(ev.pointerId); } catch (_) { /* released */ }
  if (d.moved) {
    pushUndo(d.text);
    fullMesh();
    if (interior.visible) updateInterior(state.tol);
  }
}
canvas.addEventListener('pointerup', endDrag);
canvas.addEventListener('pointercancel', endDrag);

// ---------- the panel ----------
function restore(text) {
  const doc = JSON.parse(text);
  commit(text, doc);
  state.selected = -1;
  updateSelected();
}
$('undo').onclick = () => { if (state.undo.length) { state.redo.push(state.text); restore(state.undo.pop()); } };
$('redo').onclick = () => { if (state.redo.length) { state.undo.push(state.text); restore(state.redo.pop()); } };
window.addEventListener('keydown', (ev) => {
  if (ev.target === $('json') || ev.target.tagName === 'INPUT') return;
  if ((ev.ctrlKey || ev.metaKey) && ev.key === 'z') { $('undo').onclick(); ev.preventDefault(); }
  if ((ev.ctrlKey || ev.metaKey) && (ev.key === 'y' || ev.key === 'Z')) { $('redo').onclick(); ev.preventDefault(); }
});
$('sel-apply').onclick = () => {
  const xyz = ['x', 'y', 'z'].map((a) => Number($('sel-' + a).value));
  coons.moveControlPoint(state.selected, xyz).catch(() => {});
};
$('apply-json').onclick = () => { try { loadText($('json').value); } catch (_) { /* shown */ } };
for (const id of ['show-solid', 'show-points', 'show-nets', 'show-wire']) {
  $(id).onchange = () => {
    solid.visible = $('show-solid').checked && !interior.visible;
    points.visible = chosen.visible = $('show-points').checked;
    nets.visible = $('show-nets').checked;
    if (wire.visible !== $('show-wire').checked) {
      wire.visible = $('show-wire').checked;
      updateWire();
    }
    requestRender();
  };
}
$('show-cells').onchange = updateCells;
wire.visible = false;
$('iso-dir').onchange = $('detj').onchange = () => updateInterior(state.tol);
$('iso-n').oninput = () => { $('iso-n-value').textContent = $('iso-n').value; updateInterior(state.tol); };
$('time').oninput = () => {
  state.time = Number($('time').value);
  $('time-value').textContent = state.time.toFixed(2);
  try { state.model.setTime(state.time); setMesh(state.tol); updateInterior(state.tol); updateCells(); } catch (e) { showError(e); }
};
for (const b of document.querySelectorAll('[data-export]')) {
  b.onclick = async () => {
    const f = b.dataset.export;
    try {
      const bytes = await coons.export(f);
      const a = document.createElement('a');
      a.href = URL.createObjectURL(new Blob([bytes]));
      a.download = state.name + '.' + f;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    } catch (e) { showError(e); }
  };
}
$('file').onchange = async () => {
  const f = $('file').files[0];
  if (f) try { loadText(await f.text(), f.name); } catch (_) { /* shown */ }
};
const stage = $('stage');
stage.addEventListener('dragover', (ev) => { ev.preventDefault(); stage.classList.add('drop'); });
stage.addEventListener('dragleave', () => stage.classList.remove('drop'));
stage.addEventListener('drop', async (ev) => {
  ev.preventDefault();
  stage.classList.remove('drop');
  const f = ev.dataTransfer.files[0];
  if (f) try { loadText(await f.text(), f.name); } catch (_) { /* shown */ }
});
$('examples').onchange = async () => {
  const n = $('examples').value;
  if (!n) return;
  const text = await (await fetch('examples/' + n)).text();
  try { loadText(text, n); } catch (_) { /* shown */ }
};

// ---------- the contract (tests) ----------
const ready = createCoons().then(async (M) => {
  api = CoonsApi.wrap(M);
  resize();
  try {
    const list = await (await fetch('examples/index.json')).json();
    for (const n of list) $('examples').add(new Option(n.replace(/\.json$/, ''), n));
    const first = new URLSearchParams(location.search).get('example') || (list.includes('spool.json') ? 'spool.json' : list[0]);
    if (first && !state.text) {
      $('examples').value = first;
      loadText(await (await fetch('examples/' + first)).text(), first);
    }
  } catch (e) { showError(e); }
});

const coons = {
  ready,
  load: async (text, name) => { await ready; loadText(text, name); },
  model: () => state.text,
  controlPoints: () => (state.cps ? state.cps.points.map((p) => ({ id: p.id, body: p.body, xyz: p.xyz.slice() })) : []),
  moveControlPoint: async (id, xyz) => {
    await ready;
    const before = state.text;
    try { moveTo(id, xyz, 0); } catch (e) { showError(e); throw e; }
    pushUndo(before);
    state.selected = nearest(xyz);
    updateSelected();
  },
  export: async (format) => {
    await ready;
    if (format === 'json') return new TextEncoder().encode(state.text);
    const m = api.load(state.text, state.name + '.json'); // its own time: what coons2stl writes
    try { return api.write(m, format, state.name); } finally { m.free(); }
  },
  // for the tests: a control point's place on the screen (client pixels),
  // and the remesh times of the drags so far
  screen: (id) => { const s = toScreen(state.cps.points[id].xyz); return { x: s.x, y: s.y, visible: s.z <= 1 }; },
  stats: () => ({ remesh: state.stats.remesh.slice(), lastFull: state.stats.lastFull, triangles: state.triangles,
                  preview: { ...state.preview }, selected: state.selected }),
  // resolves when the worker has delivered the last full-tolerance mesh
  idle: () => (state.busy || Promise.resolve()).then(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res)))),
  rendered: () => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))),
};
window.coons = coons;
