"""kasumi.phase: models by scene-file description, eval/pdf on arrays, located errors."""
import numpy as np
import pytest

import kasumi
from kasumi import phase
from quadrature import integrate


def test_every_model_name_is_listed():
    assert set(phase.models()) == {"isotropic", "rayleigh", "hg", "double-hg", "cornette-shanks",
                                   "draine", "jendersie-deon", "tabulated", "mie"}


def test_normalisation_and_mean_cosine_equal_the_library(description):
    p = phase.make(description)
    # The library's own quadrature and closed forms (phase_quadrature, mean_cosine) ...
    assert p.normalisation() == pytest.approx(1.0, abs=1e-6)
    assert p.mean_cosine_quadrature() == pytest.approx(p.mean_cosine(), abs=1e-6)
    # ... and an independent NumPy quadrature of the arrays eval() returns.
    norm = 2 * np.pi * integrate(p.eval, -1.0, 1.0)
    g = 2 * np.pi * integrate(lambda mu: mu * p.eval(mu), -1.0, 1.0)
    assert norm == pytest.approx(p.normalisation(), abs=2e-5)
    assert g == pytest.approx(p.mean_cosine_quadrature(), abs=2e-5)


def test_tabulated_from_a_file(tmp_path):
    table = tmp_path / "table.csv"
    table.write_text("theta_deg,value\n0,20\n10,8\n30,2\n90,0.5\n150,0.8\n180,1\n")
    p = phase.make({"model": "tabulated", "file": str(table)})
    assert p.model == "tabulated"
    assert p.normalisation() == pytest.approx(1.0, abs=1e-6)
    assert 2 * np.pi * integrate(lambda mu: mu * p.eval(mu), -1, 1) == pytest.approx(
        p.mean_cosine(), abs=1e-4)


def test_eval_keeps_any_shape_and_matches_the_formula():
    g = 0.8
    p = phase.make({"model": "hg", "g": g})
    mu = np.linspace(-1.0, 1.0, 24).reshape(2, 3, 4)
    value = p.eval(mu)
    assert value.shape == mu.shape and value.dtype == np.float64
    hg = (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)
    np.testing.assert_allclose(value, hg, rtol=1e-6)  # g is a float in the library
    np.testing.assert_array_equal(p.pdf(mu), value)
    assert p.eval(0.5).shape == ()
    assert p.eval([0.5, 1.0]).shape == (2,)


def test_eval_into_a_given_array():
    p = phase.make({"model": "rayleigh"})
    mu = np.linspace(-1, 1, 11)
    out = np.empty_like(mu)
    assert p.eval(mu, out=out) is not None
    np.testing.assert_array_equal(out, p.eval(mu))
    with pytest.raises(TypeError, match="float64"):
        p.eval(mu, out=np.empty(11, np.float32))
    with pytest.raises(ValueError, match="shape"):
        p.pdf(mu, out=np.empty(12))


def test_float32_input_takes_the_renderers_float_path():
    p = phase.make({"model": "hg", "g": 0.9})
    mu32 = np.linspace(-1, 1, 101, dtype=np.float32)
    v = p.eval(mu32)
    assert v.dtype == np.float32
    np.testing.assert_allclose(v, p.eval(mu32.astype(np.float64)), rtol=1e-6)


def test_large_arrays_are_vectorised():
    p = phase.make({"model": "draine", "g": 0.5, "alpha": 0.8})
    mu = np.random.default_rng(1).uniform(-1, 1, 2_000_000)
    assert np.all(p.eval(mu) > 0)


def test_bad_parameter_raises_scene_error_with_the_pointer():
    with pytest.raises(kasumi.SceneError) as e:
        phase.make({"model": "hg", "g": 1.2})
    assert isinstance(e.value, ValueError)
    assert str(e.value) == "phase: /g = 1.2: must be in (-1, 1)"


def test_error_is_located_like_the_scene_loader():
    with pytest.raises(kasumi.SceneError, match=r"^scene\.json: /media/0/phase/g = 1\.2: "):
        phase.make({"model": "hg", "g": 1.2}, source="scene.json", pointer="/media/0/phase")


@pytest.mark.parametrize("description, where", [
    ({"model": "fog"}, "/model"),
    ({"model": "hg"}, "/"),
    ({"model": "hg", "g": 0.5, "gg": 1}, "gg"),
    ({"model": "mie", "m": [1.33, -0.1], "x": 3}, "/m/1"),
    ({"model": "double-hg", "g1": 0.5, "g2": 0.1, "w": 2}, "/w"),
])
def test_invalid_models_name_the_pointer(description, where):
    with pytest.raises(kasumi.SceneError, match=where):
        phase.make(description)


def test_import_forms():
    import kasumi.phase as kp
    from kasumi.mie import efficiencies  # noqa: F401
    assert kp is phase
