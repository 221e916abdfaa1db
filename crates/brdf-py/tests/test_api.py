"""Broadcasting, dtype rules, scalars, NaN, and every documented error path."""

import math

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import brdf_kernels as bk


def elementwise(f, *arrays):
    """The reference for broadcasting: one scalar call per element of the broadcast shape."""
    b = np.broadcast_arrays(*arrays)
    out = np.empty(b[0].shape)
    for idx in np.ndindex(b[0].shape):
        out[idx] = f(*(float(x[idx]) for x in b))
    return out


def test_scalar_call_returns_float_and_equals_array_call():
    g = bk.g_modified(0.5, 0.7, 0.3)
    assert isinstance(g, float)
    assert g == bk.g_modified(np.array([0.5]), np.array([0.7]), 0.3)[0]
    assert isinstance(bk.g_blinn(0, 1), float)
    # NumPy scalars and 0-d arrays give a NumPy scalar of the dtype rule, as ufuncs do.
    g64 = bk.g_modified(np.float64(0.5), 0.7, 0.3)
    assert type(g64) is np.float64 and g64 == g
    g32 = bk.g_modified(np.array(0.5, np.float32), np.float32(0.7), 0.3)
    assert type(g32) is np.float32
    assert g32 == bk.g_modified(np.array([0.5], np.float32), np.array([0.7], np.float32), 0.3)[0]


@pytest.mark.parametrize("sa,sb", [((4, 1), (3,)), ((2, 1, 5), (1, 3, 1)), ((), (6,)), ((0,), (1,))])
def test_broadcasting_matches_scalar_calls(sa, sb):
    rng = np.random.default_rng(1)
    a = rng.uniform(0, 1.5, sa)
    b = rng.uniform(-1.5, 1.5, sb)
    got = bk.g_modified(a, b, 0.4)
    assert got.shape == np.broadcast_shapes(sa, sb)
    assert_array_equal(got, elementwise(lambda x, y: bk.g_modified(x, y, 0.4), a, b))


def test_python_number_broadcasts_with_array_and_keeps_float32():
    a = np.linspace(0, 1.5, 7, dtype=np.float32)
    got = bk.g_modified(a, 0.25, 0.3)
    assert got.dtype == np.float32 and got.shape == (7,)
    assert_array_equal(got, bk.g_modified(a, np.full(7, 0.25, np.float32), 0.3))


def test_non_contiguous_views():
    rng = np.random.default_rng(2)
    big = rng.uniform(0, 1.5, (8, 10))
    view_a = big[::2, 1::3]  # strided
    view_b = big.T[:4, :3]  # transposed
    got = bk.g_modified(view_a, view_b, 0.3)
    want = bk.g_modified(np.ascontiguousarray(view_a), np.ascontiguousarray(view_b), 0.3)
    assert_array_equal(got, want)
    wi = rng.normal(size=(5, 6))[:, ::2]  # (5, 3) with stride 2
    wo = np.asfortranarray(rng.normal(size=(5, 3)))
    assert_array_equal(bk.eval("ggx", wi, wo), bk.eval("ggx", np.ascontiguousarray(wi), np.ascontiguousarray(wo)))


@pytest.mark.parametrize(
    "da,db,want",
    [
        (np.float32, np.float32, np.float32),
        (np.float64, np.float64, np.float64),
        (np.float32, np.float64, np.float64),
        (np.int64, np.float32, np.float64),
        (np.float16, np.float32, np.float32),
        (bool, bool, np.float64),
    ],
)
def test_dtype_rule(da, db, want):
    a = np.array([0, 1], dtype=da)
    b = np.array([1, 0], dtype=db)
    assert bk.g_blinn(a, b).dtype == want
    assert bk.g_smith_correlated(a, b, 0.5).dtype == want


def test_lists_are_arrays():
    assert_array_equal(bk.g_blinn([0.1, 0.2], [0.3, 0.4]), bk.g_blinn(np.array([0.1, 0.2]), np.array([0.3, 0.4])))


@pytest.mark.parametrize("bad", [np.array([1 + 2j]), np.array(["a"]), np.array([object()], dtype=object)])
def test_unsupported_dtype_is_type_error(bad):
    with pytest.raises(TypeError, match="theta_i.*float32 or float64"):
        bk.g_modified(bad, 0.1, 0.3)


def test_nan_in_nan_out():
    x = np.array([np.nan, 0.3])
    assert np.isnan(bk.g_modified(x, 0.2, 0.3)[0])
    assert np.isnan(bk.g_blinn(x, 0.2)[0])
    assert np.isnan(bk.g_smith_correlated(x, 0.5, 0.3)[0])
    assert math.isnan(bk.g_modified(float("nan"), 0.2, 0.3))
    assert np.isnan(bk.eval("ggx", [np.nan, 0, 1], [0, 0, 1])).all()
    assert np.isnan(bk.eval("ggx", [0, 0, 0], [0, 0, 1])).all()  # zero vector


def test_results_in_shape_of_directions():
    rng = np.random.default_rng(5)
    wi = rng.normal(size=(4, 1, 3))
    wo = rng.normal(size=(5, 3))
    assert bk.eval("ggx", wi, wo, alpha=0.2).shape == (4, 5, 3)
    assert bk.albedo("lambert", wo).shape == (5, 3)
    wi_s, w, pdf = bk.sample("ggx", wo, rng.uniform(size=(2, 5, 2)))
    assert wi_s.shape == (2, 5, 3) and w.shape == (2, 5, 3) and pdf.shape == (2, 5)


def test_vectors_in_plane_equal_the_angle_form():
    # Coplanar directions: the 3-D extension reduces to the in-plane G of the angles (θr > 0
    # on the forward side: wo's tangential part opposite wi's). The two forms reach G through
    # different trigonometry (angles vs dot products), so they agree to rounding: a few ulps
    # of the cosines, times dG/dθ (below 10 here), well inside 1e-12.
    ti, tr = 0.5, np.linspace(-1.5, 1.5, 61)
    wi = np.array([np.sin(ti), 0.0, np.cos(ti)])
    wo = np.stack([-np.sin(tr), np.zeros_like(tr), np.cos(tr)], axis=-1)
    np.testing.assert_allclose(bk.g_modified_vectors(wi, wo, 0.3), bk.g_modified(ti, tr, 0.3), rtol=0, atol=1e-12)
    # A rotated frame (normal, wi and wo rotated together) gives the same G, to rounding.
    c, s = np.cos(0.7), np.sin(0.7)
    rot = np.array([[1, 0, 0], [0, c, -s], [0, s, c]]) @ np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    got = bk.g_modified_vectors(wi @ rot.T, wo @ rot.T, 0.3, n=rot @ [0.0, 0.0, 1.0])
    np.testing.assert_allclose(got, bk.g_modified(ti, tr, 0.3), rtol=0, atol=1e-12)
    # Lengths do not matter (normalised inside); terms as in the angle form.
    gm, gs, g = bk.g_modified_vectors(3 * wi, 0.5 * wo, 0.3, terms=True)
    gm2, gs2, g2 = bk.g_modified(ti, tr, 0.3, terms=True)
    np.testing.assert_allclose(np.stack([gm, gs, g]), np.stack([gm2, gs2, g2]), rtol=0, atol=1e-12)


def test_vectors_match_the_validation_crates_published_values():
    # docs/validation-2d.json (the 3-D study of crates/brdf-validate) records, per cell
    # (θi, θo, azimuth φ between them), the reciprocal 3-D extension's GM, GS and G as
    # computed there, rounded to 4 decimals: agreement to half a unit of the 4th decimal
    # checks the direction convention and the azimuthal part of the extension.
    import json

    from conftest import ROOT

    data = json.loads((ROOT / "docs" / "validation-2d.json").read_text())
    for sweep in data["sweeps"]:
        c = sweep["cells"]
        ti, to, ph = (np.radians([x[k] for x in c]) for k in ("theta_i", "theta_o", "phi"))
        wi = np.stack([np.sin(ti), np.zeros_like(ti), np.cos(ti)], axis=-1)
        wo = np.stack([np.sin(to) * np.cos(ph), np.sin(to) * np.sin(ph), np.cos(to)], axis=-1)
        gm, gs, g = bk.g_modified_vectors(wi, wo, sweep["sigma"], terms=True)
        for got, key in [(gm, "modified_gm"), (gs, "modified_gs")]:
            np.testing.assert_allclose(got, [x[key] for x in c], rtol=0, atol=5e-5 + 1e-12)
        np.testing.assert_allclose(g, [x["models"]["modified"] for x in c], rtol=0, atol=5e-5 + 1e-12)


def test_terms_is_tuple_with_g_the_minimum():
    t = np.linspace(-1.5, 1.5, 31)
    gm, gs, g = bk.g_modified(0.6, t, 0.5, terms=True)
    assert_array_equal(g, np.minimum(gm, gs))


def test_lambert_albedo_and_eval_are_known_values():
    # Lambert with albedo a: f = a/pi, directional albedo a (independent closed forms).
    f = bk.eval("lambert", [0.3, 0.1, 0.9], [0, 0, 1], albedo=0.5)
    np.testing.assert_allclose(f, 0.5 / np.pi, rtol=1e-15)
    r = bk.albedo("lambert", [[0, 0, 1], [0.5, 0, 0.5]], albedo=0.5)
    np.testing.assert_allclose(r, 0.5, rtol=1e-5)  # the quadrature's documented 3e-5 bound


def test_sample_pdf_matches_eval_for_lambert():
    wo = np.array([0.2, 0.1, 0.9])
    u = np.random.default_rng(9).uniform(size=(100, 2))
    wi, w, pdf = bk.sample("lambert", wo, u, albedo=0.8)
    np.testing.assert_allclose(pdf, wi[:, 2] / np.pi, rtol=1e-12)  # cosine sampling
    np.testing.assert_allclose(w, 0.8, rtol=1e-12)  # f cos / pdf = albedo
    np.testing.assert_allclose(np.linalg.norm(wi, axis=1), 1, rtol=1e-12)


def test_models_lists_the_catalogue():
    ms = bk.models()
    names = [m["name"] for m in ms]
    for n in ["ggx", "torrance-sparrow", "lambert", "ward", "ashikhmin-shirley"]:
        assert n in names
    ts = next(m for m in ms if m["name"] == "torrance-sparrow")
    sigma = next(p for p in ts["params"] if p["name"] == "sigma")
    assert sigma["default"] == 0.3 and sigma["kind"] == "scalar" and sigma["range"]
    for m in ms:  # every model builds with its defaults and evaluates
        bk.eval(m["name"], [0, 0, 1], [0.1, 0, 1])


def test_choice_and_rgb_params():
    a = bk.eval("torrance-sparrow", [0.3, 0, 1], [-0.2, 0, 1], g="blinn")
    b = bk.eval("torrance-sparrow", [0.3, 0, 1], [-0.2, 0, 1])
    assert a.shape == b.shape == (3,)
    ms = {m["name"]: m for m in bk.models()}
    rgb = [p for m in ms.values() for p in m["params"] if p["kind"] == "rgb"]
    assert rgb, "the catalogue has colour parameters"


# --- errors ----------------------------------------------------------------------------


@pytest.mark.parametrize("sigma", [0.0, -1.0, float("nan"), float("inf"), 2e6])
def test_sigma_out_of_range(sigma):
    with pytest.raises(ValueError, match=r"argument `sigma` = .* outside its range \(0, 1e6\]"):
        bk.g_modified(0.1, 0.2, sigma)


def test_bad_nodes_and_convention():
    with pytest.raises(ValueError, match="nodes.*not one of"):
        bk.g_modified(0.1, 0.2, 0.3, nodes=7)
    with pytest.raises(ValueError, match="convention"):
        bk.g_modified(0.1, 0.2, 0.3, convention="paper")
    with pytest.raises(ValueError, match="distribution"):
        bk.g_smith_correlated(0.1, 0.2, 0.3, distribution="phong")
    with pytest.raises(ValueError, match="width"):
        bk.g_smith_correlated(0.1, 0.2, float("nan"))


def test_shapes_that_do_not_broadcast_name_both():
    with pytest.raises(ValueError, match=r"`theta_i` \(3,\).*`theta_r` \(4,\)"):
        bk.g_modified(np.zeros(3), np.zeros(4), 0.3)
    with pytest.raises(ValueError, match=r"`wi` \(2,\).*`wo` \(5,\)"):
        bk.eval("ggx", np.zeros((2, 3)), np.zeros((5, 3)))


def test_directions_need_last_axis_3():
    with pytest.raises(ValueError, match=r"`wi`.*\(\.\.\., 3\)"):
        bk.eval("ggx", np.zeros((2, 2)), np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"`u`.*\(\.\.\., 2\)"):
        bk.sample("ggx", [0, 0, 1], np.zeros(3))


def test_model_errors():
    with pytest.raises(ValueError, match="unknown model.*ggx"):
        bk.eval("nonsense", [0, 0, 1], [0, 0, 1])
    with pytest.raises(ValueError, match="no parameter `beta`.*alpha"):
        bk.eval("ggx", [0, 0, 1], [0, 0, 1], beta=0.3)
    with pytest.raises(ValueError, match="alpha.*range"):
        bk.eval("ggx", [0, 0, 1], [0, 0, 1], alpha=-1.0)
    with pytest.raises(ValueError, match="alpha.*not finite"):
        bk.eval("ggx", [0, 0, 1], [0, 0, 1], alpha=float("nan"))
    with pytest.raises(ValueError, match="`g`.*not one of"):
        bk.eval("torrance-sparrow", [0, 0, 1], [0, 0, 1], g="nope")
    with pytest.raises(ValueError, match="alpha.*number"):
        bk.eval("ggx", [0, 0, 1], [0, 0, 1], alpha="x")


def test_gil_is_released_while_rust_computes():
    # While a long call runs in a worker thread, this thread keeps running Python: the
    # longest pause between its loop iterations stays well below the call's duration (with
    # the GIL held, one pause would span the whole call).
    import threading
    import time

    ti = np.random.default_rng(0).uniform(0, 1.5, 400_000)
    done = threading.Event()
    span = []

    def work():
        t0 = time.perf_counter()
        bk.g_modified(ti, ti, 0.3)
        span.append(time.perf_counter() - t0)
        done.set()

    w = threading.Thread(target=work)
    stamps = []
    w.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
    w.join()
    gaps = np.diff(stamps) if len(stamps) > 1 else np.array([span[0]])
    assert span[0] > 0.05, "the call is too short to tell"
    assert gaps.max() < 0.5 * span[0], (gaps.max(), span[0])


def test_every_function_has_a_numpy_style_docstring_and_a_stub():
    from pathlib import Path

    stub = (Path(bk.__file__).parent / "_native.pyi").read_text()
    assert (Path(bk.__file__).parent / "py.typed").exists()
    funcs = [getattr(bk, n) for n in bk.__all__ if n not in ("__version__", "LutError", "Table")]
    methods = [getattr(bk.Table, m) for m in ("load", "from_bytes", "save", "to_bytes", "lookup")]
    for f in funcs + methods + [bk.Table.header]:
        doc = f.__doc__ or ""
        assert "Returns\n-------" in doc or "Raises\n------" in doc, f"{f}: {doc[:80]!r}"
    for n in bk.__all__:
        assert f"def {n}(" in stub or f"class {n}(" in stub or f"class {n}:" in stub or f"{n}:" in stub, n
