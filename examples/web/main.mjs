// The web example: loads the brdf-wasm module and draws with its kernels.
//
// * Fig. 6 of the paper: Blinn's, the modified and Smith's G against θr at θi = 30°, σ = 0.3
//   (brdf_g_batch over 181 angles per curve).
// * The same modified G looked up in the default table over σ (assets/g_modified.blut),
//   drawn as dots on the curve.
// * A lit sphere for the model picked from the list, one slider per parameter
//   (brdf_render_sphere: the module shades every pixel; this script only copies the RGBA
//   bytes into an ImageData).
//
// window.brdfPage exposes what the browser test reads: `ready` (a promise), the curves, the
// parameters last rendered and the status.

import { loadBrdf, G, LUT } from '../../crates/brdf-wasm/js/brdf.mjs';

const WASM_URL = new URL('../../crates/brdf-wasm/pkg/brdf_wasm.wasm', import.meta.url);
// The default LUT assets, one per slot of the module.
const LUT_FILES = [
  [LUT.G_MODIFIED, 'g_modified.blut'],
  [LUT.G_FIXED_SIGMA, 'g_modified_sigma0.3.blut'],
  [LUT.DFG, 'dfg_ggx.blut'],
];
// Labels of the integer-choice parameters.
const CHOICES = {
  g: ['none', 'Blinn', 'Smith sep.', 'Smith corr.', 'modified', 'mod. printed'],
  smith: ['separable', 'correlated'],
  k: ['conserving', 'printed'],
  highlight: ['Phong', 'Blinn-Phong'],
};

const page = { curves: null, model: null, params: null, status: '' };
window.brdfPage = page;

function setStatus(text, error = false) {
  const el = document.getElementById('status');
  el.textContent = text;
  el.classList.toggle('error', error);
  page.status = text;
}

/** Fig. 6 curves: θr = −90°…90° in 1° steps. */
function computeCurves(brdf) {
  const sigma = 0.3;
  const thetaI = (30 * Math.PI) / 180;
  const deg = Array.from({ length: 181 }, (_, k) => k - 90);
  const tr = new Float32Array(deg.map((d) => (d * Math.PI) / 180));
  const ti = new Float32Array(tr.length).fill(thetaI);
  return {
    deg,
    blinn: brdf.gBatch(G.BLINN, sigma, ti, tr),
    modified: brdf.gBatch(G.MODIFIED, sigma, ti, tr),
    smith: brdf.gBatch(G.SMITH_SEPARABLE, sigma, ti, tr),
    modified_lut: brdf.gLutBatch(sigma, ti, tr),
  };
}

function drawFig6(canvas, curves) {
  const ctx = canvas.getContext('2d');
  const W = canvas.width;
  const H = canvas.height;
  const m = { l: 48, r: 16, t: 16, b: 40 };
  const x = (d) => m.l + ((d + 90) / 180) * (W - m.l - m.r);
  const y = (g) => H - m.b - g * (H - m.t - m.b);
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, W, H);
  ctx.strokeStyle = '#ddd';
  ctx.fillStyle = '#444';
  ctx.font = '12px sans-serif';
  ctx.lineWidth = 1;
  for (let d = -90; d <= 90; d += 30) {
    ctx.beginPath();
    ctx.moveTo(x(d), y(0));
    ctx.lineTo(x(d), y(1));
    ctx.stroke();
    ctx.textAlign = 'center';
    ctx.fillText(`${d}°`, x(d), H - m.b + 16);
  }
  for (let g = 0; g <= 1.0001; g += 0.2) {
    ctx.beginPath();
    ctx.moveTo(x(-90), y(g));
    ctx.lineTo(x(90), y(g));
    ctx.stroke();
    ctx.textAlign = 'right';
    ctx.fillText(g.toFixed(1), m.l - 6, y(g) + 4);
  }
  ctx.textAlign = 'center';
  ctx.fillText('θr (signed; θr = θi is the mirror direction)', (m.l + W - m.r) / 2, H - 6);
  ctx.save();
  ctx.translate(14, (m.t + H - m.b) / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.fillText('G', 0, 0);
  ctx.restore();
  const series = [
    ['Blinn (eq 4)', curves.blinn, '#d9822b', []],
    ['modified (eqs 6–13)', curves.modified, '#1f5fbf', []],
    ['Smith–Beckmann', curves.smith, '#2e9b4f', [6, 4]],
  ];
  // Legend in the empty lower middle of the plot.
  const lx = x(-45);
  const ly = (k) => y(0.62) + 18 * k;
  // The table's values every 5°, as dots (under the lines).
  ctx.fillStyle = '#0b2f6b';
  curves.deg.forEach((d, i) => {
    if (d % 5 === 0) {
      ctx.beginPath();
      ctx.arc(x(d), y(curves.modified_lut[i]), 2.5, 0, 2 * Math.PI);
      ctx.fill();
    }
  });
  ctx.beginPath();
  ctx.arc(lx + 14, ly(3), 2.5, 0, 2 * Math.PI);
  ctx.fill();
  ctx.fillStyle = '#222';
  ctx.textAlign = 'left';
  ctx.fillText('modified, from g_modified.blut (LUT)', lx + 34, ly(3) + 4);
  series.forEach(([name, vals, color, dash], k) => {
    ctx.strokeStyle = color;
    ctx.lineWidth = 2;
    ctx.setLineDash(dash);
    ctx.beginPath();
    curves.deg.forEach((d, i) => (i ? ctx.lineTo(x(d), y(vals[i])) : ctx.moveTo(x(d), y(vals[i]))));
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(lx, ly(k));
    ctx.lineTo(lx + 28, ly(k));
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = '#222';
    ctx.textAlign = 'left';
    ctx.fillText(name, lx + 34, ly(k) + 4);
  });
}

/** A slider's value rounded to its step's decimals (the browser's stepping computes
 * min + k·step in binary, e.g. 0.29999999999999993 for 0.3). */
function sliderValue(input) {
  const decimals = (input.step.split('.')[1] ?? '').length;
  return Number(Number(input.value).toFixed(decimals));
}

function buildControls(brdf, onChange) {
  const select = document.getElementById('model');
  for (const m of brdf.models) select.add(new Option(m.name, m.name));
  const controls = document.getElementById('controls');
  const show = () => {
    const model = brdf.models[brdf.modelId(select.value)];
    controls.replaceChildren();
    for (const p of model.params) {
      const label = document.createElement('label');
      const input = Object.assign(document.createElement('input'), {
        type: 'range',
        min: p.min,
        max: p.max,
        step: p.step,
        value: p.default,
        name: p.name,
      });
      const out = document.createElement('output');
      const text = () =>
        (out.textContent = CHOICES[p.name]?.[sliderValue(input)] ?? sliderValue(input));
      input.addEventListener('input', () => (text(), onChange()));
      text();
      label.append(p.name, input, out);
      controls.append(label);
    }
    onChange();
  };
  select.addEventListener('change', show);
  show();
}

function renderSphere(brdf) {
  const canvas = document.getElementById('sphere');
  const name = document.getElementById('model').value;
  const id = brdf.modelId(name);
  const params = brdf.models[id].params.map(
    (p) => sliderValue(document.querySelector(`#controls input[name="${p.name}"]`)),
  );
  const rgba = brdf.renderSphere(id, params, canvas.width);
  canvas.getContext('2d').putImageData(new ImageData(rgba, canvas.width, canvas.height), 0, 0);
  page.model = name;
  page.params = Array.from(Float32Array.from(params));
}

async function loadLuts(brdf) {
  const info = [];
  for (const [slot, file] of LUT_FILES) {
    const res = await fetch(new URL(`../../assets/${file}`, import.meta.url));
    if (!res.ok) throw new Error(`${file}: HTTP ${res.status}`);
    const bytes = new Uint8Array(await res.arrayBuffer());
    brdf.loadLut(slot, bytes);
    info.push(`${file} (${(bytes.length / 1024).toFixed(1)} KiB)`);
  }
  return info;
}

async function main() {
  const brdf = await loadBrdf(WASM_URL);
  const luts = await loadLuts(brdf);
  page.curves = computeCurves(brdf);
  drawFig6(document.getElementById('fig6'), page.curves);
  buildControls(brdf, () => renderSphere(brdf));
  const [a, b] = brdf.dfg(0.5, 0.5);
  const deg = Math.PI / 180;
  setStatus(
    `module: ${brdf.models.length} models; LUTs: ${luts.join(', ')}\n` +
      `G(30°, 60°; σ = ${brdf.gLutFixedSigma().toFixed(1)}) from the one-σ table: ${brdf.gLutFixed(30 * deg, 60 * deg).toFixed(5)}` +
      ` (direct ${brdf.g(G.MODIFIED, 0.3, 30 * deg, 60 * deg).toFixed(5)}); DFG(μ = 0.5, r = 0.5) = (${a.toFixed(4)}, ${b.toFixed(4)})`,
  );
}

page.ready = main().catch((err) => {
  setStatus(`error: ${err.message}`, true);
  console.error(err);
  throw err;
});
