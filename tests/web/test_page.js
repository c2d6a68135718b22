// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 29: the page (build-web/) in headless Chromium (Debian's, driven by
// puppeteer-core; no browser is downloaded), served by a static server on
// 127.0.0.1 that this test starts. For every example the C core writes (the
// unions need CGAL): the page loads it and renders a non-blank view (the
// screenshot is kept in OUT_DIR), a real mouse drag on a control point
// (pressed where the page's camera projects it) changes the model and the
// mesh, and export("stl") equals the binary STL that the native coons2stl
// writes from the same JSON (window.coons.model()), byte for byte.
//   node tests/web/test_page.js BUILD_WEB COONS2STL EXAMPLES_DIR OUT_DIR
'use strict';
const fs = require('fs');
const path = require('path');
const http = require('http');
const { execFileSync } = require('child_process');

const [buildWeb, coons2stl, examplesDir, outDir] = process.argv.slice(2);
// A drag's previews (the remesh of each pointer move: the module's mesh and
// its upload to three.js, app.js) must take at most PREVIEW_BOUND_MS each:
// per example, the longest preview of a drag, as the median of three drags
// (two when they agree), so that one preview slowed by another process on a
// shared machine does not fail the test while a preview plan that is slow
// on every drag does.
const PREVIEW_BOUND_MS = Number(process.env.COONS_PREVIEW_BOUND_MS || 50);
if (!outDir) {
  console.error('usage: test_page.js BUILD_WEB COONS2STL EXAMPLES_DIR OUT_DIR');
  process.exit(2);
}
const puppeteer = require(require.resolve('puppeteer-core', {
  paths: [path.resolve(__dirname, '../../web/node_modules')] }));
const CHROMIUM = process.env.COONS_CHROMIUM || '/usr/bin/chromium';
let passed = 0, failed = 0;
function check(ok, what) {
  if (ok) passed++;
  else { failed++; console.log('FAIL ' + what); }
  return ok;
}

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
                '.json': 'application/json', '.wasm': 'application/wasm' };
function serve(root) {
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(req.url.split('?')[0]);
    const file = path.join(root, url === '/' ? 'index.html' : url);
    if (!file.startsWith(path.resolve(root)) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'Content-Type': TYPES[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// coons2stl's binary STL of `text` (null when it refuses)
function nativeStl(text, base) {
  const json = path.join(outDir, base + '.json'), stl = path.join(outDir, base + '.stl');
  fs.writeFileSync(json, text);
  try {
    execFileSync(coons2stl, ['-q', '-o', stl, json], { stdio: ['ignore', 'ignore', 'pipe'] });
  } catch (e) {
    return null;
  }
  return fs.readFileSync(stl);
}

async function main() {
  fs.mkdirSync(outDir, { recursive: true });
  const server = await serve(path.resolve(buildWeb));
  const port = server.address().port;
  const browser = await puppeteer.launch({
    executablePath: CHROMIUM, headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
           '--disable-gpu-sandbox', '--disable-dev-shm-usage', '--no-first-run', '--window-size=1100,760'],
  });
  const t0 = Date.now();
  const page = await browser.newPage();
  await page.setViewport({ width: 1100, height: 760 });
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') pageErrors.push(m.text()); });
  await page.goto(`http://127.0.0.1:${port}/`, { waitUntil: 'load' });
  await page.evaluate(() => window.coons.ready);
  check(await page.$('canvas#view') !== null, 'the page has canvas#view');
  check(await page.evaluate(() => !!document.querySelector('footer a[href="libcoons-source.tar.gz"]')) &&
        fs.existsSync(path.join(buildWeb, 'libcoons-source.tar.gz')), 'the footer offers the source');

  // COONS_WEB_EXAMPLES: a regular expression to take only some examples
  const only = new RegExp(process.env.COONS_WEB_EXAMPLES || '.');
  const names = fs.readdirSync(examplesDir).filter((f) => f.endsWith('.json') && only.test(f)).sort();
  const times = [];
  let examples = 0;
  for (const f of names) {
    const base = f.replace(/\.json$/, '');
    const text = fs.readFileSync(path.join(examplesDir, f), 'utf8');
    const want0 = nativeStl(text, base);
    if (!want0) {
      // a union the C core cannot make: the page shows the bodies unmerged
      // and refuses export("stl") with coons2stl's message
      await page.evaluate((t, n) => window.coons.load(t, n), text, f);
      await page.evaluate(() => window.coons.rendered());
      const refused = await page.evaluate(async () => {
        try { await window.coons.export('stl'); return null; } catch (e) { return e.message; }
      });
      const said = (() => {
        try { execFileSync(coons2stl, ['-q', '-o', path.join(outDir, base + '.stl'), path.join(examplesDir, f)],
                            { stdio: ['ignore', 'ignore', 'pipe'] }); return ''; } catch (e) { return String(e.stderr); }
      })();
      check(refused !== null && said.includes(refused), `${f}: export("stl") refused as coons2stl refuses it: ${refused}`);
      check(/shown unmerged/.test(await page.$eval('#status', (e) => e.textContent)), `${f}: the status says the bodies are unmerged`);
      await (await page.$('#view')).screenshot({ path: path.join(outDir, base + '.png') });
      console.log(`${f}: a union without CGAL, shown unmerged`);
      continue;
    }
    examples++;
    await page.evaluate((t, n) => window.coons.load(t, n), text, f);
    await page.evaluate(() => window.coons.rendered());
    check(await page.evaluate(() => window.coons.model()) === text, `${f}: model() is the text loaded`);

    // a non-blank view: the screenshot, decoded by the browser's own PNG
    // decoder on a 2-D canvas, has many pixels off the white background
    // and several shades (a shaded solid, not a flat silhouette)
    // and the solid alone (points and nets switched off in the panel) too
    const view = await page.$('#view');
    await view.screenshot({ path: path.join(outDir, base + '.png') });
    await page.click('#show-points');
    await page.click('#show-nets');
    await page.evaluate(() => window.coons.rendered());
    const png = await view.screenshot();
    await page.click('#show-points');
    await page.click('#show-nets');
    await page.evaluate(() => window.coons.rendered());
    const seen = await page.evaluate(async (b64) => {
      const img = new Image();
      img.src = 'data:image/png;base64,' + b64;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width; c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      const d = g.getImageData(0, 0, c.width, c.height).data;
      let off = 0;
      const shades = new Set();
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) off++;
        shades.add((d[i] >> 3) << 10 | (d[i + 1] >> 3) << 5 | (d[i + 2] >> 3));
      }
      return { off: off / (d.length / 4), shades: shades.size };
    }, Buffer.from(png).toString('base64'));
    check(seen.off > 0.02 && seen.shades > 8, `${f}: the solid is blank (${(100 * seen.off).toFixed(1)}% ` +
          `drawn, ${seen.shades} shades)`);

    // the cells of a lattice: with "cells" on (points and nets off), the
    // view changes, and the pixels that change turn to the cells' green
    if (/lattice/.test(f)) {
      await page.click('#show-points');
      await page.click('#show-nets');
      await page.click('#show-cells');
      await page.evaluate(() => window.coons.rendered());
      const withCells = await view.screenshot({ path: path.join(outDir, base + '-cells.png') });
      await page.click('#show-cells');
      await page.click('#show-points');
      await page.click('#show-nets');
      await page.evaluate(() => window.coons.rendered());
      const diff = await page.evaluate(async (a64, b64) => {
        const pixels = async (b) => {
          const img = new Image();
          img.src = 'data:image/png;base64,' + b;
          await img.decode();
          const c = document.createElement('canvas');
          c.width = img.width; c.height = img.height;
          const g = c.getContext('2d');
          g.drawImage(img, 0, 0);
          return g.getImageData(0, 0, c.width, c.height).data;
        };
        const a = await pixels(a64), b = await pixels(b64);
        let changed = 0, green = 0;
        for (let i = 0; i < a.length; i += 4) {
          if (Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]) < 24) continue;
          changed++;
          // nearer the cells' colour (0x0a7d3b, blended over the solid or the background)
          const to = (p, j) => Math.hypot(p[j] - 10, p[j + 1] - 125, p[j + 2] - 59);
          if (to(b, i) < to(a, i) - 20) green++;
        }
        return { changed: changed / (a.length / 4), green: changed ? green / changed : 0 };
      }, Buffer.from(png).toString('base64'), Buffer.from(withCells).toString('base64'));
      check(diff.changed > 0.003 && diff.green > 0.9, `${f}: the cells change ${(100 * diff.changed).toFixed(2)}% ` +
            `of the view, ${(100 * diff.green).toFixed(0)}% of it green`);
      console.log(`${f}: the cells change ${(100 * diff.changed).toFixed(2)}% of the view, ` +
                  `${(100 * diff.green).toFixed(0)}% of it toward their green`);
    }

    // export("stl") of the loaded model equals coons2stl's
    const stl0 = Buffer.from(await page.evaluate(async () => Array.from(await window.coons.export('stl'))));
    check(Buffer.compare(stl0, want0) === 0, `${f}: export("stl") differs from coons2stl's before the drag`);

    // a real drag: press on a control point where the camera shows it
    // (apart from its neighbours on the screen), move, release
    const cps = await page.evaluate(() => window.coons.controlPoints());
    const screen = await page.evaluate((n) => Array.from({ length: n }, (_, i) => window.coons.screen(i)), cps.length);
    const box = await view.boundingBox();
    const inside = (s) => s.visible && s.x > box.x + 20 && s.x < box.x + box.width - 60 &&
                          s.y > box.y + 60 && s.y < box.y + box.height - 20;
    const apart = (i) => screen.every((s, j) => j === i || Math.hypot(s.x - screen[i].x, s.y - screen[i].y) > 26);
    const candidates = cps.map((p) => p.id).filter((i) => inside(screen[i]) && apart(i));
    let dragged = false;
    const before = await page.evaluate(() => window.coons.stats().remesh.length);
    // a drag from s, 6 pointer moves; the previews' times
    const drag = async (s, sign = 1) => {
      const n0 = await page.evaluate(() => window.coons.stats().remesh.length);
      await page.mouse.move(s.x, s.y);
      await page.mouse.down();
      for (let k = 1; k <= 6; k++) {
        await page.mouse.move(s.x + sign * 5 * k, s.y - sign * 4 * k);
        await page.evaluate(() => window.coons.rendered());
      }
      await page.mouse.up();
      await page.evaluate(() => window.coons.idle()); // the worker's full-tolerance mesh
      return (await page.evaluate(() => window.coons.stats().remesh)).slice(n0);
    };
    const dragMax = []; // the longest preview of each drag
    for (const id of candidates.slice(0, 6)) {
      const s = screen[id];
      const ms = await drag(s);
      const after = await page.evaluate(() => window.coons.model());
      if (after === text) continue; // refused (the moved model did not load): next point
      const moved = (await page.evaluate(() => window.coons.controlPoints()))
        .reduce((m, p) => Math.min(m, Math.hypot(p.xyz[0] - cps[id].xyz[0], p.xyz[1] - cps[id].xyz[1],
                                                  p.xyz[2] - cps[id].xyz[2])), Infinity);
      const stl1 = Buffer.from(await page.evaluate(async () => Array.from(await window.coons.export('stl'))));
      const want1 = nativeStl(after, base + '-dragged');
      check(moved > 0, `${f}: control point ${id} is still where it was`);
      check(Buffer.compare(stl1, stl0) !== 0, `${f}: the drag of point ${id} left the mesh unchanged`);
      check(want1 !== null && Buffer.compare(stl1, want1) === 0,
            `${f}: export("stl") after the drag differs from coons2stl's of model()`);
      await view.screenshot({ path: path.join(outDir, base + '-dragged.png') });
      dragged = true;
      if (ms.length) dragMax.push(Math.max(...ms));
      // the same point dragged back and forth again: the median of three
      // drags' longest previews (the third only when the two disagree)
      for (let k = 0; k < 3 && dragMax.length < 3; k++) {
        if (dragMax.length === 2 && (dragMax[0] <= PREVIEW_BOUND_MS) === (dragMax[1] <= PREVIEW_BOUND_MS)) break;
        const sel = await page.evaluate(() => window.coons.stats().selected);
        const q = await page.evaluate((i) => window.coons.screen(i), sel);
        const again = await drag(q, k % 2 ? 1 : -1);
        if (again.length) dragMax.push(Math.max(...again));
      }
      break;
    }
    check(dragged, `${f}: no drag of ${candidates.length} candidate points changed the model`);
    const st = await page.evaluate(() => window.coons.stats());
    const ms = st.remesh.slice(before);
    if (ms.length) {
      const sorted = dragMax.slice().sort((a, b) => a - b);
      const median = sorted.length === 2 ? sorted[1] : sorted[Math.floor(sorted.length / 2)];
      times.push({ f, n: ms.length, max: Math.max(...ms), median, drags: dragMax.length,
                   mean: ms.reduce((a, b) => a + b, 0) / ms.length, full: st.lastFull, preview: st.preview });
      check(median <= PREVIEW_BOUND_MS, `${f}: the longest preview of a drag took ${median.toFixed(1)} ms ` +
            `(median of ${dragMax.length} drags: ${dragMax.map((x) => x.toFixed(1)).join(', ')}), more than ${PREVIEW_BOUND_MS} ms`);
    }
  }
  // The rest of the contract and the panel, on spool.json: a drag along z
  // moves the point along z only; undo and redo; moveControlPoint; the
  // JSON export; a broken model is refused with its path shown.
  if (only.test('spool.json')) {
    const text = fs.readFileSync(path.join(examplesDir, 'spool.json'), 'utf8');
    await page.evaluate((t) => window.coons.load(t, 'spool.json'), text);
    await page.select('#constraint', 'z');
    const cps = await page.evaluate(() => window.coons.controlPoints());
    const box = await (await page.$('#view')).boundingBox();
    let id = -1, s = null;
    for (const p of cps) {
      const q = await page.evaluate((i) => window.coons.screen(i), p.id);
      if (q.visible && q.x > box.x + 40 && q.x < box.x + box.width - 40 && q.y > box.y + 80) { id = p.id; s = q; break; }
    }
    await page.mouse.move(s.x, s.y);
    await page.mouse.down();
    for (let k = 1; k <= 5; k++) await page.mouse.move(s.x + 7 * k, s.y - 6 * k);
    await page.mouse.up();
    await page.evaluate(() => window.coons.idle());
    await page.select('#constraint', 'free');
    const dragged = await page.evaluate(() => window.coons.model());
    const after = await page.evaluate(() => window.coons.controlPoints());
    // the points that moved are new places with the x and y of the dragged point
    const key = (p) => p.xyz.join(',');
    const was = new Set(cps.map(key));
    const moved = after.filter((p) => !was.has(key(p)));
    check(dragged !== text && moved.length > 0 &&
          moved.every((p) => p.xyz[0] === cps[id].xyz[0] && p.xyz[1] === cps[id].xyz[1]),
          `a drag along z of point ${id} at ${cps[id].xyz} moved points to ${moved.map(key).join(' ')}`);
    await page.click('#undo');
    check(await page.evaluate(() => window.coons.model()) === text, 'undo restores the model before the drag');
    await page.click('#redo');
    check(await page.evaluate(() => window.coons.model()) === dragged, 'redo restores the dragged model');
    const json = Buffer.from(await page.evaluate(async () => Array.from(await window.coons.export('json'))));
    check(json.toString('utf8') === dragged, 'export("json") is model()');
    // moveControlPoint: the point (and its links) to an exact place
    const p0 = after[0], to = [p0.xyz[0] + 0.5, p0.xyz[1] - 0.25, p0.xyz[2] + 0.125];
    await page.evaluate((i, x) => window.coons.moveControlPoint(i, x), p0.id, to);
    const placed = await page.evaluate(() => window.coons.controlPoints());
    check(placed.some((p) => p.xyz.every((v, d) => Math.abs(v - to[d]) < 1e-12)), 'moveControlPoint puts the point there');
    const stl = Buffer.from(await page.evaluate(async () => Array.from(await window.coons.export('stl'))));
    const want = nativeStl(await page.evaluate(() => window.coons.model()), 'spool-moved');
    check(want !== null && Buffer.compare(stl, want) === 0, 'export("stl") after moveControlPoint is coons2stl\'s');
    // a broken model: refused, the error shown with its JSON path, the model kept
    const before = await page.evaluate(() => window.coons.model());
    const err = await page.evaluate(async () => {
      try { await window.coons.load('{"coons": 1,\n "bodies": [{"type": "body0", "corners": [[0, 0, 0]]}]}', 'bad.json'); return null; }
      catch (e) { return { message: e.message, path: e.path, shown: document.getElementById('error').textContent,
                           visible: !document.getElementById('error').hidden }; }
    });
    check(err !== null && err.path === '/bodies/0/corners' && err.visible && err.shown.includes('/bodies/0/corners') &&
          err.shown.includes('bad.json:2:'), `a broken model's error: ${JSON.stringify(err)}`);
    check(await page.evaluate(() => window.coons.model()) === before, 'a refused model leaves the model as it was');
  }
  check(pageErrors.length === 0, 'page errors: ' + pageErrors.join(' | '));
  await browser.close();
  server.close();
  for (const t of times)
    console.log(`drag remesh ${t.f}: ${t.n} previews (${t.preview.resolution ? 'lattice ' + t.preview.resolution
                : t.preview.factor + ' tolerances'}), mean ${t.mean.toFixed(1)} ms, max ${t.max.toFixed(1)} ms, ` +
                `longest of a drag ${t.median.toFixed(1)} ms (median of ${t.drags}); ` +
                `full tolerance ${t.full === undefined ? '?' : t.full.toFixed(0)} ms (worker)`);
  if (times.length) {
    const worst = times.reduce((a, b) => (b.median > a.median ? b : a));
    const worstAny = times.reduce((a, b) => (b.max > a.max ? b : a));
    console.log(`drag previews: longest per example at most ${worst.median.toFixed(1)} ms (${worst.f}, median of drags; ` +
                `bound ${PREVIEW_BOUND_MS} ms); longest single preview ${worstAny.max.toFixed(1)} ms (${worstAny.f})`);
  }
  console.log(`page: ${examples} examples in ${((Date.now() - t0) / 1000).toFixed(1)} s; screenshots in ${outDir}`);
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}
main().catch((e) => { console.error(e); process.exit(1); });
