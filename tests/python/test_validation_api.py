"""kasumi.phase.validate: the checks of `kasumi phase validate`, as a dict with p-values."""
import pytest

import kasumi
from kasumi import phase


def test_hg_09999_passes_with_the_cli_defaults():
    # Failed with the former rule (p = 0.0068 against 0.01) at the CLI's default seed.
    report = phase.validate({"model": "hg", "g": 0.9999})
    assert report["passed"], report
    assert report["model"] == "hg"
    assert report["samples"] == 4_000_000 and report["seed"] == 1
    assert report["significance"] == 1e-4 and report["alpha"] == pytest.approx(1e-4)
    assert "false-failure rate 0.0001" in report["decision_rule"]
    names = [c["name"] for c in report["checks"]]
    assert names == ["normalisation", "mean_cosine", "reciprocity", "sample_pdf_eval",
                     "chi_square"]
    for c in report["checks"]:
        if c["name"] == "chi_square":
            assert c["p_value"] > c["alpha"] == pytest.approx(1e-4)
            assert c["value"] == c["p_value"]
        else:
            assert c["p_value"] is None and c["alpha"] is None


def test_sidak_over_a_run_of_models():
    report = phase.validate(phase.make({"model": "rayleigh"}), samples=200_000, seed=3,
                            n_tests=33)
    assert report["alpha"] == pytest.approx(1 - (1 - 1e-4) ** (1 / 33))
    assert report["passed"]


def test_power_of_the_default_run():
    # A 1 % error in 1 - g at g = 0.9999 is caught with probability >= 0.99.
    assert phase.chi_square_power({"model": "hg", "g": 0.9999},
                                  {"model": "hg", "g": 0.999899}) >= 0.99


def test_invalid_model_raises_scene_error():
    with pytest.raises(kasumi.SceneError, match="/g"):
        phase.validate({"model": "hg", "g": -1.0})
    with pytest.raises(ValueError, match="samples"):
        phase.validate({"model": "hg", "g": 0.5}, samples=10)
