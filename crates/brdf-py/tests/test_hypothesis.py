"""Random inputs (hypothesis): only the documented exceptions, results in range."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import brdf_kernels as bk

ANY_FLOAT = st.floats(allow_nan=True, allow_infinity=True, width=64)
ANGLES = hnp.arrays(np.float64, st.integers(0, 20), elements=ANY_FLOAT)
SIGMA = st.floats(allow_nan=True, allow_infinity=True)


def in_unit_or_nan(x):
    x = np.asarray(x)
    return bool(np.all(np.isnan(x) | ((x >= 0) & (x <= 1))))


@settings(max_examples=300, deadline=None)
@given(ANGLES, ANGLES, SIGMA, st.sampled_from([4, 10, 32]), st.sampled_from(["reciprocal", "printed"]))
def test_g_modified(ti, tr, sigma, nodes, conv):
    n = min(ti.size, tr.size)
    ti, tr = ti[:n], tr[:n]
    if not (math.isfinite(sigma) and 0 < sigma <= 1e6):  # the documented range (0, 1e6]
        try:
            bk.g_modified(ti, tr, sigma)
        except ValueError:
            return
        raise AssertionError("no ValueError for a bad sigma")
    gm, gs, g = bk.g_modified(ti, tr, sigma, nodes=nodes, convention=conv, terms=True)
    assert in_unit_or_nan(gm) and in_unit_or_nan(gs) and in_unit_or_nan(g)
    # NaN exactly where an input is NaN
    assert np.array_equal(np.isnan(g), np.isnan(ti) | np.isnan(tr))
    assert in_unit_or_nan(bk.g_blinn(ti, tr))


@settings(max_examples=300, deadline=None)
@given(ANGLES, ANGLES, ANGLES, st.floats(1e-3, 10))
def test_g_dots_and_smith(a, b, c, w):
    n = min(a.size, b.size, c.size)
    a, b, c = a[:n], b[:n], c[:n]
    assert in_unit_or_nan(bk.g_modified_dots(a, b, c, w))
    assert in_unit_or_nan(bk.g_blinn_dots(a, b, c))
    for dist in ["beckmann", "ggx"]:
        assert in_unit_or_nan(bk.g_smith_separable(a, b, w, distribution=dist))
        assert in_unit_or_nan(bk.g_smith_correlated(a, b, w, distribution=dist))


VECS = hnp.arrays(np.float64, st.tuples(st.integers(0, 8), st.just(3)), elements=ANY_FLOAT)


@settings(max_examples=300, deadline=None)
@given(VECS, VECS, VECS, st.floats(1e-3, 10), st.booleans())
def test_g_vectors(wi, wo, n, sigma, with_normal):
    k = min(len(wi), len(wo), len(n))
    wi, wo, n = wi[:k], wo[:k], n[:k]
    kw = {"n": n} if with_normal else {}
    gm, gs, g = bk.g_modified_vectors(wi, wo, sigma, terms=True, **kw)
    assert g.shape == (k,)
    assert in_unit_or_nan(gm) and in_unit_or_nan(gs) and in_unit_or_nan(g)
    # NaN where a vector has a NaN component (such a vector is not a direction).
    bad = np.isnan(wi).any(axis=1) | np.isnan(wo).any(axis=1)
    if with_normal:
        bad |= np.isnan(n).any(axis=1)
    assert np.all(np.isnan(g[bad]))


MODELS = bk.models()
DIRS = hnp.arrays(np.float64, st.tuples(st.integers(0, 8), st.just(3)), elements=st.floats(-1e3, 1e3))


@st.composite
def model_and_params(draw):
    m = draw(st.sampled_from(MODELS))
    params = {}
    for p in m["params"]:
        if not draw(st.booleans()):
            continue
        if p["kind"] == "choice":
            params[p["name"]] = draw(st.sampled_from(p["options"]))
        else:
            lo, hi = p["ui_range"]
            params[p["name"]] = draw(st.floats(lo - 0.5, hi + 0.5) | st.sampled_from([math.nan, -math.inf]))
    return m, params


@settings(max_examples=300, deadline=None)
@given(model_and_params(), DIRS, DIRS)
def test_models(mp, wi, wo):
    m, params = mp
    n = min(len(wi), len(wo))
    wi, wo = wi[:n], wo[:n]
    try:
        f = bk.eval(m["name"], wi, wo, **params)
    except ValueError:
        return  # a parameter outside its range: the documented exception
    assert f.shape == (n, 3)
    assert np.all(np.isnan(f) | (f >= 0)), f
    u = np.random.default_rng(n).uniform(size=(n, 2))
    s_wi, weight, pdf = bk.sample(m["name"], wo, u, **params)
    ok = ~np.isnan(pdf)
    assert np.all(pdf[ok] >= 0)
    np.testing.assert_allclose(np.linalg.norm(s_wi[ok], axis=-1), 1, rtol=1e-9)
    if not m["lit_colour"] and n:
        r = bk.albedo(m["name"], wo[:2], **params)
        assert np.all(np.isnan(r) | (r >= 0))
