"""Sample/pdf agreement from NumPy: sample() histogrammed in mu against the pdf integrated over
each bin, by a chi-square test whose p-value comes from the library's incomplete gamma.

False-failure rate: 1e-4 for this file, Šidák over its models (each test compares its p-value
with 1 - (1 - 1e-4)^(1/n)); seeds are fixed, so a build passes or fails deterministically. The
planted fault (HG 0.8 sampled, HG 0.78 expected) shows the test can fail.
"""
import numpy as np
import pytest

from conftest import MODELS
from kasumi import phase
from quadrature import integrate

N = 1_000_000
ALPHA = 1 - (1 - 1e-4) ** (1 / len(MODELS))


def edges():
    """mu bins: 64 uniform steps plus 1 - |mu| = 10^-k, k = 2..9, toward both poles."""
    fine = 10.0 ** -np.arange(2, 10)
    return np.unique(np.concatenate([np.linspace(-1, 1, 65), -1 + fine, 1 - fine]))


def chi_square(sampled, expected_phase, seed=7):
    rng = np.random.default_rng(seed)
    u1, u2 = rng.random(N), rng.random(N)
    mu, pdf = sampled.sample(u1, u2)
    e = edges()
    observed = np.histogram(mu, e)[0].astype(float)
    mass = np.array([2 * np.pi * integrate(expected_phase.pdf, a, b, n=401)
                     for a, b in zip(e[:-1], e[1:])])
    expected = N * mass / mass.sum()
    # Cells expecting fewer than 5 samples are pooled into one.
    small = expected < 5
    obs = np.append(observed[~small], observed[small].sum())
    exp = np.append(expected[~small], expected[small].sum())
    if exp[-1] < 5:
        obs, exp = obs[:-1], exp[:-1]
    statistic = np.sum((obs - exp) ** 2 / exp)
    dof = len(obs) - 1
    return phase.chi_square_q(dof / 2, statistic / 2), mu, pdf


def test_sample_follows_pdf(description):
    p = phase.make(description)
    p_value, mu, pdf = chi_square(p, p)
    assert p_value > ALPHA, f"{description}: p = {p_value}"
    # The returned pdf is the density at the returned mu (float direction: 1e-3 relative).
    np.testing.assert_allclose(pdf, p.pdf(mu), rtol=2e-2)
    assert np.all((mu >= -1) & (mu <= 1))


def test_a_wrong_sampler_fails():
    p_value, _, _ = chi_square(phase.make({"model": "hg", "g": 0.8}),
                               phase.make({"model": "hg", "g": 0.78}))
    assert p_value < 1e-10
