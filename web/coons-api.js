// SPDX-License-Identifier: GPL-3.0-or-later
// The WebAssembly module's calls as JavaScript functions (web/src/coons_web.c),
// shared by the page (a plain <script>: the global CoonsApi) and the node
// tests (require). Every output equals what coons2stl writes with its
// default options: the `name` is the base name coons2stl takes from its
// output file ("dir/part.scad" -> "part").
(function (root) {
  'use strict';
  // the values of coons_format (include/coons/io.h)
  const FORMATS = { stl: 1, off: 3, scad: 4, msh: 6, vtu: 8, inp: 9 };
  const SURFACE = { stl: true, off: true, scad: true };

  function wrap(M) {
    function cstr(s) {
      const n = M.lengthBytesUTF8(s) + 1;
      const p = M._malloc(n);
      M.stringToUTF8(s, p, n);
      return p;
    }
    function lastError() {
      const e = new Error(M.UTF8ToString(M._cw_error_message()));
      e.path = M.UTF8ToString(M._cw_error_path());
      e.line = M._cw_error_line();
      e.column = M._cw_error_column();
      return e;
    }
    function takeOutput() {
      const p = M._cw_out_data(), n = M._cw_out_size();
      const bytes = M.HEAPU8.slice(p, p + n);
      M._cw_out_free();
      return bytes;
    }
    // A loaded model; free() it. Throws the loader's error (message
    // "NAME:LINE:COL: /json/path: ...", with .path, .line, .column).
    function load(text, name) {
      const bytes = new TextEncoder().encode(text);
      const buf = M._malloc(bytes.length || 1);
      M.HEAPU8.set(bytes, buf);
      const pname = cstr(name || 'model.json');
      const ptr = M._cw_load(buf, bytes.length, pname);
      M._free(buf);
      M._free(pname);
      if (!ptr) throw lastError();
      return {
        ptr,
        tolerance: () => M._cw_tolerance(ptr),
        morphs: () => M._cw_morph_count(ptr),
        bodies: () => M._cw_body_count(ptr),
        setTime(t) { if (M._cw_set_time(ptr, t)) throw lastError(); },
        free() { M._cw_free(ptr); },
      };
    }
    // The bytes coons2stl -o NAME.FORMAT writes (format: stl off scad vtu
    // msh inp); throws its refusal. tolerance (surfaces only): <= 0 or
    // undefined for the model's.
    function write(model, format, name, tolerance) {
      const f = FORMATS[format];
      if (!f) throw new Error('unknown format ' + format);
      const pname = cstr(name || '');
      const rc = SURFACE[format] ? M._cw_write_surface(model.ptr, f, pname, tolerance || 0)
                                 : M._cw_write_volume(model.ptr, f, pname);
      M._free(pname);
      if (rc) throw lastError();
      return takeOutput();
    }
    // The solid's triangles at `tolerance` for display: {positions
    // (Float32Array xyz), indices (Uint32Array), united, note}.
    function mesh(model, tolerance, resolution) {
      if (M._cw_preview(model.ptr, tolerance || 0, resolution || 0)) throw lastError();
      const nv = M._cw_preview_vertex_count(), nt = M._cw_preview_triangle_count();
      const pv = M._cw_preview_vertices() >> 3, pt = M._cw_preview_triangles() >> 2;
      const united = !!M._cw_preview_united();
      return {
        positions: Float32Array.from(M.HEAPF64.subarray(pv, pv + 3 * nv)),
        indices: M.HEAPU32.slice(pt, pt + 3 * nt),
        // false: a union the C core cannot make, shown as the bodies' shells
        united, note: united ? '' : M.UTF8ToString(M._cw_error_message()),
      };
    }
    // The isoparametric surfaces direction (0 u, 1 v, 2 w) = values of
    // every body, with each body's boundary, and det J at every vertex:
    // {positions, indices, detj (Float64Array), parts: [{first, count,
    // boundary}]} (triangle ranges; body k's boundary is part k (n + 1)).
    function iso(model, direction, values, tolerance) {
      const n = values.length, pv = M._malloc(8 * Math.max(1, n));
      M.HEAPF64.set(values, pv >> 3);
      const rc = M._cw_iso(model.ptr, direction, pv, n, tolerance || 0);
      M._free(pv);
      if (rc) throw lastError();
      const nv = M._cw_iso_vertex_count(), nt = M._cw_iso_triangle_count();
      const v = M._cw_iso_vertices() >> 3, t = M._cw_iso_triangles() >> 2, d = M._cw_iso_detj() >> 3;
      const parts = [];
      for (let i = 0; i < M._cw_iso_part_count(); i++)
        parts.push({ first: M._cw_iso_part_first(i), count: M._cw_iso_part_triangles(i), boundary: i % (n + 1) === 0 });
      return {
        positions: Float32Array.from(M.HEAPF64.subarray(v, v + 3 * nv)),
        indices: M.HEAPU32.slice(t, t + 3 * nt),
        detj: M.HEAPF64.slice(d, d + nv),
        parts,
      };
    }
    // The cells: the 12 boundary edges of every body (u = 0..1 at the
    // corners of the unit cube in v, w; then v; then w), each at n + 1
    // points of coons_body_eval(): {n, positions (Float64Array xyz; body
    // b's edge e, point s at 3 ((12 b + e)(n + 1) + s))}.
    function cells(model, n) {
      const np = M._cw_cells(model.ptr, n);
      if (!np && model.bodies()) throw lastError();
      const p = M._cw_cells_data() >> 3;
      return { n, positions: M.HEAPF64.slice(p, p + 3 * np) };
    }
    return { load, write, mesh, iso, cells, version: () => M.UTF8ToString(M._cw_version()), FORMATS };
  }

  const api = { wrap, FORMATS };
  if (typeof module !== 'undefined' && module.exports) module.exports = api;
  else root.CoonsApi = api;
})(typeof self !== 'undefined' ? self : this);
