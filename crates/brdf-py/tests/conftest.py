"""Shared helpers: the repository root, and the Rust side of the bit-for-bit tests.

The Rust values come from programs that do not load this package: `cargo xtask eval g|brdf`
(the project's command line, f64) and `rust-ref/` (brdf_core called directly, f32 and f64).
Without cargo those tests are skipped, unless BRDF_PY_REQUIRE_RUST=1 (set by
.ci/python.sh), which turns the skip into a failure.
"""

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
REF_MANIFEST = ROOT / "crates" / "brdf-py" / "rust-ref" / "Cargo.toml"


def need_cargo():
    if shutil.which("cargo") is None:
        if os.environ.get("BRDF_PY_REQUIRE_RUST") == "1":
            pytest.fail("cargo is not on PATH but BRDF_PY_REQUIRE_RUST=1")
        pytest.skip("cargo is not on PATH")


def cargo(args, stdin=None):
    """Runs cargo in the repository root and returns stdout (text)."""
    need_cargo()
    r = subprocess.run(
        ["cargo", *args],
        cwd=ROOT,
        input=stdin,
        capture_output=True,
        text=True,
        timeout=3000,
    )
    if r.returncode != 0:
        raise AssertionError(f"cargo {' '.join(args)} failed:\n{r.stderr[-4000:]}")
    return r.stdout


@pytest.fixture(scope="session")
def rust_ref():
    """A function running the rust-ref program: (cmd, dtype, arg, inputs, ncols) -> columns."""
    cargo(["build", "--release", "--quiet", "--manifest-path", str(REF_MANIFEST)])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REF_MANIFEST.parent / "target"))
    if not target.is_absolute():
        target = ROOT / target
    exe = target / "release" / "brdf-py-ref"

    def run(cmd, dtype, arg, inputs, ncols, extra=(), tmp=None):
        dtype = np.dtype(dtype)
        src = tmp / f"{cmd}-in.bin"
        dst = tmp / f"{cmd}-out.bin"
        np.concatenate([np.ascontiguousarray(x, dtype=dtype).ravel() for x in inputs]).tofile(src)
        name = "f32" if dtype == np.float32 else "f64"
        subprocess.run([str(exe), cmd, name, str(arg), str(src), str(dst), *extra], check=True)
        out = np.fromfile(dst, dtype=dtype)
        return out.reshape(ncols, -1)

    return run
