// WebGL2 test of an engine LUT: the khronos table written by `cargo xtask lut engine`
// (target/lut-engine-web/, prepared by `cargo xtask web`) is decoded by Chromium's own PNG
// decoder, uploaded as the glTF Sample Viewer uploads it (RGBA8, no vertical flip, no colour
// conversion, no premultiplication, LINEAR + CLAMP_TO_EDGE) and sampled by a fragment shader
// that calls the emitted GLSL function `dfg_khronos` verbatim at 2,048 random (mu, r). The
// values read back (RGBA32F render target) are compared with the f64 integral: the bound per
// point (points.json) is the bilinear interpolation error of exact texel values + half an
// 8-bit unit + the GPU's 8-bit fixed-point filter weights + f32 arithmetic.
//
// The second test does the same for a native export: `lut export --raw-f16` of
// assets/dfg_ggx.blut (target/lut-engine-web/native/), uploaded as its sidecar says (width =
// axis 0 count, height = axis 1 count, first data row at v = 0, RG16F: half floats filter
// linearly in core WebGL2) and sampled by the function the exporter emitted, named by the
// sidecar, called verbatim, at 2,048 random (mu, r), 5 % of them outside the axis ranges (the
// function clamps). The bound per point (native_points.json, tools/runners/src/web/prepare.rs) is the
// bilinear error in the sidecar's warped coordinates (log mu, r) of texels holding the exact
// integral at their nodes + the texel encoding (half a unorm16 unit of the .blut + half an f16
// ulp) + the GPU's 8-bit filter weights + f32 arithmetic.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { check, useBrowser } from '../webgl_lut.mjs';

const webDir = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const lutDir = path.resolve(webDir, '../../target/lut-engine-web');

const draw = useBrowser(lutDir, {
  '/lut_ggx.png': 'image/png',
  '/native/dfg_ggx.f16.bin': 'application/octet-stream',
});

// The (A, B) a GLSL function `call(u_lut, mu, r)` from the file `glsl` returns at every row's
// (mu, r) with the texture `tex` bound: renderTexture of webgl_lut.mjs.
async function sample(rows, glsl, call, tex) {
  return draw({
    points: rows.map((p) => [p[0], p[1]]),
    tex,
    glsl: await readFile(glsl, 'utf8'),
    expr: `${call}(u_lut, x.x, x.y)`,
  });
}

test('khronos lut_ggx.png sampled by the emitted GLSL in a WebGL2 shader', async () => {
  const pts = JSON.parse(await readFile(path.join(lutDir, 'points.json'), 'utf8')).points;
  const result = await sample(pts, path.join(lutDir, 'lut_ggx.glsl'), 'dfg_khronos', {
    kind: 'png8',
    url: '/lut_ggx.png',
  });
  console.log(`lut_engine: ${pts.length} points on ${result.renderer}`);
  // Row: [mu, r, A, B, bound A, bound B].
  for (const c of [0, 1]) {
    const gpu = (k) => result.values[4 * k + c];
    check(`lut_ggx.${'AB'[c]}`, pts, gpu, (p) => p[2 + c], (p) => p[4 + c], 'integral');
  }
});

test('native export dfg_ggx.f16.bin sampled by its emitted GLSL in a WebGL2 shader', async () => {
  const dir = path.join(lutDir, 'native');
  const side = JSON.parse(await readFile(path.join(dir, 'dfg_ggx.f16.bin.json'), 'utf8'));
  // What the sidecar promises, and this upload relies on.
  assert.equal(side.format, 'raw-f16');
  assert.equal(side.byte_order, 'little-endian');
  assert.deepEqual(side.channels, ['A', 'B']);
  assert.equal(side.shaders.glsl, 'dfg_ggx.f16.bin.glsl');
  assert.match(side.shaders.signature_glsl, /^vec2 \w+\(sampler2D lut, float p0, float p1\)$/);
  const [m0, m1] = side.inverse_mapping;
  const pts = JSON.parse(await readFile(path.join(dir, 'native_points.json'), 'utf8')).points;
  assert.ok(pts.length >= 2000, `${pts.length} points`);
  const result = await sample(pts, path.join(dir, side.shaders.glsl), side.shaders.function, {
    kind: 'rg16f',
    url: '/native/dfg_ggx.f16.bin',
    dims: [m0.count, m1.count],
  });
  // Row: [mu, r, A, B, bound A, bound B, A_lin, B_lin].
  let maxBound = 0;
  for (const c of [0, 1]) {
    const name = `dfg_ggx.f16.${'AB'[c]}`;
    const gpu = (k) => result.values[4 * k + c];
    maxBound = Math.max(maxBound, check(name, pts, gpu, (p) => p[2 + c], (p) => p[4 + c], 'integral'));
    // Reported only: the GPU against bilinear sampling of exact texels, over the bound's
    // non-interpolation part (texel encoding, filter weights, f32).
    let worstLin = 0;
    let ratioLin = 0;
    pts.forEach((p, k) => {
      const e = Math.abs(gpu(k) - p[6 + c]);
      worstLin = Math.max(worstLin, e);
      ratioLin = Math.max(ratioLin, e / (p[4 + c] - Math.abs(p[6 + c] - p[2 + c])));
    });
    console.log(
      `${name}: max |GPU - bilinear of exact texels| ${worstLin.toExponential(3)}, ` +
        `over the non-interpolation bound ${ratioLin.toFixed(3)}`,
    );
  }
  // The bounds are not vacuous: the largest is the bilinear error of the 64 x 64 nodes in
  // (log mu, r) near grazing mu (1.6e-3 measured; the table was built for Catmull-Rom, whose
  // error is 1.9e-4) plus half an f16 ulp (<= 2.5e-4 for values below 1). Edited copies of
  // the GLSL sampling 0.1 texel off along mu, half a texel off (texel-centre placement),
  // without the log warp, with u and v swapped or with v flipped were each seen to fail here
  // (the first failing point 1.8x, 6x, 430x, 30x and 970x over its bound).
  assert.ok(maxBound < 4e-3, `max bound ${maxBound}`);
});
