// brdf.mjs: a small ES-module wrapper around the brdf-wasm module (plain C-ABI exports,
// no wasm-bindgen). Works in browsers and in Node ≥ 18; no dependencies.
//
// Example (Node; in a browser pass a URL such as new URL('brdf_wasm.wasm', import.meta.url)):
//
//   import { loadBrdf, G, LUT } from './brdf.mjs';
//   import { readFile } from 'node:fs/promises';
//   const brdf = await loadBrdf(new URL('../pkg/brdf_wasm.wasm', import.meta.url));
//   const deg = Math.PI / 180;
//   brdf.g(G.MODIFIED, 0.3, 30 * deg, 60 * deg);          // the paper's G, ≈ 0.9963
//   brdf.gBatch(G.SMITH_SEPARABLE, 0.3,                     // many angles at once
//               new Float32Array([0.5, 0.5]), new Float32Array([-0.2, 1.0]));
//   const ts = brdf.modelId('torrance-sparrow');
//   const p = brdf.defaults(ts);                            // [sigma, g, r0, ks, albedo]
//   brdf.eval(ts, p, [0, 0.6, 0.8], [0, -0.6, 0.8]);         // [r, g, b] in 1/sr
//   const rgba = brdf.renderSphere(ts, p, 128);             // Uint8ClampedArray, 128×128×4
//   brdf.loadLut(LUT.G_MODIFIED, await readFile('assets/g_modified.blut'));
//   brdf.gLut(0.3, 30 * deg, 60 * deg);                     // the same G from the table
//   brdf.loadLut(LUT.DFG, await readFile('assets/dfg_ggx.blut'));
//   brdf.dfg(0.5, 0.5);                                     // [A, B]
//
// Angles are radians; directions are unit vectors in the local shading frame (z = normal,
// x = tangent), pointing away from the surface. Scalar functions return NaN for invalid
// parameters; array functions throw a BrdfError carrying the module's status code.

/** G kinds (the `kind` argument): the order of brdf_core::models::GeometricTerm::ALL. */
export const G = Object.freeze({
  NONE: 0,
  BLINN: 1,
  SMITH_SEPARABLE: 2,
  SMITH_CORRELATED: 3,
  MODIFIED: 4,
  MODIFIED_PRINTED: 5,
});

/** Status codes returned by the module's array and loading exports. */
export const STATUS = Object.freeze({
  OK: 0,
  BAD_PARAM: -1,
  BAD_BUFFER: -2,
  BAD_LUT: -3,
  NO_LUT: -4,
});

/** LUT slots of the module and the default asset of each (paths relative to the repository). */
export const LUT = Object.freeze({
  G_MODIFIED: 0, // modified G over σ, assets/g_modified.blut
  G_FIXED_SIGMA: 1, // modified G for one σ, assets/g_modified_sigma0.3.blut
  DFG: 2, // split-sum (A, B), assets/dfg_ggx.blut
});

/** Reasons reported by brdf_lut_error after a failed load. */
export const LUT_ERRORS = Object.freeze([
  'none', 'truncated', 'bad magic', 'unsupported version', 'malformed header',
  'inconsistent header', 'wrong payload length', 'checksum mismatch', 'wrong table kind for the slot', 'other',
]);

const STATUS_NAMES = Object.fromEntries(Object.entries(STATUS).map(([k, v]) => [v, k]));

/** An error status from the module. */
export class BrdfError extends Error {
  constructor(fn, status) {
    super(`${fn}: ${STATUS_NAMES[status] ?? 'status'} (${status})`);
    this.status = status;
  }
}

async function toBytesOrModule(source) {
  if (source instanceof WebAssembly.Module) return source;
  if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return source;
  if (typeof Response !== 'undefined' && source instanceof Response) {
    return new Uint8Array(await source.arrayBuffer());
  }
  const url = source instanceof URL ? source : new URL(String(source), globalThis.location?.href);
  if (url.protocol === 'file:') {
    const { readFile } = await import('node:fs/promises');
    return readFile(url);
  }
  const res = await fetch(url);
  if (!res.ok) throw new Error(`fetching ${url}: HTTP ${res.status}`);
  return new Uint8Array(await res.arrayBuffer());
}

/**
 * Loads the module. `source`: a URL (string or URL; file: URLs are read with node:fs),
 * a Response, bytes (ArrayBuffer / typed array) or a compiled WebAssembly.Module.
 * @returns {Promise<Brdf>}
 */
export async function loadBrdf(source) {
  const src = await toBytesOrModule(source);
  const instance =
    src instanceof WebAssembly.Module
      ? await WebAssembly.instantiate(src, {})
      : (await WebAssembly.instantiate(src, {})).instance;
  return new Brdf(instance);
}

/** The loaded module. `exports` gives the raw C-ABI functions. */
export class Brdf {
  constructor(instance) {
    this.exports = instance.exports;
    const e = this.exports;
    this.scratch = e.brdf_scratch_ptr();
    this.scratchLen = e.brdf_scratch_len();
    /** [{id, name, params: [{name, min, max, default, step}]}] */
    this.models = [];
    for (let id = 0; id < e.brdf_model_count(); id++) {
      const params = [];
      for (let k = 0; k < e.brdf_model_param_count(id); k++) {
        // f32 in the module; the table's values are short decimals, so 6 digits restore them
        // (0.01f32 → 0.01 rather than 0.009999999776482582).
        const f = (i) => Number(e.brdf_model_param(id, k, i).toPrecision(6));
        params.push({ name: this.#str(id, k), min: f(0), max: f(1), default: f(2), step: f(3) });
      }
      this.models.push({ id, name: this.#str(id, 0xffffffff), params });
    }
  }

  #str(id, k) {
    const p = this.exports.brdf_model_str_ptr(id, k);
    const n = this.exports.brdf_model_str_len(id, k);
    return new TextDecoder().decode(new Uint8Array(this.exports.memory.buffer, p, n));
  }

  #f32(byteOffset, n) {
    return new Float32Array(this.exports.memory.buffer, this.scratch + byteOffset, n);
  }

  /** The id of the model called `name` (throws when unknown). */
  modelId(name) {
    const m = this.models.find((m) => m.name === name);
    if (!m) throw new Error(`unknown model ${name}`);
    return m.id;
  }

  /** The default parameters of model `id`, in order. */
  defaults(id) {
    return this.models[id].params.map((p) => p.default);
  }

  /** G of `kind` at in-plane angles θi ∈ [0, π/2], θr ∈ [−π/2, π/2] (signed), RMS slope σ. */
  g(kind, sigma, thetaI, thetaR) {
    return this.exports.brdf_g(kind, sigma, thetaI, thetaR);
  }

  /** G of `kind` from the dot products n·wi, n·wo, wi·wo. */
  gDots(kind, sigma, nI, nO, iO) {
    return this.exports.brdf_g_dots(kind, sigma, nI, nO, iO);
  }

  /** The Torrance–Sparrow BRDF (shader form) with G of `gKind` and Schlick F(R0). */
  torranceSparrow(sigma, gKind, r0, ks, albedo, nI, nO, iO) {
    return this.exports.brdf_torrance_sparrow(sigma, gKind, r0, ks, albedo, nI, nO, iO);
  }

  /** The same with n·h = normalize(wi + wo)·n as well: exact for near-mirror pairs at the horizon. */
  torranceSparrowNh(sigma, gKind, r0, ks, albedo, nI, nO, iO, nH) {
    return this.exports.brdf_torrance_sparrow_nh(sigma, gKind, r0, ks, albedo, nI, nO, iO, nH);
  }

  // Runs `call(inOff, outOff, count)` over chunks that fit in the scratch buffer: `inWidth`
  // f32 per row in, `outWidth` out, inputs copied from `inputs` (array of [Float32Array,
  // width] column groups), results copied into a new Float32Array.
  #chunked(fn, n, inputs, outWidth, reserved, call) {
    const inWidth = inputs.reduce((a, [, w]) => a + w, 0);
    const per = 4 * (inWidth + outWidth);
    const rows = Math.max(1, Math.floor((this.scratchLen - reserved) / per) - 4);
    const out = new Float32Array(n * outWidth);
    for (let start = 0; start < n; start += rows) {
      const count = Math.min(rows, n - start);
      let off = reserved;
      const offs = [];
      for (const [arr, w] of inputs) {
        this.#f32(off, count * w).set(arr.subarray(start * w, (start + count) * w));
        offs.push(off);
        off += 16 * Math.ceil((4 * count * w) / 16);
      }
      const s = call(offs, off, count);
      if (s < 0) throw new BrdfError(fn, s);
      out.set(this.#f32(off, count * outWidth), start * outWidth);
    }
    return out;
  }

  /** G of `kind` for arrays of in-plane angles (one σ). Returns a Float32Array. */
  gBatch(kind, sigma, thetaI, thetaR) {
    const ti = Float32Array.from(thetaI);
    const tr = Float32Array.from(thetaR);
    if (ti.length !== tr.length) throw new Error('gBatch: arrays differ in length');
    return this.#chunked('brdf_g_batch', ti.length, [[ti, 1], [tr, 1]], 1, 0, ([a, b], o, n) =>
      this.exports.brdf_g_batch(kind, sigma, this.scratch + a, this.scratch + b, this.scratch + o, n),
    );
  }

  /** G of `kind` from (n·wi, n·wo, wi·wo) triples, flat Float32Array of length 3n. */
  gDotsBatch(kind, sigma, dots) {
    const d = Float32Array.from(dots);
    return this.#chunked('brdf_g_dots_batch', d.length / 3, [[d, 3]], 1, 0, ([a], o, n) =>
      this.exports.brdf_g_dots_batch(kind, sigma, this.scratch + a, this.scratch + o, n),
    );
  }

  #params(id, params) {
    const want = this.models[id]?.params.length ?? 0;
    const p = this.#f32(0, 16);
    p.fill(0);
    p.set(Float32Array.from(params).subarray(0, Math.min(16, want)));
    if (params.length < want) p.fill(NaN, params.length, want); // rejected by the module
    return 64; // bytes reserved for the parameters at the start of the scratch buffer
  }

  /** f(wi, wo) of model `id` as [r, g, b] in 1/sr (NaNs for bad parameters). */
  eval(id, params, wi, wo) {
    const reserved = this.#params(id, params);
    const out = this.scratch + reserved;
    const s = this.exports.brdf_eval(id, this.scratch, out, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]);
    if (s < 0) return [NaN, NaN, NaN];
    return Array.from(this.#f32(reserved, 3));
  }

  /** Model `id` over rows (wi_x, wi_y, wi_z, wo_x, wo_y, wo_z): Float32Array of (r, g, b) rows. */
  evalBatch(id, params, dirs) {
    const d = Float32Array.from(dirs);
    const reserved = this.#params(id, params);
    return this.#chunked('brdf_eval_batch', d.length / 6, [[d, 6]], 3, reserved, ([a], o, n) =>
      this.exports.brdf_eval_batch(id, this.scratch, this.scratch + a, this.scratch + o, n),
    );
  }

  /**
   * Copies a LUT file's bytes into slot `slot` (see LUT) and validates them. Throws a
   * BrdfError (with `reason` from LUT_ERRORS) when the module rejects them.
   */
  loadLut(slot, bytes) {
    const b = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes.buffer ?? bytes, bytes.byteOffset ?? 0, bytes.byteLength);
    const cap = this.exports.brdf_lut_capacity(slot);
    if (b.length <= cap) {
      new Uint8Array(this.exports.memory.buffer, this.exports.brdf_lut_ptr(slot), b.length).set(b);
    }
    const s = this.exports.brdf_lut_load(slot, b.length);
    if (s < 0) {
      const err = new BrdfError('brdf_lut_load', s);
      err.reason = s === STATUS.BAD_LUT ? LUT_ERRORS[this.exports.brdf_lut_error()] : 'too large or bad slot';
      err.message += `: ${err.reason}`;
      throw err;
    }
  }

  /** The modified G from the table over σ (slot 0); NaN without a table. */
  gLut(sigma, thetaI, thetaR) {
    return this.exports.brdf_g_lut(sigma, thetaI, thetaR);
  }

  /** Batch gLut for one σ. */
  gLutBatch(sigma, thetaI, thetaR) {
    const ti = Float32Array.from(thetaI);
    const tr = Float32Array.from(thetaR);
    return this.#chunked('brdf_g_lut_batch', ti.length, [[ti, 1], [tr, 1]], 1, 0, ([a, b], o, n) =>
      this.exports.brdf_g_lut_batch(sigma, this.scratch + a, this.scratch + b, this.scratch + o, n),
    );
  }

  /** The modified G from the one-σ table (slot 1); its σ is gLutFixedSigma(). */
  gLutFixed(thetaI, thetaR) {
    return this.exports.brdf_g_lut_fixed(thetaI, thetaR);
  }

  gLutFixedSigma() {
    return this.exports.brdf_g_lut_fixed_sigma();
  }

  /** Split-sum [A, B] at μ = n·v and roughness from slot 2 ([NaN, NaN] without a table). */
  dfg(mu, roughness) {
    const s = this.exports.brdf_dfg(mu, roughness, this.scratch);
    return s < 0 ? [NaN, NaN] : Array.from(this.#f32(0, 2));
  }

  /** Batch dfg: Float32Array of (A, B) pairs. */
  dfgBatch(mu, roughness) {
    const m = Float32Array.from(mu);
    const r = Float32Array.from(roughness);
    return this.#chunked('brdf_dfg_batch', m.length, [[m, 1], [r, 1]], 2, 0, ([a, b], o, n) =>
      this.exports.brdf_dfg_batch(this.scratch + a, this.scratch + b, this.scratch + o, n),
    );
  }

  /** The lit sphere of model `id` (see render.rs): a new Uint8ClampedArray, size² RGBA. */
  renderSphere(id, params, size) {
    const reserved = this.#params(id, params);
    const s = this.exports.brdf_render_sphere(id, this.scratch, size, this.scratch + reserved);
    if (s < 0) throw new BrdfError('brdf_render_sphere', s);
    const px = new Uint8ClampedArray(this.exports.memory.buffer, this.scratch + reserved, size * size * 4);
    return new Uint8ClampedArray(px);
  }
}
