"""kasumi: the renderer from Python: scenes rendered and probed into NumPy arrays, phase
functions, Lorenz-Mie theory and their validation.

Conventions are the scene format's: metres, photometric lights, pixels in scene-linear Rec.709
with luminance in cd/m²; mu = cos(theta) with +1 forward (undeflected) scattering;
phase functions and pdfs are per steradian and integrate to 1 over the sphere. See docs/python.md.
"""
import sys as _sys

from ._kasumi import RenderResult, Scene, SceneError, mie, phase, read_exr

# `import kasumi.phase` and `from kasumi.mie import efficiencies` find the submodules.
_sys.modules[__name__ + ".phase"] = phase
_sys.modules[__name__ + ".mie"] = mie

__all__ = ["RenderResult", "Scene", "SceneError", "mie", "phase", "read_exr"]
