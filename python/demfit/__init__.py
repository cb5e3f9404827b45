"""demfit: identify DEM contact parameters from measured curves.

The compiled module _demfit does the work; this package re-exports it. See docs/python.md.
SI units, except where a curve label names its unit (volume_cm3, pressure_MPa, x_mm...).
"""
from ._demfit import (  # noqa: F401
    Curve,
    Error,
    InputError,
    SimulationResult,
    Study,
    SurfaceProfile,
    diagnose,
    identify,
    open_study,
    resume,
    simulate,
    surface_profile,
)

__all__ = [
    "Curve",
    "Error",
    "InputError",
    "SimulationResult",
    "Study",
    "SurfaceProfile",
    "diagnose",
    "identify",
    "open_study",
    "resume",
    "simulate",
    "surface_profile",
]
