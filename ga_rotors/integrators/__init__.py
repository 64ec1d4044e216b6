"""Integrators: a registry of compiled, specialised fixed-step methods.

The interface (how to add an integrator, the template slots, torques, the code
generation that makes numba's cache work) is documented in
:mod:`ga_rotors.integrators.base` and, step by step, in ``docs/extending.md``. Use
:func:`get` to look one up, :func:`catalogue` to list them, and
:func:`ga_rotors.simulation.simulate` to run one.
"""

from .base import (
    ANY_TORQUE,
    FREE,
    KINEMATIC,
    ORIENTATION_TORQUES,
    TORQUED,
    Integrator,
    LoopResult,
    PrescribedOmega,
    Problem,
    TorqueTerm,
    catalogue,
    get,
    names,
    register,
    torque_conflict,
)
from .template import TemplateIntegrator

__all__ = [
    "ANY_TORQUE",
    "FREE",
    "KINEMATIC",
    "ORIENTATION_TORQUES",
    "TORQUED",
    "Integrator",
    "LoopResult",
    "PrescribedOmega",
    "Problem",
    "TemplateIntegrator",
    "TorqueTerm",
    "catalogue",
    "get",
    "names",
    "register",
    "torque_conflict",
]
