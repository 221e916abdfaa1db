"""Engine textures: export_engine writes the files of `cargo xtask lut engine`, byte for byte
(both call the brdf-engine-assets library); its errors; Ctrl-C stops it."""

import _thread
import os
import threading
import time

import pytest

import brdf_kernels as bk
from conftest import cargo

ENGINES = ["khronos", "bevy", "filament", "threejs", "exr"]


def _same_files(a, b):
    names = sorted(os.listdir(a))
    assert names, f"nothing written in {a}"
    assert sorted(os.listdir(b)) == names
    for n in names:
        assert (a / n).read_bytes() == (b / n).read_bytes(), n
    return names


@pytest.mark.parametrize("size", [8, 64])
@pytest.mark.parametrize("engine", ENGINES)
def test_export_engine_equals_xtask_lut_engine(tmp_path, engine, size):
    cargo(["xtask", "lut", "engine", engine, "--size", str(size), "--out", str(tmp_path / "xtask")])
    written = bk.export_engine(engine, tmp_path / "py", size=size)
    names = _same_files(tmp_path / "xtask", tmp_path / "py")
    assert sorted(os.path.basename(p) for p in written) == names


def test_export_engine_default_size_equals_xtask(tmp_path):
    # threejs: the engine's own 16 × 16 when no size is given, on both sides.
    cargo(["xtask", "lut", "engine", "threejs", "--out", str(tmp_path / "xtask")])
    bk.export_engine("threejs", str(tmp_path / "py"))
    _same_files(tmp_path / "xtask", tmp_path / "py")


def test_existing_files_need_force(tmp_path):
    first = bk.export_engine("threejs", tmp_path, size=4)
    before = {p: open(p, "rb").read() for p in first}
    with pytest.raises(FileExistsError, match="force=True"):
        bk.export_engine("threejs", tmp_path, size=8)
    assert {p: open(p, "rb").read() for p in first} == before  # untouched
    assert bk.export_engine("threejs", tmp_path, size=8, force=True) == first
    assert {p: open(p, "rb").read() for p in first} != before
    assert not [n for n in os.listdir(tmp_path) if ".tmp-" in n]


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"engine": "unreal"}, "engine.*khronos, bevy, filament, threejs, exr, all"),
        ({"engine": "bevy", "size": 1}, r"size.*2 … 4096"),
        ({"engine": "bevy", "size": 4097}, r"size.*2 … 4096"),
        ({"engine": "all", "size": 8}, "size.*all"),
    ],
)
def test_export_engine_errors(tmp_path, kwargs, match):
    engine = kwargs.pop("engine")
    with pytest.raises(ValueError, match=match):
        bk.export_engine(engine, tmp_path, **kwargs)
    assert os.listdir(tmp_path) == []


def test_ctrl_c_stops_an_engine_export(tmp_path):
    # khronos at its native 1024 × 1024: about 10⁶ integrals, far longer than the timer.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    t0 = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        bk.export_engine("khronos", tmp_path)
    elapsed = time.monotonic() - t0
    timer.cancel()
    assert elapsed < 10, elapsed
    assert os.listdir(tmp_path) == []
