#!/usr/bin/env python3
"""The benchmark peer: the paper's modified G computed the way a researcher would without
this project, straight from the formulas (docs/conventions.md sections 2-4) with SciPy's adaptive
quadrature (scipy.integrate.quad, default tolerances).

  p(g)   = C / (2 pi s^2 cos^3 g) * exp(-tan^2 g / (2 s^2)),  int p dg = 1 on [-pi/2, pi/2]
  M(t,a) = int_{-pi/2}^{lo} p dg + int_{lo}^{hi} p(g) r(g) dg
           lo = pi/2 - t, hi = min(pi/2, pi - 2t + a),
           r(g) = (cos(t - a) + cos(g + t)) / cos(t - a)
  GM = M(|tr|, sign(tr) alpha), GS = M(ti, -alpha), G = min(GM, GS), alpha = (tr - ti)/2

Usage: g_peer.py --sigma 0.3 --pairs "ti,tr;ti,tr;..." [--repeat K]
Prints one JSON object: the values, and the wall time per G value in ns (median and mean
over `--repeat` sweeps of all pairs, each sweep's time divided by the number of pairs) (C(s) is computed
once per sigma, outside the timed loop, as a researcher would). Exit status 3 when SciPy
cannot be imported (install it with `pip install scipy`).
"""

import argparse
import json
import math
import sys
import time

try:
    from scipy.integrate import quad
except ImportError:  # pragma: no cover - exercised by machines without SciPy
    print("scipy is not importable; install it with `pip install scipy`", file=sys.stderr)
    sys.exit(3)

HALF_PI = 0.5 * math.pi


def density(sigma):
    """p(g) for RMS slope sigma, normalised numerically to a 1-D probability density."""
    two_s2 = 2.0 * sigma * sigma

    def shape(g):
        c = math.cos(g)
        if c <= 0.0:
            return 0.0
        return math.exp(-math.tan(g) ** 2 / two_s2) / (math.pi * two_s2 * c ** 3)

    total, _ = quad(shape, -HALF_PI, HALF_PI, limit=200)
    inv = 1.0 / total
    return lambda g: shape(g) * inv


def passing(p, t, a):
    """M(t, a), docs/conventions.md section 3 (limits clamped to [-pi/2, pi/2])."""
    if t == 0.0:
        return 1.0
    lo = max(-HALF_PI, min(HALF_PI, HALF_PI - t))
    hi = max(-HALF_PI, min(HALF_PI, math.pi - 2.0 * t + a))
    full, _ = quad(p, -HALF_PI, lo)
    cb = math.cos(t - a)
    semi = 0.0
    if cb > 0.0 and hi > lo:
        semi, _ = quad(lambda g: p(g) * (cb + math.cos(g + t)) / cb, lo, hi)
    return min(1.0, max(0.0, full + semi))


def g_modified(p, ti, tr):
    """G = min(GM, GS), reciprocal convention (docs/conventions.md section 4)."""
    alpha = 0.5 * (tr - ti)
    gm = 1.0 if tr == 0.0 else passing(p, abs(tr), math.copysign(1.0, tr) * alpha)
    gs = passing(p, ti, -alpha)
    return min(gm, gs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sigma", type=float, default=0.3)
    ap.add_argument("--pairs", required=True, help='"ti,tr;ti,tr;..." in radians')
    ap.add_argument("--repeat", type=int, default=1)
    a = ap.parse_args()
    pairs = [tuple(float(x) for x in s.split(",")) for s in a.pairs.split(";") if s]
    p = density(a.sigma)
    values = [g_modified(p, ti, tr) for ti, tr in pairs]  # warm-up and the values
    # Like criterion: one sample = one sweep over all pairs; report the median sweep / pairs.
    sweeps = []
    clock = time.perf_counter
    for _ in range(a.repeat):
        t0 = clock()
        for ti, tr in pairs:
            g_modified(p, ti, tr)
        sweeps.append((clock() - t0) / len(pairs))
    ordered = sorted(sweeps)
    median = ordered[len(ordered) // 2]
    mean = sum(sweeps) / len(sweeps)
    import scipy

    print(
        json.dumps(
            {
                "sigma": a.sigma,
                "values": values,
                "evaluations": a.repeat * len(pairs),
                "ns_per_g": median * 1e9,
                "ns_per_g_mean": mean * 1e9,
                "python": sys.version.split()[0],
                "scipy": scipy.__version__,
            }
        )
    )


if __name__ == "__main__":
    main()
