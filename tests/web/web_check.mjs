// Opens vgd's web pages in headless Chromium (playwright-core, Debian's
// /usr/bin/chromium) as a visitor would: serves DIR on 127.0.0.1, loads each
// page, waits for X_ITE's <x3d-canvas> load event, reads the scene through
// X_ITE's own API, and takes a screenshot whose pixels it measures. Prints
// one JSON object. Used by tests/io/vrml/test_web.cpp.
//
//   node web_check.mjs DIR SPEC.json
//
// SPEC: {"pages": [{"page": "a.html",
//                   "lengths": ["GarmentCoord.point", "Piece_FRONT.geometry.coordIndex"],
//                   "motion": {"node": "Flag", "field": "coordinate", "after_s": 1.5},
//                   "screenshot": "a.png", "colour": [0.18, 0.30, 0.62], "fps": true}]}
// Output: {"pages": [{"page", "event": "load"|"error"|"timeout", "ms", "lengths": {...},
//          "motion": {"count", "max_moved", "pinned_moved"}, "fps", "pixels": {...}}]}
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { chromiumArgs, serveFolder } from './serve.mjs';

const [dir, specFile] = process.argv.slice(2);
const spec = JSON.parse(fs.readFileSync(specFile, 'utf8'));
const root = path.resolve(dir);

const { server, base } = await serveFolder(root);

const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'vgd-chromium-'));
let context;
const out = { pages: [] };
try {
  context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport: { width: 800, height: 600 },
    args: chromiumArgs,
  });
  // X_ITE fires a DOM load (or error) event on the element: catch it however early it comes.
  await context.addInitScript(() => {
    window.__x3d = new Promise((resolve) => {
      const t0 = performance.now();
      const on = (kind) => (e) => {
        if (e.target && e.target.tagName === 'X3D-CANVAS') resolve({ event: kind, ms: performance.now() - t0 });
      };
      document.addEventListener('load', on('load'), true);
      document.addEventListener('error', on('error'), true);
      setTimeout(() => resolve({ event: 'timeout', ms: performance.now() - t0 }), 30000);
    });
  });
  for (const p of spec.pages) {
    const page = context.pages()[0] || (await context.newPage());
    const r = { page: p.page, console_errors: [] };
    page.removeAllListeners('console');
    page.on('console', (m) => { if (m.type() === 'error') r.console_errors.push(m.text()); });
    await page.goto(base + p.page);
    Object.assign(r, await page.evaluate(() => window.__x3d));
    // Field lengths through X_ITE's scene API: "DEF.field[.field...]".
    if (p.lengths) {
      r.lengths = await page.evaluate((paths) => {
        const scene = document.querySelector('x3d-canvas').browser.currentScene;
        const res = {};
        for (const q of paths) {
          try {
            const [name, ...fields] = q.split('.');
            let v = scene.getNamedNode(name);
            for (const f of fields) v = v[f];
            res[q] = v.length;
          } catch (e) { res[q] = -1; }
        }
        return res;
      }, p.lengths);
    }
    // A live scene moves by itself: compare a field now with it at six
    // moments over the next `after_s` (the largest move of each point; one
    // sample could fall where a looped animation is back where it began).
    if (p.motion) {
      const read = () => page.evaluate(({ node, field }) => {
        const v = document.querySelector('x3d-canvas').browser.currentScene.getNamedNode(node)[field];
        const a = [];
        for (let i = 0; i < v.length; i++) a.push([v[i].x, v[i].y, v[i].z]);
        return a;
      }, p.motion);
      await page.waitForTimeout(300);
      const first = await read();
      const moved = first.map(() => 0);
      let second = first;
      for (let k = 0; k < 6; k++) {
        await page.waitForTimeout((1000 * p.motion.after_s) / 6);
        second = await read();
        first.forEach((q, i) => {
          if (second[i]) moved[i] = Math.max(moved[i], Math.hypot(q[0] - second[i][0], q[1] - second[i][1], q[2] - second[i][2]));
        });
      }
      let maxMoved = 0;
      for (const d of moved) maxMoved = Math.max(maxMoved, d);
      r.motion = { count: first.length, count_later: second.length, max_moved: maxMoved,
        pinned_moved: (p.motion.pinned || []).map((i) => moved[i] ?? -1) };
    }
    // Frames the page draws in one second (a live scene's script runs once per frame).
    if (p.fps) {
      r.fps = await page.evaluate(() => new Promise((done) => {
        let n = 0;
        const t0 = performance.now();
        const step = () => (performance.now() - t0 < 1000 ? (n++, requestAnimationFrame(step)) : done(n));
        requestAnimationFrame(step);
      }));
    }
    if (p.screenshot) {
      await page.waitForTimeout(500);
      const canvas = await page.$('x3d-canvas');
      const box = await canvas.boundingBox();
      const png = await page.screenshot({ path: path.join(root, p.screenshot), clip: box, timeout: 60000 });
      // Measure the image in the browser itself (no PNG library here).
      r.pixels = await page.evaluate(async ({ data, colour }) => {
        const img = new Image();
        img.src = 'data:image/png;base64,' + data;
        await img.decode();
        const c = document.createElement('canvas');
        c.width = img.width, c.height = img.height;
        const g = c.getContext('2d');
        g.drawImage(img, 0, 0);
        const px = g.getImageData(0, 0, c.width, c.height).data;
        const hue = (r, gg, b) => {
          const mx = Math.max(r, gg, b), mn = Math.min(r, gg, b), d = mx - mn;
          if (d === 0) return { h: 0, s: 0, v: mx };
          let h = mx === r ? ((gg - b) / d) % 6 : mx === gg ? (b - r) / d + 2 : (r - gg) / d + 4;
          return { h: (h * 60 + 360) % 360, s: d / mx, v: mx };
        };
        const want = hue(colour[0], colour[1], colour[2]);
        const colours = new Set();
        let n = 0, sum = 0, sum2 = 0, centreN = 0, centreHits = 0, hits = 0;
        for (let y = 0; y < c.height; y++)
          for (let x = 0; x < c.width; x++) {
            const i = 4 * (y * c.width + x), r = px[i] / 255, gg = px[i + 1] / 255, b = px[i + 2] / 255;
            const l = 0.299 * r + 0.587 * gg + 0.114 * b;
            n++, sum += l, sum2 += l * l;
            if (colours.size < 5000) colours.add((px[i] >> 3) << 10 | (px[i + 1] >> 3) << 5 | (px[i + 2] >> 3));
            const h = hue(r, gg, b);
            const dh = Math.min(Math.abs(h.h - want.h), 360 - Math.abs(h.h - want.h));
            const hit = dh < 30 && h.s > 0.25 && h.v > 0.08;
            hits += hit;
            // The expected region: the middle third across, the middle half down.
            if (x > c.width / 3 && x < 2 * c.width / 3 && y > c.height / 4 && y < 3 * c.height / 4) centreN++, centreHits += hit;
          }
        const mean = sum / n;
        return { width: c.width, height: c.height, mean_luma: mean, luma_stddev: Math.sqrt(Math.max(0, sum2 / n - mean * mean)),
          distinct_colours: colours.size, garment_fraction: hits / n, centre_garment_fraction: centreHits / centreN };
      }, { data: png.toString('base64'), colour: p.colour || [0.18, 0.3, 0.62] });
    }
    out.pages.push(r);
  }
} catch (e) {
  out.error = String((e && e.message) || e);
} finally {
  if (context) await context.close();
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
console.log(JSON.stringify(out));
