// WebGL2 test of the sheen and rough-glass engine textures (issue 23): the files and points
// written by `cargo xtask web` (tools/runners/src/web/prepare.rs, prepare_sheen and prepare_glass)
// into target/lut-engine-web/{sheen,glass}/ are uploaded to headless Chromium's WebGL2
// (SwiftShader) and sampled with texture() at 2,048 random points each; every expected
// value and bound comes from the Rust side.
//
// Sheen (64 x 64, texel centres, uv = (mu, r)): lut_charlie.png's B channel (8-bit, decoded
// by the browser and uploaded as the glTF Sample Viewer uploads it) and lut_sheen_E.png
// (16-bit: decoded here, webgl_lut.mjs, since browsers reduce 16-bit PNGs to 8 bits, and
// uploaded as R16F, code / 65535 rounded to binary16). The GPU value is compared with the
// converged sheen albedo at the point (brdf_lut::generate::sheen_e) within the bilinear
// error of the exact texels + half an encoding unit (+ half an f16 ulp for R16F) + the
// 8-bit filter weights x the texels' spread + f32; and with the bilinear value of the texels
// the Rust `png` crate decoded, within the last three terms only.
//
// Rough glass (12^3, (u, v, w) = (mu, r, (eta - lo)/(hi - lo))), both tables: light from
// outside (glass_e, eta in [1, 3]) and from inside (glass_e_inv, eta in [1/3, 1]): the KTX2's
// level 0 (R16G16_SFLOAT) as a TEXTURE_3D RG16F, compared with the f64 trilinear value of its
// binary16 texels within 3 axes x 2^-9 x spread + f32, and with the BLUT's
// GlassAlbedoTable::rt lookup within that bound plus the lookup's own f32 bound. Their
// averages over mu (glass_e_avg, glass_e_avg_inv: 12^2, (u, v) = (r, (eta - lo)/(hi - lo)))
// the same way as a TEXTURE_2D RG16F, bilinear, against GlassAverageTable::rt_avg.
//
// Edited copies of the shader expressions were each seen to fail here: lut_sheen_E sampled
// with u and v swapped, lut_charlie 0.1 texel off along mu, glass_e with v and w swapped or
// 0.05 texel off along eta, glass_e_avg with u and v swapped.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { check, decodePng, useBrowser } from '../webgl_lut.mjs';

const webDir = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const lutDir = path.resolve(webDir, '../../target/lut-engine-web');

const draw = useBrowser(lutDir, {
  '/sheen/lut_charlie.png': 'image/png',
  '/glass/glass_e.rg16f.bin': 'application/octet-stream',
  '/glass/glass_e_inv.rg16f.bin': 'application/octet-stream',
  '/glass/glass_e_avg.rg16f.bin': 'application/octet-stream',
  '/glass/glass_e_avg_inv.rg16f.bin': 'application/octet-stream',
  });

test('sheen textures lut_charlie.png (B, 8-bit) and lut_sheen_E.png (R16F) sampled in WebGL2', async () => {
  const dir = path.join(lutDir, 'sheen');
  const { n, points } = JSON.parse(await readFile(path.join(dir, 'sheen_points.json'), 'utf8'));
  assert.ok(points.length >= 2000, `${points.length} points`);
  const png = decodePng(await readFile(path.join(dir, 'lut_sheen_E.png')));
  assert.deepEqual([png.width, png.height, png.depth, png.channels], [n, n, 16, 3]);
  const codes = Array.from({ length: n * n }, (_, i) => png.samples[3 * i]);
  codes.forEach((c, i) => {
    assert.equal(png.samples[3 * i + 1], c, 'lut_sheen_E.png: R = G = B');
    assert.equal(png.samples[3 * i + 2], c, 'lut_sheen_E.png: R = G = B');
  });
  const xy = points.map((p) => [p[0], p[1]]);
  const ek = await draw({
    points: xy,
    tex: { kind: 'r16f', width: n, height: n, codes },
    expr: 'vec2(texture(u_lut, x.xy).r, 0.0)',
  });
  const ash = await draw({
    points: xy,
    tex: { kind: 'png8', url: '/sheen/lut_charlie.png' },
    expr: 'texture(u_lut, x.xy).bg',
  });
  console.log(`lut_sheen: ${n}x${n} on ${ek.renderer}`);
  // Row: [mu, r, E_ek, E_ash, bound_ek, bound_ash, S_ek, S_ash, b_ek, b_ash].
  const gEk = (k) => ek.values[4 * k];
  const gAsh = (k) => ash.values[4 * k];
  check('lut_sheen_E vs sheen_e', points, gEk, (p) => p[2], (p) => p[4], 'min(1, integral)');
  const tEk = check('lut_sheen_E vs table', points, gEk, (p) => p[6], (p) => p[8], 'bilinear of its texels');
  check('lut_charlie.b vs sheen_e', points, gAsh, (p) => p[3], (p) => p[5], 'min(1, integral)');
  const tAsh = check('lut_charlie.b vs table', points, gAsh, (p) => p[7], (p) => p[9], 'bilinear of its texels');
  // The bounds against the table are a small fraction of its values' range [0, 1]: the
  // weights' 2^-8 x spread (< 0.01 here) + half an f16 ulp.
  assert.ok(tEk < 0.01 && tAsh < 0.01, `bounds against the table ${tEk} ${tAsh}`);
  // G of lut_charlie.png is 0 (the viewer reads B only).
  points.forEach((_, k) => assert.equal(ash.values[4 * k + 1], 0));
});

for (const stem of ['glass_e', 'glass_e_inv', 'glass_e_avg', 'glass_e_avg_inv']) {
  const is3d = !stem.includes('avg');
  test(`rough glass ${stem} (${is3d ? '3-D' : '2-D'} RG16F) sampled with texture(${is3d ? 'sampler3D' : 'sampler2D'}) in WebGL2`, async () => {
    const dir = path.join(lutDir, 'glass');
    const { n, points } = JSON.parse(await readFile(path.join(dir, `${stem}_points.json`), 'utf8'));
    const d = n.length;
    assert.equal(d, is3d ? 3 : 2);
    assert.ok(points.length >= 2000, `${points.length} points`);
    const res = await draw({
      points: points.map((p) => p.slice(0, d)),
      tex: { kind: 'rg16f', url: `/glass/${stem}.rg16f.bin`, dims: n },
      expr: is3d ? 'texture(u_lut, x).rg' : 'texture(u_lut, x.xy).rg',
    });
    console.log(`${stem}: ${n.join('x')} on ${res.renderer}`);
    // Row: [coordinates (d), R, T, bound R, bound T, R_blut, T_blut, b_R, b_T].
    for (const c of [0, 1]) {
      const name = `${stem}.${'RT'[c]}`;
      const gpu = (k) => res.values[4 * k + c];
      const maxBound = check(`${name} vs table`, points, gpu, (p) => p[d + c], (p) => p[d + 2 + c], 'multilinear of its f16 texels');
      check(`${name} vs BLUT lookup`, points, gpu, (p) => p[d + 4 + c], (p) => p[d + 2 + c] + p[d + 6 + c], 'the typed BLUT lookup');
      // Not vacuous: the values span [0, 1]; the bound is d x 2^-9 x the local spread + 1e-6.
      assert.ok(maxBound < 0.01, `${name}: max bound ${maxBound}`);
    }
  });
}
