// Opens a catalogue's contact sheet (OUT/index.html, written by vgd batch)
// in headless Chromium (playwright-core, Debian's /usr/bin/chromium) as a
// visitor would: serves OUT on 127.0.0.1, counts the cards shown and the
// preview images that loaded, then chooses each filter value given and
// counts again. Prints one JSON object. Used by tests/batch/test_contact_sheet.cpp.
//
//   node contact_sheet.mjs OUT '{"size": "38", "state": "failed"}'
//
// Output: {"cards", "shown", "images", "loaded", "counts": "...",
//          "filtered": {"size=38": n, ...}, "errors": [...]}
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { chromiumArgs, serveFolder } from './serve.mjs';

const [dir, filtersJson] = process.argv.slice(2);
const filters = JSON.parse(filtersJson || '{}');
const root = path.resolve(dir);
const { server, base } = await serveFolder(root);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'vgd-chromium-'));
let context;
const out = { errors: [], filtered: {} };
try {
  context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1200, height: 900 },
    args: chromiumArgs,
  });
  const page = await context.newPage();
  page.on('pageerror', (e) => out.errors.push(String(e)));
  await page.goto(base + 'index.html', { waitUntil: 'load' });
  const count = () => page.evaluate(() => {
    const cards = [...document.querySelectorAll('.card')];
    const imgs = [...document.querySelectorAll('.card img')];
    return {
      cards: cards.length,
      shown: cards.filter((c) => !c.hidden).length,
      images: imgs.length,
      loaded: imgs.filter((i) => i.complete && i.naturalWidth > 0).length,
      counts: document.getElementById('counts').textContent,
      label: document.getElementById('shown').textContent,
    };
  });
  // Lazy images load once scrolled into view: the page is small enough to show them all.
  await page.waitForFunction(() => [...document.querySelectorAll('.card img')].every((i) => i.complete),
    null, { timeout: 20000 }).catch(() => {});
  Object.assign(out, await count());
  for (const [key, value] of Object.entries(filters)) {
    await page.selectOption(`select[name=${key}]`, value);
    const c = await count();
    out.filtered[`${key}=${value}`] = c.shown;
    out.filtered[`${key}=${value} label`] = c.label;
  }
} catch (e) {
  out.errors.push(String(e));
} finally {
  if (context) await context.close();
  server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
console.log(JSON.stringify(out));
