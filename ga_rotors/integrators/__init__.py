"""Integrators: a registry of compiled, specialised fixed-step methods.

The interface (how to add an integrator, the template slots, torques, the code
generation that makes numba's cache work) is documented in
:mod:`ga_rotors.integrators.base` and, step by step, in ``docs/extending.md``; problem
kinds (what a kind of problem brings to a loop) in :mod:`ga_rotors.integrators.kinds`.
Use :func:`get` to look one up, :func:`catalogue` to list them, :meth:`Integrator.run` to
run one, and :func:`ga_rotors.simulation.simulate` to simulate a body.
"""

from .base import (
    ANY_TORQUE,
    FREE,
    KINEMATIC,
    MOTION,
    ORIENTATION_TORQUES,
    TORQUED,
    Batch,
    ForceTerm,
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
from .kinds import KINDS, ProblemKind, SlotSource, register_kind
from .template import TemplateIntegrator

__all__ = [
    "ANY_TORQUE",
    "FREE",
    "KINDS",
    "KINEMATIC",
    "MOTION",
    "ORIENTATION_TORQUES",
    "TORQUED",
    "Batch",
    "ForceTerm",
    "Integrator",
    "LoopResult",
    "PrescribedOmega",
    "Problem",
    "ProblemKind",
    "SlotSource",
    "TemplateIntegrator",
    "TorqueTerm",
    "catalogue",
    "get",
    "names",
    "register",
    "register_kind",
    "torque_conflict",
]
