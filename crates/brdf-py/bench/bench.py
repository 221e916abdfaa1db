"""Benchmark (not a test): the modified G through Python against the Rust batch call on the
same inputs, against a scipy.integrate.quad loop (the project's SciPy peer,
crates/brdf-bench/peer/g_peer.py), and the overhead of a scalar call.

Run from the repository root with the package installed (e.g. the venv of .ci/python.sh):
    .cache/python-venv/bin/python crates/brdf-py/bench/bench.py [--pairs 1000000]
Needs cargo (builds crates/brdf-py/rust-ref in release) and, for the peer, SciPy.
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


def quad_ns_per_element(ti, tr):
    pairs = ";".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(ti[:64], tr[:64]))
    peer = ROOT / "crates/brdf-bench/peer/g_peer.py"
    r = subprocess.run([sys.executable, str(peer), "--sigma", str(SIGMA), "--pairs", pairs, "--repeat", "3"], capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr.strip()
    j = json.loads(r.stdout)
    return float(j["ns_per_g"]), None  # median over the sweeps


def scalar_ns(f, *args, n=200_000):
    return min(timeit.repeat(lambda: f(*args), number=n, repeat=5)) * 1e9 / n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", type=int, default=1_000_000)
    ap.add_argument("--reps", type=int, default=5)
    a = ap.parse_args()
    rng = np.random.default_rng(6)
    ti = rng.uniform(0, np.pi / 2, a.pairs)
    tr = rng.uniform(-np.pi / 2, np.pi / 2, a.pairs)
    rust = rust_ns_per_element(ti, tr, a.reps)
    py = python_ns_per_element(ti, tr, a.reps)
    quad, why = quad_ns_per_element(ti, tr)
    s_mod = scalar_ns(bk.g_modified, 0.5, 0.7, SIGMA)
    s_blinn = scalar_ns(bk.g_blinn, 0.5, 0.7)
    print(f"G over {a.pairs} pairs (sigma {SIGMA}, f64, best of {a.reps}):")
    print(f"  Rust brdf_core::batch::g_modified : {rust:8.1f} ns/element")
    print(f"  Python brdf_kernels.g_modified    : {py:8.1f} ns/element  ratio {py / rust:.3f} (goal <= 1.3)")
    if quad is None:
        print(f"  scipy.integrate.quad loop         : not run ({why})")
    else:
        print(f"  scipy.integrate.quad loop         : {quad:8.1f} ns/element  Python is {quad / py:.0f}x faster (goal >= 1000)")
    print(f"scalar call g_modified(0.5, 0.7, 0.3): {s_mod:.0f} ns; overhead over Rust's per-element time {s_mod - rust:.0f} ns (goal <= 1000)")
    print(f"scalar call g_blinn(0.5, 0.7)        : {s_blinn:.0f} ns (kernel a few ns: almost all overhead)")


if __name__ == "__main__":
    main()
