"""Shared cases: one scene-file description per phase model and a few extremes."""
import pytest

# Every model by its scene-file name (docs/phase.md); the Mie tables are small ones.
MODELS = {
    "isotropic": {"model": "isotropic"},
    "hg": {"model": "hg", "g": 0.8},
    "hg_backward": {"model": "hg", "g": -0.5},
    "hg_0_9999": {"model": "hg", "g": 0.9999},
    "rayleigh": {"model": "rayleigh"},
    "double_hg": {"model": "double-hg", "g1": 0.8, "g2": -0.3, "w": 0.7},
    "cornette_shanks": {"model": "cornette-shanks", "g": 0.76},
    "draine": {"model": "draine", "g": 0.5, "alpha": 0.8},
    "jendersie_deon": {"model": "jendersie-deon", "diameter_um": 10.0},
    "mie_x1": {"model": "mie", "m": 1.5, "x": 1.0},
    "mie_x30_absorbing": {"model": "mie", "m": [1.33, 0.01], "x": 30.0},
}


@pytest.fixture(params=sorted(MODELS), ids=sorted(MODELS))
def description(request):
    return MODELS[request.param]
