"""The rough dielectric (Walter et al. 2007) and the Charlie sheen (Estevez and Kulla 2017)
through the Python package, against their formulas written out here from the papers and
against the generalised reciprocity of a BTDF (Veach 1997, §5.2)."""

import numpy as np
import pytest

import brdf_kernels as bk


def unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def random_dirs(rng, n, upper):
    """n random unit vectors on the upper (z > 0.05) or lower (z < -0.05) hemisphere."""
    v = unit(rng.normal(size=(n, 3)))
    v[:, 2] = np.maximum(np.abs(v[:, 2]), 0.05)
    v = unit(v)
    if not upper:
        v[:, 2] = -v[:, 2]
    return v


def fresnel_dielectric(c, eta):
    """Unpolarised Fresnel reflectance at |cos| = c for the relative index eta = n_t / n_i
    (Walter et al. 2007, eq 22); 1 past the critical angle."""
    g2 = eta * eta - 1.0 + c * c
    g = np.sqrt(np.maximum(g2, 0.0))
    a = (g - c) / (g + c)
    b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0)
    return np.where(g2 < 0.0, 1.0, 0.5 * a * a * (1.0 + b * b))


def ggx_d(cos_h, alpha):
    """GGX normal distribution (Walter eq 33)."""
    c2 = cos_h * cos_h
    t2 = (1.0 - c2) / c2
    return alpha**2 / (np.pi * c2 * c2 * (alpha**2 + t2) ** 2)


def ggx_g1(cos_v, alpha):
    """GGX Smith G1 (Walter eq 34), for a direction on the facet's front side."""
    c2 = cos_v * cos_v
    return 2.0 / (1.0 + np.sqrt(1.0 + alpha**2 * (1.0 - c2) / c2))


@pytest.mark.parametrize("alpha,eta", [(0.3, 1.5), (0.7, 1.33), (0.15, 1 / 1.5)])
def test_rough_dielectric_reflection_matches_walter_eq_20(alpha, eta):
    rng = np.random.default_rng(7)
    wi = random_dirs(rng, 200, True)
    wo = random_dirs(rng, 200, True)
    h = unit(wi + wo)
    ci, co, ch = wi[:, 2], wo[:, 2], h[:, 2]
    ih = np.sum(wi * h, axis=-1)
    want = (
        fresnel_dielectric(ih, eta) * ggx_d(ch, alpha) * ggx_g1(ci, alpha) * ggx_g1(co, alpha)
        / (4.0 * ci * co)
    )
    got = bk.eval("rough-dielectric", wi, wo, alpha=alpha, eta=eta)
    # f64 on both sides; the kernel and this transcription differ only by rounding (the
    # D denominator's cancellation near h = n costs a few ulp): 1e-10 relative.
    np.testing.assert_allclose(got[:, 0], want, rtol=1e-10)
    np.testing.assert_array_equal(got[:, 0], got[:, 2])


@pytest.mark.parametrize("eta", [1.5, 1 / 1.5, 2.4])
def test_rough_dielectric_transmission_obeys_generalised_reciprocity(eta):
    # Veach (1997) eq 5.14: f_t(i -> o) / n_o^2 = f_t(o -> i) / n_i^2, with n = 1 above the
    # surface and n = eta below. With wo above (n_o = 1) and wi below (n_i = eta):
    # f(wi, wo) = f(wo, wi) / eta^2 in the radiance convention.
    rng = np.random.default_rng(11)
    wi = random_dirs(rng, 2000, False)
    wo = random_dirs(rng, 2000, True)
    fwd = bk.eval("rough-dielectric", wi, wo, alpha=0.4, eta=eta)[:, 0]
    back = bk.eval("rough-dielectric", wo, wi, alpha=0.4, eta=eta)[:, 0]
    lit = fwd > 1e-12
    # Only pairs whose refraction facet faces both directions transmit (about one in five).
    assert lit.sum() > 200
    # Rounding only: relative 1e-9, and 1e-12 of the largest value for the pairs whose
    # facet is nearly tangent to one direction (docs/conventions.md §12: the error grows as
    # 1 / ((1 - F) min(|i.h|, |o.h|)) there).
    np.testing.assert_allclose(fwd[lit] * eta**2, back[lit], rtol=1e-9, atol=1e-12 * back.max())
    # And the pairs with no transmission are zero both ways.
    assert np.all(back[~lit] <= 1e-12 * eta**2)


def test_rough_dielectric_sample_weights_agree_with_eval_and_pdf():
    # weight = f |cos wi| / pdf: each sampled direction checked against eval and the pdf the
    # sampler returns (both sides of the surface are reached).
    rng = np.random.default_rng(3)
    wo = np.tile(unit([0.3, -0.2, 0.8]), (4000, 1))
    u = rng.uniform(0.0, 1.0, (4000, 2))
    wi, weight, pdf = bk.sample("rough-dielectric", wo, u, alpha=0.5, eta=1.5)
    ok = np.isfinite(pdf) & (pdf > 0)
    assert ok.mean() > 0.95
    below = wi[ok, 2] < 0
    assert 0.5 < below.mean() < 0.99, "most light enters glass at 37 degrees, some reflects"
    f = bk.eval("rough-dielectric", wi[ok], wo[ok], alpha=0.5, eta=1.5)[:, 0]
    np.testing.assert_allclose(weight[ok, 0], f * np.abs(wi[ok, 2]) / pdf[ok], rtol=1e-9)


def test_rough_dielectric_u_equal_one_samples_as_the_float_below_one():
    # The documented clamp of u into [0, 1) (brdf_core::sampling): u = 1.0 from a float RNG
    # is the largest float below 1, not a failure; a NaN u is a failed sample (NaN out).
    below_one = np.nextafter(1.0, 0.0)
    for u0, u1 in [(1.0, 0.5), (0.5, 1.0), (1.0, 1.0)]:
        a = bk.sample("rough-dielectric", [0.2, 0, 1], [u0, u1], alpha=0.3, eta=1.5)
        b = bk.sample(
            "rough-dielectric", [0.2, 0, 1], [min(u0, below_one), min(u1, below_one)],
            alpha=0.3, eta=1.5,
        )
        for x, y in zip(a, b):
            np.testing.assert_array_equal(x, y)
        assert np.all(np.isfinite(a[0])) and np.isfinite(a[2]) and a[2] > 0
    wi, weight, pdf = bk.sample("rough-dielectric", [0, 0, 1], [np.nan, 0.5], alpha=0.3, eta=1.5)
    assert np.all(np.isnan(wi)) and np.all(np.isnan(weight)) and np.isnan(pdf)


def test_rough_dielectric_parameters_are_range_checked():
    with pytest.raises(ValueError, match="eta"):
        bk.eval("rough-dielectric", [0, 0, 1], [0, 0, 1], eta=20.0)
    with pytest.raises(ValueError, match="distribution"):
        bk.eval("rough-dielectric", [0, 0, 1], [0, 0, 1], distribution="phong")


@pytest.mark.parametrize("r", [0.3, 0.6, 1.0])
def test_sheen_ashikhmin_matches_charlie_d_times_v(r):
    # Estevez and Kulla (2017) eq 2: D = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi), a = r^2;
    # Ashikhmin's visibility V = 1 / (4 (mu_i + mu_o - mu_i mu_o)).
    rng = np.random.default_rng(5)
    wi = random_dirs(rng, 200, True)
    wo = random_dirs(rng, 200, True)
    h = unit(wi + wo)
    a = r * r
    sin_h = np.sqrt(np.maximum(1.0 - h[:, 2] ** 2, 0.0))
    d = (2.0 + 1.0 / a) * sin_h ** (1.0 / a) / (2.0 * np.pi)
    v = 1.0 / (4.0 * (wi[:, 2] + wo[:, 2] - wi[:, 2] * wo[:, 2]))
    got = bk.eval("sheen", wi, wo, roughness=r, visibility="ashikhmin", color=[1.0, 0.5, 0.25])
    np.testing.assert_allclose(got[:, 0], d * v, rtol=1e-10, atol=1e-300)
    np.testing.assert_allclose(got[:, 1], 0.5 * d * v, rtol=1e-10, atol=1e-300)
    np.testing.assert_allclose(got[:, 2], 0.25 * d * v, rtol=1e-10, atol=1e-300)


def test_sheen_is_reciprocal_for_both_visibilities():
    rng = np.random.default_rng(9)
    wi = random_dirs(rng, 300, True)
    wo = random_dirs(rng, 300, True)
    for vis in ["estevez-kulla", "ashikhmin"]:
        a = bk.eval("sheen", wi, wo, roughness=0.5, visibility=vis)
        b = bk.eval("sheen", wo, wi, roughness=0.5, visibility=vis)
        np.testing.assert_allclose(a, b, rtol=1e-12)


def test_catalogue_lists_both_models_with_their_parameters():
    names = {m["name"]: m for m in bk.models()}
    assert {"sheen", "rough-dielectric"} <= set(names)
    sheen = {p["name"] for p in names["sheen"]["params"]}
    assert {"roughness", "visibility", "color"} <= sheen
    glass = {p["name"] for p in names["rough-dielectric"]["params"]}
    assert {"alpha", "eta", "distribution"} <= glass
