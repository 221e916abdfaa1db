// Headless-browser test of the web example: Debian's Chromium driven by playwright-core.
//
// Serves the repository from a tiny HTTP server on 127.0.0.1 (an ephemeral port), loads
// examples/web/index.html, fails on any console error, page error, failed request or HTTP
// error, and compares what the page computed in WebAssembly with the native (host) results
// in crates/brdf-wasm/pkg/web-expected.json (written by `cargo xtask wasm`):
// * the three Fig. 6 curves and the modified G from the default LUT asset, value by value
//   (bit-exact);
// * the sphere canvas's pixels at fixed points for each setting, after choosing the model
//   and moving the sliders through the page's own controls (exact 8-bit RGBA).
// Saves examples/web/screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const webDir = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const repo = path.resolve(webDir, '../..');
const expected = JSON.parse(
  await readFile(path.join(repo, 'crates/brdf-wasm/pkg/web-expected.json'), 'utf8'),
);

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.png': 'image/png',
  '.blut': 'application/octet-stream',
};
// Only these trees are served.
const SERVED = ['examples/web/', 'crates/brdf-wasm/js/', 'crates/brdf-wasm/pkg/', 'assets/'];

let server;
let baseUrl;
let context;
let userDataDir;
const problems = [];

function serve(req, res) {
  const url = new URL(req.url, 'http://127.0.0.1');
  const rel = path.posix.normalize(decodeURIComponent(url.pathname)).replace(/^\/+/, '');
  const file = path.join(repo, rel);
  if (req.method !== 'GET' || !file.startsWith(repo + path.sep) || !SERVED.some((p) => rel.startsWith(p))) {
    res.writeHead(404).end();
    return;
  }
  readFile(file).then(
    (body) => res.writeHead(200, { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream' }).end(body),
    () => res.writeHead(404).end(),
  );
}

before(async () => {
  server = http.createServer(serve);
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  baseUrl = `http://127.0.0.1:${server.address().port}`;
  userDataDir = await mkdtemp(path.join(tmpdir(), 'brdf-web-chromium-'));
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    viewport: { width: 1000, height: 760 },
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
    ],
  });
});

after(async () => {
  await context?.close();
  await new Promise((ok) => (server ? server.close(ok) : ok()));
  if (userDataDir) await rm(userDataDir, { recursive: true, force: true });
});

async function openPage() {
  const page = await context.newPage();
  page.on('console', (m) => m.type() === 'error' && problems.push(`console: ${m.text()}`));
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
  page.on('response', (r) => r.status() >= 400 && problems.push(`HTTP ${r.status()}: ${r.url()}`));
  await page.goto(`${baseUrl}/examples/web/index.html`);
  await page.evaluate(() => window.brdfPage.ready);
  return page;
}

const dv = new DataView(new ArrayBuffer(4));
const f32 = (bits) => (dv.setUint32(0, bits), dv.getFloat32(0));
const same = (a, b) => a === b || (Number.isNaN(a) && Number.isNaN(b));

test('page loads, draws Fig. 6 from WASM values equal to the native ones', async () => {
  const page = await openPage();
  const curves = await page.evaluate(() => {
    const c = window.brdfPage.curves;
    return {
      blinn: Array.from(c.blinn),
      modified: Array.from(c.modified),
      smith: Array.from(c.smith),
      modified_lut: Array.from(c.modified_lut),
    };
  });
  for (const name of ['blinn', 'modified', 'smith', 'modified_lut']) {
    const want = expected.curves[name].map(f32);
    assert.equal(curves[name].length, 181);
    const bad = want.findIndex((w, k) => !same(w, curves[name][k]));
    assert.equal(bad, -1, `${name} at θr = ${bad - 90}°: ${curves[name][bad]} vs native ${want[bad]}`);
  }
  // The curves are on the canvas: the modified G's line colour appears near its value at
  // θr = 0° (x, y computed with the page's own mapping).
  const g0 = want0(expected.curves.modified);
  const hit = await page.evaluate((g) => {
    const c = document.getElementById('fig6');
    const x = Math.round(48 + (90 / 180) * (c.width - 64));
    const y = Math.round(c.height - 40 - g * (c.height - 56));
    const d = c.getContext('2d').getImageData(x - 2, y - 2, 5, 5).data;
    for (let i = 0; i < d.length; i += 4) if (d[i + 2] > 150 && d[i] < 90) return true;
    return false;
  }, g0);
  assert.ok(hit, 'the modified-G curve is drawn where its value says');
  const status = await page.evaluate(() => window.brdfPage.status);
  assert.ok(Number.isInteger(expected.models) && expected.models > 0, 'native model count');
  assert.match(status, new RegExp(`^module: ${expected.models} models; LUTs: g_modified\\.blut .*g_modified_sigma0\\.3\\.blut .*dfg_ggx\\.blut`));
  await page.close();
  assert.deepEqual(problems, []);
});

function want0(bitsArr) {
  return f32(bitsArr[90]);
}

test('sphere pixels equal the native rendering for every setting; screenshot saved', async () => {
  const page = await openPage();
  for (const s of expected.spheres) {
    await page.selectOption('#model', s.model);
    const names = await page.$$eval('#controls input', (els) => els.map((e) => e.name));
    assert.equal(names.length, s.params.length, `${s.model}: parameter count`);
    for (let k = 0; k < names.length; k++) {
      await page.$eval(
        `#controls input[name="${names[k]}"]`,
        (el, v) => {
          el.value = String(v);
          el.dispatchEvent(new Event('input', { bubbles: true }));
        },
        s.params[k],
      );
    }
    const used = await page.evaluate(() => window.brdfPage.params);
    assert.deepEqual(used, s.params.map(Math.fround), `${s.model}: the sliders hold the parameters`);
    const got = await page.evaluate((pts) => {
      const c = document.getElementById('sphere');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      return pts.map(([x, y]) => Array.from(d.subarray(4 * (y * c.width + x), 4 * (y * c.width + x) + 4)));
    }, s.pixels);
    let mismatches = 0;
    let first = null;
    s.pixels.forEach(([x, y, ...want], k) => {
      if (got[k].some((v, c) => v !== want[c])) {
        mismatches++;
        first ??= `(${x},${y}): page ${got[k]} vs native ${want}`;
      }
    });
    console.log(`${s.model} ${JSON.stringify(s.params)}: ${s.pixels.length - mismatches}/${s.pixels.length} pixels equal`);
    assert.equal(mismatches, 0, first);
    // Not a flat image: lit and background pixels both occur.
    assert.ok(new Set(s.pixels.map((p) => p[2] + 256 * p[3])).size > 20, 'shading varies');
  }
  await page.screenshot({ path: path.join(webDir, 'screenshot.png'), fullPage: true });
  await page.close();
  assert.deepEqual(problems, []);
});
