#!/usr/bin/env python3
"""The Monte Carlo peer of the converged split-sum generator: the GGX DFG table (A, B) made
the way the engines' own tools make it (Karis 2013, "Real Shading in Unreal Engine 4",
the IntegrateBRDF listing; Filament's cmgen and the Khronos sampler do the same), with
numpy, vectorised over texels.

Per texel (mu = n.v, perceptual roughness r, alpha = r^2) and for the k-th point of the
2-D Hammersley set of n samples, (k/n, radical inverse of k in base 2):
  half vector from D(h) cos(theta_h):  cos^2(theta_h) = (1 - u) / (1 + (alpha^2 - 1) u),
                                        phi = 2 pi u2
  l = 2 (v.h) h - v;  if n.l > 0:
  weight = G2 (v.h) / (mu n.h),  G2 = 1 / (1 + Lambda(l) + Lambda(v))  (height-correlated
           Smith, Lambda(w) = (sqrt(1 + alpha^2 tan^2 theta_w) - 1) / 2)
  A += weight (1 - Fc),  B += weight Fc,  Fc = (1 - v.h)^5;  A, B divided by n.

Texel centres of a size x size table: mu = (i + 0.5)/size, r = (j + 0.5)/size (the Khronos
lut_ggx.png axes: x = n.v, y = roughness).

Usage: dfg_mc_peer.py [--size 1024] [--samples 1024] [--chunk 4] [--stride 1]
                      [--reference converged.f64]
`--stride s` computes the roughness rows j = 0, s, 2s, ... only. The reference file is the
converged table of the same rows as raw little-endian f64, row-major
[r row][mu column i][A, B] (what `cargo run --release -p brdf-bench --example
dfg_converged -- --out FILE` writes). Prints one JSON object: the wall time per texel in
microseconds (texels computed in chunks of `--chunk` roughness rows, the timer around the
whole table), and with a reference the max and median |error| over both channels, overall
and on the four grazing columns (mu < 4/size).
"""

import argparse
import json
import sys
import time

try:
    import numpy as np
except ImportError:  # pragma: no cover - machines without numpy
    print("numpy is not importable; install it with `pip install numpy`", file=sys.stderr)
    sys.exit(3)


def hammersley(n):
    """The 2-D Hammersley set: (k/n, van der Corput radical inverse of k in base 2)."""
    k = np.arange(n, dtype=np.uint64)
    bits = k.copy()
    rev = np.zeros(n, dtype=np.float64)
    scale = 0.5
    for _ in range(32):
        rev += (bits & 1).astype(np.float64) * scale
        bits >>= 1
        scale *= 0.5
    return k.astype(np.float64) / n, rev


def dfg_rows(mu, r, u1, u2):
    """(A, B) for the texels mu[i] x r[j] (shape (len(r), len(mu), 2))."""
    a2 = (r * r)[:, None, None] ** 2  # alpha^2, shape (R, 1, 1)
    m = mu[None, :, None]  # (1, M, 1)
    sv = np.sqrt((1.0 - m) * (1.0 + m))
    u = u1[None, None, :]
    c2 = (1.0 - u) / (1.0 + (a2 - 1.0) * u)
    ch = np.sqrt(c2)
    sh = np.sqrt(np.maximum(0.0, 1.0 - c2))
    cphi = np.cos(2.0 * np.pi * u2)[None, None, :]
    vh = sv * sh * cphi + m * ch
    nl = 2.0 * vh * ch - m
    lit = (nl > 0.0) & (vh > 0.0)
    nlc = np.clip(nl, 1e-150, 1.0)

    def lam(z):
        t2 = (1.0 - z * z) / (z * z)
        return 0.5 * (np.sqrt(1.0 + a2 * t2) - 1.0)

    g2 = 1.0 / (1.0 + lam(nlc) + lam(m))
    w = np.where(lit, g2 * vh / (m * ch), 0.0)
    fc = np.maximum(0.0, 1.0 - vh) ** 5
    n = u1.shape[0]
    a = np.sum(w * (1.0 - fc), axis=2) / n
    b = np.sum(w * fc, axis=2) / n
    return np.stack([a, b], axis=-1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--samples", type=int, default=1024)
    ap.add_argument("--chunk", type=int, default=4, help="roughness rows per vectorised chunk")
    ap.add_argument("--stride", type=int, default=1, help="every s-th roughness row only")
    ap.add_argument("--reference", default=None)
    args = ap.parse_args()
    n = args.size
    centres = (np.arange(n, dtype=np.float64) + 0.5) / n
    u1, u2 = hammersley(args.samples)
    rows = centres[:: args.stride]
    out = np.empty((len(rows), n, 2))
    t0 = time.perf_counter()
    for j in range(0, len(rows), args.chunk):
        out[j : j + args.chunk] = dfg_rows(centres, rows[j : j + args.chunk], u1, u2)
    dt = time.perf_counter() - t0
    res = {
        "size": n,
        "rows": len(rows),
        "samples": args.samples,
        "seconds": dt,
        "us_per_texel": dt / (len(rows) * n) * 1e6,
    }
    if args.reference:
        ref = np.fromfile(args.reference, dtype="<f8").reshape(len(rows), n, 2)
        err = np.abs(out - ref)
        g = err[:, : min(4, n), :]
        res.update(
            max_error=float(err.max()),
            median_error=float(np.median(err)),
            max_error_at=[int(x) for x in np.unravel_index(np.argmax(err), err.shape)],
            grazing_max_error=float(g.max()),
            frac_over_half_lsb16=float(np.mean(err.max(axis=2) > 0.5 / 65535.0)),
        )
    print(json.dumps(res))


if __name__ == "__main__":
    main()
