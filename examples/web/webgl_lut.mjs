// Helpers of the WebGL2 table tests (test/lut_engine.test.mjs, test/lut_sheen_glass.test.mjs):
// a PNG reader that keeps 16-bit samples (browsers decode 16-bit PNGs to 8 bits), a static
// file server, the headless Chromium launch (Debian's chromium, SwiftShader), the in-page
// renderer that samples one texture at a list of points, and the bound check of its values.

import assert from 'node:assert/strict';
import { after, before } from 'node:test';
import http from 'node:http';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { inflateSync } from 'node:zlib';
import { chromium } from 'playwright-core';

// Decodes a non-interlaced PNG (greyscale, RGB, grey + alpha or RGBA; 8 or 16 bits) with
// Node's zlib and the PNG filters (ISO/IEC 15948, section 9): { width, height, depth,
// channels, samples } with samples row-major, channels interleaved, 16-bit ones big-endian
// in the file read as integers.
export function decodePng(buf) {
  const sig = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
  if (!sig.every((b, i) => buf[i] === b)) throw new Error('not a PNG');
  let off = 8;
  let hdr;
  const idat = [];
  while (off < buf.length) {
    const len = buf.readUInt32BE(off);
    const type = buf.toString('latin1', off + 4, off + 8);
    const data = buf.subarray(off + 8, off + 8 + len);
    if (type === 'IHDR') {
      hdr = {
        width: data.readUInt32BE(0),
        height: data.readUInt32BE(4),
        depth: data[8],
        colour: data[9],
        interlace: data[12],
      };
    } else if (type === 'IDAT') idat.push(data);
    else if (type === 'IEND') break;
    off += 12 + len;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[hdr?.colour];
  if (!channels || ![8, 16].includes(hdr.depth) || hdr.interlace !== 0) {
    throw new Error(`unsupported PNG ${JSON.stringify(hdr)}`);
  }
  const raw = inflateSync(Buffer.concat(idat));
  const bpp = (channels * hdr.depth) / 8;
  const stride = hdr.width * bpp;
  if (raw.length !== hdr.height * (stride + 1)) throw new Error('PNG data length');
  const img = Buffer.alloc(hdr.height * stride);
  for (let y = 0; y < hdr.height; y++) {
    const filter = raw[y * (stride + 1)];
    const src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    const row = img.subarray(y * stride, (y + 1) * stride);
    const prev = y > 0 ? img.subarray((y - 1) * stride, y * stride) : Buffer.alloc(stride);
    for (let i = 0; i < stride; i++) {
      const a = i >= bpp ? row[i - bpp] : 0;
      const b = prev[i];
      const c = i >= bpp ? prev[i - bpp] : 0;
      let p;
      if (filter === 0) p = 0;
      else if (filter === 1) p = a;
      else if (filter === 2) p = b;
      else if (filter === 3) p = (a + b) >> 1;
      else if (filter === 4) {
        const q = a + b - c;
        const [pa, pb, pc] = [Math.abs(q - a), Math.abs(q - b), Math.abs(q - c)];
        p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      } else throw new Error(`PNG filter ${filter}`);
      row[i] = (src[i] + p) & 0xff;
    }
  }
  const n = hdr.width * hdr.height * channels;
  const samples = new Uint16Array(n);
  for (let i = 0; i < n; i++) samples[i] = hdr.depth === 16 ? img.readUInt16BE(2 * i) : img[i];
  return { width: hdr.width, height: hdr.height, depth: hdr.depth, channels, samples };
}

// Serves the files of `root` named in `types` (path -> content type) and a blank page at
// /index.html; returns { url, close }.
export async function serve(root, types) {
  const server = http.createServer((req, res) => {
    const p = new URL(req.url, 'http://127.0.0.1').pathname;
    if (p === '/index.html') {
      res.writeHead(200, { 'content-type': 'text/html; charset=utf-8' }).end('<!doctype html><title>lut</title>');
      return;
    }
    if (req.method !== 'GET' || !(p in types)) {
      res.writeHead(404).end();
      return;
    }
    readFile(path.join(root, p.slice(1))).then(
      (body) => res.writeHead(200, { 'content-type': types[p] }).end(body),
      () => res.writeHead(404).end(),
    );
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return {
    url: `http://127.0.0.1:${server.address().port}`,
    close: () => new Promise((ok) => server.close(ok)),
  };
}

// Headless Chromium with SwiftShader WebGL2, in a fresh profile; returns { context, close }.
export async function launch() {
  const userDataDir = await mkdtemp(path.join(tmpdir(), 'brdf-lut-chromium-'));
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  return {
    context,
    close: async () => {
      await context.close();
      await rm(userDataDir, { recursive: true, force: true });
    },
  };
}

// Runs in the page: uploads one texture (`tex`), evaluates the GLSL expression `expr` (a
// vec2 of `u_lut` and the point `x`, a vec3) at every point of `points` ([x, y, z] each,
// given as f32 values) in a fragment shader, with `glsl` (function definitions, e.g. an
// emitted sampling function) pasted verbatim before main, and reads the RGBA32F target back.
// Texture kinds:
// - png8: a PNG at `url` decoded by the browser, uploaded as the glTF Sample Viewer uploads
//   its LUTs (RGBA8, no flip, no colour conversion, no premultiplication);
// - r16f: `codes` (width × height 16-bit UNORM codes, row 0 first), each code / 65535
//   rounded to the nearest binary16 by Float16Array (ties to even), uploaded as R16F;
// - rg16f: raw little-endian binary16 (R, G) pairs at `url`, x fastest, then y (then z),
//   read explicitly little-endian whatever the host order, uploaded as a TEXTURE_2D or, for
//   three `dims`, a TEXTURE_3D RG16F (row j of the data is texture row j, v = (j + 0.5) / h).
// All LINEAR, CLAMP_TO_EDGE, one level.
export async function renderTexture({ points, tex, expr, glsl = '' }) {
  const W = 64;
  const H = Math.ceil(points.length / W);
  const canvas = document.createElement('canvas');
  canvas.width = W;
  canvas.height = H;
  const gl = canvas.getContext('webgl2');
  if (!gl) return { error: 'no WebGL2' };
  if (!gl.getExtension('EXT_color_buffer_float')) return { error: 'no EXT_color_buffer_float' };
  gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
  const is3d = tex.kind === 'rg16f' && tex.dims.length === 3;
  const target = is3d ? gl.TEXTURE_3D : gl.TEXTURE_2D;
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(target, gl.createTexture());
  if (tex.kind === 'png8') {
    const blob = await (await fetch(tex.url)).blob();
    const bmp = await createImageBitmap(blob, {
      premultiplyAlpha: 'none',
      colorSpaceConversion: 'none',
      imageOrientation: 'none',
    });
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, bmp);
  } else if (tex.kind === 'r16f') {
    if (typeof Float16Array !== 'function') return { error: 'no Float16Array' };
    const h = new Float16Array(tex.codes.map((c) => c / 65535));
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R16F, tex.width, tex.height, 0, gl.RED, gl.HALF_FLOAT,
      new Uint16Array(h.buffer));
  } else {
    const [nx, ny, nz = 1] = tex.dims;
    const buf = await (await fetch(tex.url)).arrayBuffer();
    if (buf.byteLength !== nx * ny * nz * 4) return { error: `size ${buf.byteLength}` };
    const dv = new DataView(buf);
    const half = new Uint16Array(buf.byteLength / 2);
    for (let i = 0; i < half.length; i++) half[i] = dv.getUint16(2 * i, true);
    if (is3d) {
      gl.texImage3D(gl.TEXTURE_3D, 0, gl.RG16F, nx, ny, nz, 0, gl.RG, gl.HALF_FLOAT, half);
      gl.texParameteri(target, gl.TEXTURE_WRAP_R, gl.CLAMP_TO_EDGE);
    } else {
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RG16F, nx, ny, 0, gl.RG, gl.HALF_FLOAT, half);
    }
  }
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(target, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(target, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  const data = new Float32Array(W * H * 4);
  points.forEach((p, k) => data.set([p[0], p[1], p[2] ?? 0, 0], 4 * k));
  gl.activeTexture(gl.TEXTURE1);
  gl.bindTexture(gl.TEXTURE_2D, gl.createTexture());
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, W, H, 0, gl.RGBA, gl.FLOAT, data);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  const vs = `#version 300 es
    void main() {
      vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID >> 1) * 4 - 1));
      gl_Position = vec4(p, 0.0, 1.0);
    }`;
  const sampler = is3d ? 'sampler3D' : 'sampler2D';
  const fs = `#version 300 es
    precision highp float;
    precision highp sampler2D;
    precision highp sampler3D;
    uniform ${sampler} u_lut;
    uniform sampler2D u_pts;
    out vec4 o;
    ${glsl}
    void main() {
      vec3 x = texelFetch(u_pts, ivec2(gl_FragCoord.xy), 0).xyz;
      o = vec4(${expr}, 0.0, 1.0);
    }`;
  const prog = gl.createProgram();
  for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) return { error: gl.getShaderInfoLog(s) };
    gl.attachShader(prog, s);
  }
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) return { error: gl.getProgramInfoLog(prog) };
  gl.useProgram(prog);
  gl.uniform1i(gl.getUniformLocation(prog, 'u_lut'), 0);
  gl.uniform1i(gl.getUniformLocation(prog, 'u_pts'), 1);
  const rt = gl.createTexture();
  gl.activeTexture(gl.TEXTURE2);
  gl.bindTexture(gl.TEXTURE_2D, rt);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, W, H, 0, gl.RGBA, gl.FLOAT, null);
  gl.bindFramebuffer(gl.FRAMEBUFFER, gl.createFramebuffer());
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, rt, 0);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) return { error: 'framebuffer' };
  gl.viewport(0, 0, W, H);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  const out = new Float32Array(W * H * 4);
  gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, out);
  return { err: gl.getError(), values: Array.from(out.slice(0, points.length * 4)), renderer: gl.getParameter(gl.RENDERER) };
}

// Opens a blank page of `server` in the browser's `context`, runs renderTexture(arg) in it
// and asserts that it ran without error (no GL error, no page error); returns its result.
export async function render(context, server, arg) {
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${server.url}/index.html`);
  const result = await page.evaluate(renderTexture, arg);
  await page.close();
  assert.equal(result.error, undefined, result.error);
  assert.equal(result.err, 0, 'GL error');
  assert.deepEqual(problems, []);
  return result;
}

// Serves `root` (`types` as for serve) and launches the browser before the calling test
// file's tests, closes both after them; returns render bound to them: draw(arg).
export function useBrowser(root, types) {
  const env = {};
  before(async () => {
    env.server = await serve(root, types);
    env.browser = await launch();
  });
  after(async () => {
    await env.browser?.close();
    await env.server?.close();
  });
  return (arg) => render(env.browser.context, env.server, arg);
}

// Asserts |gpu(k) - want(p)| <= bound(p) at every point p = rows[k]; logs the max error, the
// max of error / bound and the bound's median, 95th percentile and maximum; returns the
// maximum bound.
export function check(name, rows, gpu, want, bound, what) {
  let worst = 0;
  let ratio = 0;
  const bounds = [];
  rows.forEach((p, k) => {
    const e = Math.abs(gpu(k) - want(p));
    assert.ok(e <= bound(p), `${name} at ${p.slice(0, 3)}: GPU ${gpu(k)}, ${what} ${want(p)}, bound ${bound(p)}`);
    worst = Math.max(worst, e);
    ratio = Math.max(ratio, e / bound(p));
    bounds.push(bound(p));
  });
  bounds.sort((x, y) => x - y);
  const q = (f) => bounds[Math.min(bounds.length - 1, Math.floor(f * bounds.length))].toExponential(2);
  console.log(
    `${name}: ${rows.length} points, max |GPU - ${what}| ${worst.toExponential(3)}, ` +
      `max |err|/bound ${ratio.toFixed(3)}; bound median ${q(0.5)}, 95% ${q(0.95)}, max ${q(1)}`,
  );
  return bounds[bounds.length - 1];
}
