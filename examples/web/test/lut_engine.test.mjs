// WebGL2 test of an engine LUT: the khronos table written by `cargo xtask lut engine`
// (target/lut-engine-web/, prepared by `cargo xtask web`) is decoded by Chromium's own PNG
// decoder, uploaded as the glTF Sample Viewer uploads it (RGBA8, no vertical flip, no colour
// conversion, no premultiplication, LINEAR + CLAMP_TO_EDGE) and sampled by a fragment shader
// that calls the emitted GLSL function `dfg_khronos` verbatim at 2,048 random (mu, r). The
// values read back (RGBA32F render target) are compared with the f64 integral: the bound per
// point (points.json) is the bilinear interpolation error of exact texel values + half an
// 8-bit unit + the GPU's 8-bit fixed-point filter weights + f32 arithmetic.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const webDir = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const lutDir = path.resolve(webDir, '../../target/lut-engine-web');
const FILES = {
  '/lut_ggx.png': 'image/png',
  '/lut_ggx.glsl': 'text/plain; charset=utf-8',
  '/points.json': 'application/json',
  '/index.html': 'text/html; charset=utf-8',
};

let server;
let baseUrl;
let context;
let userDataDir;

before(async () => {
  server = http.createServer((req, res) => {
    const p = new URL(req.url, 'http://127.0.0.1').pathname;
    if (req.method !== 'GET' || !(p in FILES)) {
      res.writeHead(404).end();
      return;
    }
    if (p === '/index.html') {
      res.writeHead(200, { 'content-type': FILES[p] }).end('<!doctype html><title>lut</title>');
      return;
    }
    readFile(path.join(lutDir, p.slice(1))).then(
      (body) => res.writeHead(200, { 'content-type': FILES[p] }).end(body),
      () => res.writeHead(404).end(),
    );
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  baseUrl = `http://127.0.0.1:${server.address().port}`;
  userDataDir = await mkdtemp(path.join(tmpdir(), 'brdf-lut-chromium-'));
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: '/usr/bin/chromium',
    headless: true,
    args: ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
});

after(async () => {
  await context?.close();
  await new Promise((ok) => (server ? server.close(ok) : ok()));
  if (userDataDir) await rm(userDataDir, { recursive: true, force: true });
});

test('khronos lut_ggx.png sampled by the emitted GLSL in a WebGL2 shader', async () => {
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${baseUrl}/index.html`);
  const result = await page.evaluate(async () => {
    const pts = (await (await fetch('/points.json')).json()).points;
    const fn = await (await fetch('/lut_ggx.glsl')).text();
    const blob = await (await fetch('/lut_ggx.png')).blob();
    const bmp = await createImageBitmap(blob, {
      premultiplyAlpha: 'none',
      colorSpaceConversion: 'none',
      imageOrientation: 'none',
    });
    const W = 64;
    const H = Math.ceil(pts.length / W);
    const canvas = document.createElement('canvas');
    canvas.width = W;
    canvas.height = H;
    const gl = canvas.getContext('webgl2');
    if (!gl) return { error: 'no WebGL2' };
    if (!gl.getExtension('EXT_color_buffer_float')) return { error: 'no EXT_color_buffer_float' };
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    const lut = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, lut);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, bmp);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    // The points (mu, r) as an RG32F texture read with texelFetch.
    const data = new Float32Array(W * H * 2);
    pts.forEach((p, k) => {
      data[2 * k] = p[0];
      data[2 * k + 1] = p[1];
    });
    const ptex = gl.createTexture();
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, ptex);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RG32F, W, H, 0, gl.RG, gl.FLOAT, data);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const vs = `#version 300 es
      void main() {
        vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID >> 1) * 4 - 1));
        gl_Position = vec4(p, 0.0, 1.0);
      }`;
    const fs = `#version 300 es
      precision highp float;
      precision highp sampler2D;
      uniform sampler2D u_lut;
      uniform sampler2D u_pts;
      out vec4 o;
      ${fn}
      void main() {
        vec2 x = texelFetch(u_pts, ivec2(gl_FragCoord.xy), 0).xy;
        o = vec4(dfg_khronos(u_lut, x.x, x.y), 0.0, 1.0);
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
    const fb = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, rt, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) return { error: 'framebuffer' };
    gl.viewport(0, 0, W, H);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    const out = new Float32Array(W * H * 4);
    gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, out);
    const err = gl.getError();
    return { err, values: Array.from(out.slice(0, pts.length * 4)), renderer: gl.getParameter(gl.RENDERER) };
  });
  assert.equal(result.error, undefined, result.error);
  assert.equal(result.err, 0, 'GL error');
  const pts = JSON.parse(await readFile(path.join(lutDir, 'points.json'), 'utf8')).points;
  let worst = 0;
  pts.forEach(([mu, r, a, b, ba, bb], k) => {
    const ga = result.values[4 * k];
    const gb = result.values[4 * k + 1];
    assert.ok(Math.abs(ga - a) <= ba, `A at mu ${mu} r ${r}: GPU ${ga}, integral ${a}, bound ${ba}`);
    assert.ok(Math.abs(gb - b) <= bb, `B at mu ${mu} r ${r}: GPU ${gb}, integral ${b}, bound ${bb}`);
    worst = Math.max(worst, Math.abs(ga - a), Math.abs(gb - b));
  });
  console.log(`lut_engine: ${pts.length} points on ${result.renderer}, max |GPU - integral| ${worst.toExponential(3)}`);
  await page.close();
  assert.deepEqual(problems, []);
});
