"""Tables: built in Python equal `cargo xtask lut generate`'s bytes; save/load round trip;
corrupt files raise LutError; lookups broadcast; Ctrl-C stops a long build."""

import _thread
import os
import threading
import time

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import brdf_kernels as bk
from conftest import cargo

SPECS = [
    {
        "kind": "split-sum",
        "model": "ggx",
        "masking": "smith-correlated",
        "res": "9x7",
        "encoding": "f16",
        "interpolation": "linear",
        "samples": 300,
        "axes": {"mu": {"lo": 0.05, "hi": 1.0, "warp": "log", "placement": "texel-centre"}},
    },
    {"kind": "g-per-sigma", "sigma": 0.3, "res": "12x11", "samples": 200, "seed": 7},
    {"kind": "e-avg", "model": "beckmann", "roughness": "alpha", "encoding": "f32", "samples": 20, "axes": {"m": {"count": 6}}},
]


def _toml(spec, out):
    def val(v):
        return f'"{v}"' if isinstance(v, str) else repr(v)

    lines = [f"{k} = {val(v)}" for k, v in spec.items() if k != "axes"]
    lines.append(f'out = "{out}"')
    for name, ax in spec.get("axes", {}).items():
        lines.append(f"[axes.{name}]")
        lines += [f"{k} = {val(v)}" for k, v in ax.items()]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("spec", SPECS, ids=[s["kind"] for s in SPECS])
def test_python_table_equals_xtask_lut_generate(tmp_path, spec):
    cfg = tmp_path / "spec.toml"
    cfg.write_text(_toml(spec, "xtask.blut"))
    cargo(["xtask", "lut", "generate", "--config", str(cfg)])
    want = (tmp_path / "xtask.blut").read_bytes()
    got = bk.build_table(spec).to_bytes()
    assert got == want


def test_save_load_round_trip_and_no_temporary_left(tmp_path):
    t = bk.build_table(SPECS[0])
    p = tmp_path / "t.blut"
    t.save(p)
    t.save(str(p))  # replacing an existing file
    assert os.listdir(tmp_path) == ["t.blut"]
    u = bk.Table.load(p)
    assert u.to_bytes() == t.to_bytes() == p.read_bytes()
    assert u.header == t.header
    assert bk.Table.from_bytes(p.read_bytes()).to_bytes() == t.to_bytes()


def test_failed_save_leaves_nothing_half_written(tmp_path):
    # The target is a non-empty folder: the temporary file is written, the rename onto the
    # folder fails, and the temporary file is removed; the folder is untouched.
    t = bk.build_table(SPECS[2])
    target = tmp_path / "t.blut"
    target.mkdir()
    (target / "keep").write_bytes(b"x")
    with pytest.raises(OSError):
        t.save(target)
    assert os.listdir(tmp_path) == ["t.blut"] and os.listdir(target) == ["keep"]
    with pytest.raises(OSError):  # a folder that does not exist: nothing created
        t.save(tmp_path / "missing" / "t.blut")
    assert os.listdir(tmp_path) == ["t.blut"]


def test_spec_out_writes_the_file(tmp_path):
    p = tmp_path / "o.blut"
    t = bk.build_table({**SPECS[2], "out": str(p)})
    assert p.read_bytes() == t.to_bytes()


def test_header_dict():
    t = bk.build_table(SPECS[0])
    h = t.header
    assert h["kind"] == "SplitSum"
    assert [a["name"] for a in h["axes"]] == ["mu", "roughness"]
    assert [a["count"] for a in h["axes"]] == [9, 7]
    assert h["axes"][0]["lo"] == 0.05 and h["axes"][0]["placement"] == "TexelCentre"
    assert h["channels"] == ["A", "B"]
    assert h["encoding"] == "F16" and h["error_samples"] == 300
    assert 0 < h["max_error"] < 0.1


def test_corrupt_and_truncated_files_raise_lut_error(tmp_path):
    good = bk.build_table(SPECS[2]).to_bytes()
    assert issubclass(bk.LutError, ValueError)
    flipped = bytearray(good)
    flipped[len(good) // 2] ^= 0x40
    for bad in [bytes(flipped), good[: len(good) - 3], good[:10], b"", b"not a table at all"]:
        with pytest.raises(bk.LutError):
            bk.Table.from_bytes(bad)
        p = tmp_path / "bad.blut"
        p.write_bytes(bad)
        with pytest.raises(bk.LutError):
            bk.Table.load(p)
    with pytest.raises(OSError):
        bk.Table.load(tmp_path / "missing.blut")


def test_lookup_broadcasts_and_matches_direct_values():
    # A G table: lookups against the direct passing factor F(θ, φ) = M(θ, (θ − φ)/2) within
    # the table's own measured max error (from its header).
    t = bk.build_table({"kind": "g-per-sigma", "sigma": 0.3, "res": "40x40", "samples": 500})
    theta = np.linspace(0.1, 1.4, 5)[:, None]
    phi = np.linspace(-1.2, 1.2, 4)[None, :]
    v = t.lookup(theta, phi)
    assert v.shape == (5, 4, 1)
    assert v.dtype == np.float64
    assert t.lookup(theta.astype(np.float32), phi.astype(np.float32)).dtype == np.float32
    # GM for θr > 0 is F(θr, θi) (docs/conventions.md): check via the G of the kernels.
    ti, tr = 0.4, np.linspace(0.1, 1.3, 7)
    gm, gs, _ = bk.g_modified(ti, tr, 0.3, terms=True)
    tol = t.header["max_error"] * 1.01
    np.testing.assert_allclose(t.lookup(tr, ti)[:, 0], gm, atol=tol)
    np.testing.assert_allclose(t.lookup(ti, tr)[:, 0], gs, atol=tol)
    assert np.isnan(t.lookup(np.nan, 0.1)[0])


def test_lookup_errors():
    t = bk.build_table(SPECS[2])
    with pytest.raises(ValueError, match="1 coordinates"):
        t.lookup(0.1, 0.2)
    t2 = bk.build_table(SPECS[0])
    with pytest.raises(ValueError, match=r"do not broadcast: `mu` \(2,\), `roughness` \(3,\)"):
        t2.lookup(np.zeros(2), np.zeros(3))


@pytest.mark.parametrize(
    "spec,match",
    [
        ({"kind": "nope"}, "kind"),
        ({}, "kind.*missing"),
        ({"kind": "split-sum"}, "model.*missing"),
        ({"kind": "split-sum", "model": "ggx", "colour": 1}, "unknown field `colour`"),
        ({"kind": "split-sum", "model": "ggx", "res": "8"}, "res"),
        ({"kind": "split-sum", "model": "ggx", "axes": {"theta": {}}}, "no axis `theta`"),
        ({"kind": "split-sum", "model": "ggx", "encoding": "u8"}, "encoding"),
        ({"kind": "g-per-sigma"}, "sigma"),
        ({"kind": "split-sum", "model": "ggx", "masking": "modified"}, "Torrance"),
        ({"kind": "split-sum", "model": "ggx", "res": "1x8"}, r"`res` `1x8`: `1`: nodes per axis is 1; the limit is 2\.\.=65536"),
    ],
)
def test_spec_errors(spec, match):
    with pytest.raises(ValueError, match=match):
        bk.build_table(spec)


def test_max_error_exceeded_is_lut_error(tmp_path):
    p = tmp_path / "x.blut"
    with pytest.raises(bk.LutError, match="max-error"):
        bk.build_table({**SPECS[0], "max-error": 1e-9, "out": str(p)})
    assert not p.exists()


def test_ctrl_c_stops_a_long_build():
    # Beckmann: its fixed rule with the embedded check costs ~0.7 ms a node, so this build
    # takes minutes (GGX rows are converged in ~3 µs a texel and would finish first).
    spec = {"kind": "split-sum", "model": "beckmann", "res": "512x512", "samples": 10}
    timer = threading.Timer(0.5, _thread.interrupt_main)
    t0 = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        bk.build_table(spec)
    elapsed = time.monotonic() - t0
    timer.cancel()
    # The whole build takes minutes on two cores; stopping takes one row per worker.
    assert elapsed < 10, elapsed
