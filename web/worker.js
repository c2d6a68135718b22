// SPDX-License-Identifier: GPL-3.0-or-later
// The page's Web Worker: meshes a model at its full tolerance off the main
// thread (app.js posts {seq, text, name, time, tol}; the reply carries the
// same seq and the mesh's arrays, or the error).
/* global importScripts, createCoons, CoonsApi */
importScripts('coons.js', 'coons-api.js');
const ready = createCoons().then((M) => CoonsApi.wrap(M));
onmessage = async (ev) => {
  const api = await ready;
  const { seq, text, name, time, tol } = ev.data;
  let m = null;
  try {
    m = api.load(text, name);
    if (time !== null && m.morphs()) m.setTime(time);
    const t0 = performance.now();
    const r = api.mesh(m, tol);
    postMessage({ seq, positions: r.positions, indices: r.indices, united: r.united, note: r.note, ms: performance.now() - t0 },
                [r.positions.buffer, r.indices.buffer]);
  } catch (e) {
    postMessage({ seq, error: e.message });
  } finally {
    if (m) m.free();
  }
};
