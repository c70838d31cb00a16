"""kasumi.mie against published tables (Bohren & Huffman app. A; Wiscombe's MIEV0 tests)."""
import numpy as np
import pytest

import kasumi
from kasumi import mie


def test_bohren_huffman_appendix_a():
    # BH app. A: r = 0.525 µm, λ = 0.6328 µm, m = 1.55; x = 5.2128 (5.213 rounded: Qext moves
    # by 4e-4 between the two).
    q = mie.efficiencies(1.55, 2 * np.pi * 0.525 / 0.6328)
    assert q.qext == pytest.approx(3.10543, abs=1e-5)
    assert q.qsca == pytest.approx(3.10543, abs=1e-5)
    assert q.qback == pytest.approx(2.92534, abs=1e-5)
    assert q.g == pytest.approx(0.63314, abs=1e-5)
    assert q.qabs == 0.0
    qext, qsca, qback, g = q
    assert (qext, g) == (q.qext, q.g)


# Wiscombe MIEV0 (MVTstNew.f): x, m in MIEV0's convention n - ik, Qext, Qsca, g Qsca.
WISCOMBE = [
    (10.0, 0.75 + 0j, 2.232265e+00, 2.232265e+00, 2.001164e+00),
    (1000.0, 0.75 + 0j, 1.997908e+00, 1.997908e+00, 1.688121e+00),
    (1.0, 1.33 - 1e-5j, 9.395198e-02, 9.392330e-02, 1.733048e-02),
    (100.0, 1.33 - 1e-5j, 2.101321e+00, 2.096594e+00, 1.821854e+00),
    (1.0, 1.5 - 1j, 2.336321e+00, 6.634538e-01, 1.274736e-01),
    (100.0, 1.5 - 1j, 2.097502e+00, 1.283697e+00, 1.091466e+00),
    (1.0, 10 - 10j, 2.532993e+00, 2.049405e+00, -2.267961e-01),
]


@pytest.mark.parametrize("x, m, qext, qsca, gqsc", WISCOMBE)
def test_wiscombe_miev0(x, m, qext, qsca, gqsc):
    q = mie.efficiencies(np.conj(m), x)  # BH: m = n + ik
    assert q.qext == pytest.approx(qext, rel=1e-6)
    assert q.qsca == pytest.approx(qsca, rel=1e-6)
    assert q.g * q.qsca == pytest.approx(gqsc, rel=1e-6)


def test_wiscombe_case_14_amplitudes():
    mu = np.cos(np.radians(np.arange(0, 181, 30)))
    s1, s2 = mie.amplitudes(1.5 + 1j, 1.0, mu)
    assert s1.dtype == np.complex128 and s1.shape == mu.shape
    s1_ref = np.array([0.584080, 0.565702, 0.517525, 0.456340, 0.400212, 0.362157, 0.348844]) \
        - 1j * np.array([0.190515, 0.187200, 0.178443, 0.167167, 0.156643, 0.149391, 0.146829])
    s2_ref = np.array([0.584080, 0.500161, 0.287964, 0.0362285, -0.174875, -0.305682,
                       -0.348844]) \
        - 1j * np.array([0.190515, 0.145611, 0.041054, -0.0618265, -0.122959, -0.143846,
                         -0.146829])
    np.testing.assert_allclose(s1, s1_ref, atol=1e-6)
    np.testing.assert_allclose(s2, s2_ref, atol=1e-6)


@pytest.mark.parametrize("x", [0.5, 7.0, 250.0])
def test_optical_theorem(x):
    # Qext = 4 Re S(0) / x² (BH eq. 4.76).
    s1, _ = mie.amplitudes(1.5 + 0.1j, x, np.array([1.0]))
    assert 4 * s1[0].real / x**2 == pytest.approx(mie.efficiencies(1.5 + 0.1j, x).qext, rel=1e-9)


def test_amplitudes_keep_shape():
    s1, s2 = mie.amplitudes(1.33, 3.0, np.zeros((3, 2)))
    assert s1.shape == (3, 2) and s2.shape == (3, 2)


@pytest.mark.parametrize("m, x, why", [
    (1.33, 0.0, "size parameter"),
    (1.33, 2e5, "size parameter"),
    (1.33 - 0.1j, 1.0, "imaginary part must be >= 0"),
    (-1.0, 1.0, "real part"),
])
def test_bad_input_is_a_scene_error(m, x, why):
    with pytest.raises(kasumi.SceneError, match=why):
        mie.efficiencies(m, x)


@pytest.mark.parametrize("dist", [mie.LogNormal(0.5, 0.3), mie.ModifiedGamma(4.0, 6.0, 1.0)])
def test_size_distributions_are_normalised(dist):
    lo, hi = mie.scattering_radius_range(dist)
    assert 0 < lo < mie.dominant_radius_um(dist) < hi
    r = np.logspace(-4, 3, 200001)
    assert np.trapz(mie.number_density(dist, r), r) == pytest.approx(1.0, abs=1e-6)


def test_deirmendjian_c1_mode_radius():
    # n(r) ∝ r^6 exp(-1.5 r) peaks at r_c = 4 µm.
    r = np.linspace(3.0, 5.0, 2001)
    assert r[np.argmax(mie.number_density(mie.ModifiedGamma(4.0, 6.0, 1.0), r))] == \
        pytest.approx(4.0, abs=1e-3)
