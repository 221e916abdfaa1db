"""The same values as the Rust kernels, bit for bit, on one shared input set (f64 and f32).

The Rust side is computed independently of this package (see conftest.py): the project's
command line `cargo xtask eval g|brdf` for f64, and rust-ref (brdf_core called directly)
for f32 and f64. Comparisons are exact: `assert_array_equal` treats NaN as equal to NaN.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import brdf_kernels as bk
from conftest import cargo

# The shared input set: a grid over the paper's domain with the kink and edge angles, plus
# random angles (seeded).
_RNG = np.random.default_rng(20150924)
TI_DEG = np.concatenate([[0, 5, 30, 45, 60, 85, 89, 90], _RNG.uniform(0, 90, 24)])
TR_DEG = np.concatenate([[-90, -60, -30, -1, 0, 1, 30, 60, 89, 90], _RNG.uniform(-90, 90, 22)])
TI_G, TR_G = (a.ravel() for a in np.meshgrid(TI_DEG, TR_DEG, indexing="ij"))
SIGMAS = [0.1, 0.3, 1.0]
RAD = math.pi / 180.0  # Rust's f64::to_radians multiplies by PI / 180.0


def _xtask_g(sigma, extra=()):
    rows = "\n".join(f"{float(a)!r},{float(b)!r},{sigma!r}" for a, b in zip(TI_G, TR_G))
    out = cargo(["xtask", "eval", "g", *extra], stdin="theta_i_deg,theta_r_deg,sigma\n" + rows + "\n")
    lines = out.strip().splitlines()
    assert lines[0].startswith("theta_i_deg,theta_r_deg,sigma,GM,GS,G,G_blinn")
    cols = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    assert cols.shape[0] == TI_G.size
    return cols


@pytest.mark.parametrize("sigma", SIGMAS)
@pytest.mark.parametrize("convention,nodes", [("reciprocal", 10), ("printed", 10), ("reciprocal", 16)])
def test_g_equals_xtask_eval_g_f64(sigma, convention, nodes):
    cols = _xtask_g(sigma, ["--convention", convention, "--nodes", str(nodes)])
    ti, tr = TI_G * RAD, TR_G * RAD
    gm, gs, g = bk.g_modified(ti, tr, sigma, convention=convention, nodes=nodes, terms=True)
    assert_array_equal(gm, cols[:, 3])
    assert_array_equal(gs, cols[:, 4])
    assert_array_equal(g, cols[:, 5])
    assert_array_equal(bk.g_modified(ti, tr, sigma, convention=convention, nodes=nodes), cols[:, 5])
    assert_array_equal(bk.g_blinn(ti, tr), cols[:, 6])


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("sigma", SIGMAS)
def test_g_equals_rust_ref(rust_ref, tmp_path, dtype, sigma):
    ti = (TI_G * RAD).astype(dtype)
    tr = (TR_G * RAD).astype(dtype)
    ref = rust_ref("g", dtype, sigma, [ti, tr], 4, tmp=tmp_path)
    gm, gs, g = bk.g_modified(ti, tr, sigma, terms=True)
    for got, want in [(gm, ref[0]), (gs, ref[1]), (g, ref[2]), (bk.g_blinn(ti, tr), ref[3])]:
        assert got.dtype == dtype
        assert_array_equal(got, want)


def _dots(dtype):
    rng = np.random.default_rng(7)
    wi = rng.normal(size=(300, 3))
    wo = rng.normal(size=(300, 3))
    wi /= np.linalg.norm(wi, axis=1)[:, None]
    wo /= np.linalg.norm(wo, axis=1)[:, None]
    d = [wi[:, 2], wo[:, 2], np.sum(wi * wo, axis=1)]
    return [x.astype(dtype) for x in d]


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_dots_equal_rust_ref(rust_ref, tmp_path, dtype):
    n_i, n_o, i_o = _dots(dtype)
    ref = rust_ref("dots", dtype, 0.3, [n_i, n_o, i_o], 2, tmp=tmp_path)
    assert_array_equal(bk.g_modified_dots(n_i, n_o, i_o, 0.3), ref[0])
    assert_array_equal(bk.g_blinn_dots(n_i, n_o, i_o), ref[1])


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("width", [0.05, 0.3 * math.sqrt(2), 1.0])
def test_smith_equals_rust_ref(rust_ref, tmp_path, dtype, width):
    c = np.concatenate([[0.0, 1e-6, 0.01, 0.5, 1.0], np.random.default_rng(3).uniform(0, 1, 40)])
    ci, co = (a.ravel().astype(dtype) for a in np.meshgrid(c, c))
    ref = rust_ref("smith", dtype, width, [ci, co], 4, tmp=tmp_path)
    got = [
        bk.g_smith_separable(ci, co, width),
        bk.g_smith_correlated(ci, co, width),
        bk.g_smith_separable(ci, co, width, distribution="ggx"),
        bk.g_smith_correlated(ci, co, width, distribution="ggx"),
    ]
    for k in range(4):
        assert got[k].dtype == dtype
        assert_array_equal(got[k], ref[k])


def _directions(n, seed):
    rng = np.random.default_rng(seed)
    w = rng.normal(size=(n, 3))
    w[:, 2] = np.abs(w[:, 2])
    w[: n // 10, 2] *= -1  # some below the horizon
    return w


MODEL_CASES = [
    ("ggx", {"alpha": 0.3}),
    ("torrance-sparrow", {"sigma": 0.3}),
    ("lambert", {}),
    ("ashikhmin-shirley", {}),
    ("ward", {}),
]


@pytest.mark.parametrize("model,params", MODEL_CASES)
def test_eval_equals_xtask_eval_brdf_f64(model, params):
    wi, wo = _directions(200, 1), _directions(200, 2)
    rows = "\n".join(",".join(repr(float(x)) for x in (*a, *b)) for a, b in zip(wi, wo))
    args = ["xtask", "eval", "brdf", "--model", model]
    for k, v in params.items():
        args += ["--param", f"{k}={v!r}"]
    out = cargo(args, stdin="wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n" + rows + "\n")
    lines = out.strip().splitlines()[1:]
    want = np.array([[float(x) for x in ln.split(",")[6:]] for ln in lines])
    assert_array_equal(bk.eval(model, wi, wo, **params), want)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("model,params", MODEL_CASES)
def test_eval_equals_rust_ref(rust_ref, tmp_path, dtype, model, params):
    wi, wo = _directions(200, 3).astype(dtype), _directions(200, 4).astype(dtype)
    extra = [f"{k}={v!r}" for k, v in params.items()]
    ref = rust_ref("eval", dtype, model, [wi, wo], 1, extra=extra, tmp=tmp_path)
    got = bk.eval(model, wi, wo, **params)
    assert got.dtype == dtype
    assert_array_equal(got.ravel(), ref[0])


def _vectors(n, seed):
    """Unnormalised directions (lengths 0.1 … 3), some below the horizon, one zero vector
    and one NaN component."""
    rng = np.random.default_rng(seed)
    w = rng.normal(size=(n, 3)) * rng.uniform(0.1, 3.0, (n, 1))
    w[: n // 3, 2] = np.abs(w[: n // 3, 2])
    w[5] = 0.0
    w[7, 1] = np.nan
    return w


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_vectors_equal_rust_ref(rust_ref, tmp_path, dtype):
    wi, wo = _vectors(300, 21).astype(dtype), _vectors(300, 22).astype(dtype)
    normal = np.random.default_rng(23).normal(size=(300, 3)).astype(dtype)
    normal[:100] = [0.0, 0.0, 2.0]
    ref = rust_ref("vectors", dtype, 0.3, [wi, wo, normal], 1, tmp=tmp_path)
    got = bk.g_modified_vectors(wi, wo, 0.3, n=normal)
    assert got.dtype == dtype and got.shape == (300,)
    assert_array_equal(got, ref[0])
    # The default normal is +z (the local frame).
    up = np.broadcast_to(np.array([0.0, 0.0, 1.0], dtype), wi.shape)
    ref_up = rust_ref("vectors", dtype, 0.3, [wi, wo, up], 1, tmp=tmp_path)
    assert_array_equal(bk.g_modified_vectors(wi, wo, 0.3), ref_up[0])
