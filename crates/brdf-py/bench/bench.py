"""Benchmark (not a test): the modified G through Python against the Rust batch call on the
same inputs, against a scipy.integrate.quad loop (the project's SciPy peer,
crates/brdf-bench/peer/g_peer.py), and the overhead of a scalar call.

Run from the repository root with the package installed (e.g. the venv of .ci/python.sh):
    .cache/python-venv/bin/python crates/brdf-py/bench/bench.py [--pairs 1000000] [--json]
        [--peer-python PYTHON]
Needs cargo (builds crates/brdf-py/rust-ref in release) and, for the peer, SciPy: in this
interpreter, or in PYTHON (`cargo xtask bench` passes its .cache/scipy-venv). With --json
the figures are printed as one JSON object (read by `cargo xtask bench` for
docs/benchmarks.md); without, as text.
Goals (issue 24): Python ≤ 1.3× Rust's time; ≥ 1000× faster than quad per element;
scalar-call overhead ≤ 1 µs.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import timeit
from pathlib import Path

import numpy as np

import brdf_kernels as bk

ROOT = Path(__file__).resolve().parents[3]
SIGMA = 0.3


def rust_ns_per_element(ti, tr, reps):
    manifest = ROOT / "crates/brdf-py/rust-ref/Cargo.toml"
    subprocess.run(["cargo", "build", "--release", "--quiet", "--manifest-path", str(manifest)], check=True)
    target = Path(os.environ.get("CARGO_TARGET_DIR", manifest.parent / "target"))
    with tempfile.TemporaryDirectory() as d:
        src = Path(d) / "in.bin"
        np.concatenate([ti, tr]).tofile(src)
        out = subprocess.run([str(target / "release/brdf-py-ref"), "bench", str(src), str(reps)], check=True, capture_output=True, text=True)
    return float(out.stdout)


def python_ns_per_element(ti, tr, reps):
    best = min(timeit.repeat(lambda: bk.g_modified(ti, tr, SIGMA), number=1, repeat=reps))
    return best * 1e9 / ti.size


QUAD_PAIRS = 64


def quad_ns_per_element(ti, tr, python):
    """The SciPy peer's median ns per G over the first QUAD_PAIRS pairs (3 sweeps), or
    (None, why)."""
    pairs = ";".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(ti[:QUAD_PAIRS], tr[:QUAD_PAIRS]))
    peer = ROOT / "crates/brdf-bench/peer/g_peer.py"
    cmd = [python, str(peer), "--sigma", str(SIGMA), "--pairs", pairs, "--repeat", "3"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return None, (r.stderr.strip().splitlines() or ["failed"])[-1]
    j = json.loads(r.stdout)
    return float(j["ns_per_g"]), None  # median over the sweeps


def scalar_ns(f, *args, n=200_000):
    return min(timeit.repeat(lambda: f(*args), number=n, repeat=5)) * 1e9 / n


def measure(pairs, reps, peer_python):
    """Every figure of one run, as a dict (ns per element or per call)."""
    rng = np.random.default_rng(6)
    ti = rng.uniform(0, np.pi / 2, pairs)
    tr = rng.uniform(-np.pi / 2, np.pi / 2, pairs)
    rust = rust_ns_per_element(ti, tr, reps)
    py = python_ns_per_element(ti, tr, reps)
    quad, why = quad_ns_per_element(ti, tr, peer_python)
    s_mod = scalar_ns(bk.g_modified, 0.5, 0.7, SIGMA)
    return {
        "pairs": pairs,
        "reps": reps,
        "sigma": SIGMA,
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "brdf_kernels": bk.__version__,
        "rust_ns": rust,
        "python_ns": py,
        "ratio": py / rust,
        "quad_ns": quad,
        "quad_pairs": QUAD_PAIRS,
        "quad_skipped": why,
        "quad_speedup": None if quad is None else quad / py,
        "scalar_g_modified_ns": s_mod,
        "scalar_overhead_ns": s_mod - rust,
        "scalar_g_blinn_ns": scalar_ns(bk.g_blinn, 0.5, 0.7),
    }


def print_text(m):
    print(f"G over {m['pairs']} pairs (sigma {m['sigma']}, f64, best of {m['reps']}):")
    print(f"  Rust brdf_core::batch::g_modified : {m['rust_ns']:8.1f} ns/element")
    print(f"  Python brdf_kernels.g_modified    : {m['python_ns']:8.1f} ns/element  ratio {m['ratio']:.3f} (goal <= 1.3)")
    if m["quad_ns"] is None:
        print(f"  scipy.integrate.quad loop         : not run ({m['quad_skipped']})")
    else:
        print(f"  scipy.integrate.quad loop         : {m['quad_ns']:8.1f} ns/element  Python is {m['quad_speedup']:.0f}x faster (goal >= 1000)")
    print(f"scalar call g_modified(0.5, 0.7, 0.3): {m['scalar_g_modified_ns']:.0f} ns; overhead over Rust's per-element time {m['scalar_overhead_ns']:.0f} ns (goal <= 1000)")
    print(f"scalar call g_blinn(0.5, 0.7)        : {m['scalar_g_blinn_ns']:.0f} ns (kernel a few ns: almost all overhead)")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=1_000_000)
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--json", action="store_true", help="print the figures as one JSON object")
    ap.add_argument("--peer-python", default=sys.executable, help="the Python that runs the SciPy peer")
    a = ap.parse_args()
    m = measure(a.pairs, a.reps, a.peer_python)
    if a.json:
        print(json.dumps(m))
    else:
        print_text(m)


if __name__ == "__main__":
    main()
