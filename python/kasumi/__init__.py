"""kasumi: the renderer's phase functions, Lorenz-Mie theory and their validation from Python.

Conventions are the scene format's: mu = cos(theta) with +1 forward (undeflected) scattering;
phase functions and pdfs are per steradian and integrate to 1 over the sphere. See docs/python.md.
"""
import sys as _sys

from ._kasumi import SceneError, mie, phase

# `import kasumi.phase` and `from kasumi.mie import efficiencies` find the submodules.
_sys.modules[__name__ + ".phase"] = phase
_sys.modules[__name__ + ".mie"] = mie

__all__ = ["SceneError", "mie", "phase"]
