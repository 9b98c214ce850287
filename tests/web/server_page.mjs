// Opens vgd-server's browser page in headless Chromium (playwright-core,
// Debian's /usr/bin/chromium) as a visitor would, on a job: waits until the
// page has drawn frames from the job's WebSocket and the stream ended, takes
// a screenshot and measures how much of the view is garment (not the
// background). Prints one JSON object. Used by tests/net/test_page.cpp.
//
//   node server_page.mjs http://127.0.0.1:PORT JOB_ID SCREENSHOT.png
// Output: {"viewer": {frames, lastSeq, state, endState, particles, errors}, "listed": n,
//          "page_errors": [...], "pixels": {"width", "height", "garment_fraction"}}
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { chromiumArgs } from './serve.mjs';

const [base, job, shot] = process.argv.slice(2);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'vgd-chromium-'));
const out = { page_errors: [] };
let context;
try {
  context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport: { width: 900, height: 600 },
    // WebGL on SwiftShader: the GPU flag of the shared options left out.
    args: [...chromiumArgs.filter((a) => a !== '--disable-gpu'), '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  const page = await context.newPage();
  page.on('pageerror', (e) => out.page_errors.push(String(e)));
  await page.goto(`${base}/?job=${job}`, { waitUntil: 'load' });
  await page.waitForFunction(() => window.vgdViewer && window.vgdViewer.state === 'end' && window.vgdViewer.frames > 0,
    null, { timeout: 120000 });
  await page.waitForFunction(() => document.querySelectorAll('tr.job').length > 0, null, { timeout: 10000 });
  out.viewer = await page.evaluate(() => window.vgdViewer);
  out.listed = await page.evaluate(() => document.querySelectorAll('tr.job').length);
  const canvas = await page.$('#view canvas');
  await canvas.screenshot({ path: shot });
  // The garment's share of the view, read from the WebGL canvas itself
  // (drawn with preserveDrawingBuffer): pixels clearly blue, unlike the grey-blue background.
  out.pixels = await page.evaluate(() => {
    const src = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = src.width, c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    let hits = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i + 2] > px[i] + 40 && px[i + 2] > px[i + 1] + 20) hits++;
    return { width: c.width, height: c.height, garment_fraction: hits / (c.width * c.height) };
  });
} catch (e) {
  out.page_errors.push(String(e));
} finally {
  if (context) await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
console.log(JSON.stringify(out));
