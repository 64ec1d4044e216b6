"""Template slots: the names a loop template calls that code generation binds.

A template (a plain Python function, see :mod:`ga_rotors.integrators.base`) imports the
slots it uses from this module, so it reads and lints as ordinary Python. The generated
module that instantiates the template defines or imports a compiled function under the
same name instead, chosen for one orientation path, one problem kind
(:mod:`ga_rotors.integrators.kinds`) and one set of declared torques. Calling a slot
directly (running a template uninstantiated) raises :class:`TemplateSlotError`.

Every slot takes and returns tuples of floats (``x`` an orientation state, or a pose for
a motion; ``w`` the rate part, a body angular velocity 3-tuple, or for a motion the
6-tuple ω then a velocity; ``q`` a unit quaternion 4-tuple, ``t``/``h`` floats).

========== ===================================== =========================================
slot       signature                             bound to
========== ===================================== =========================================
torque     torque(t, q, w, params) -> τ          sum of the declared torque kernels, body
                                                 frame (torqued problems only)
accel      accel(t, x, w, inertia, params) -> ω̇  Euler's equations; free: no torque term
                                                 at all; torqued: + torque(t, o_quat(x), ..)
omega      omega(t, params) -> ω                 the prescribed body angular velocity
                                                 (kinematic problems only)
step       one step of the integrator            the integrator's step template for the
                                                 problem kind (used by the loop templates)
loop       the fixed-step loop                   the loop template for the problem kind
                                                 (used by ``judged_run``)
limit      limit(inertia, w, h, nsteps)          the integrator's step limit, measured:
           -> (value, bound)                     its compiled ``measure``
                                                 (:func:`~.limits.measured`); (0, 1) when
                                                 it has none or the problem is kinematic
o_rate     o_rate(x, w) -> ẋ                     the path's kinematics (q̇ = ½ q ⊗ (0, ω),
                                                 Ṙ = ½ R Ω, or the ZYZ angle rates)
o_axpy     o_axpy(x, h, k) -> x + h·k            tuple arithmetic of the path's size
o_rk4      o_rk4(x, h, k1, k2, k3, k4)           x + h/6 (k1 + 2k2 + 2k3 + k4)
o_normalize o_normalize(x) -> x / |x|            unit-sphere paths only (quaternion, rotor)
o_quat     o_quat(x) -> q                        the orientation as a unit quaternion
o_from_quat o_from_quat(q) -> x                  a unit quaternion in the path's coordinates
                                                 (unit-sphere paths only)
o_load     o_load(array) -> x                    read a state from a 1-D array
o_store    o_store(out, row, x)                  write a state into a 2-D array
o_watch    o_watch(t, x, w, h, stats)            the path's own diagnostics (the Euler-angle
                                                 path counts steps near sin θ = 0); a path
                                                 with nothing to watch binds a kernel that
                                                 compiles to no instruction
o_flow     o_flow(x, h, w) -> x'                 the exact flow of constant rates w for a
                                                 time h (the path's group exponential:
                                                 q ⊗ Exp(hω), M exp(hB/2)); motion paths
o_centre   o_centre(x, w, body) -> (q, c, ω, v)  a motion state's orientation, centre of
                                                 mass and its velocity (space), body ω
o_from_centre o_from_centre(q, c, ω, v, body)    the inverse: (x, w) of those
o_motion   o_motion(x, w, body, f) -> ẇ          the equations of motion in the path's rate
                                                 variables under the wrench f = (F, τ_c)
o_free_motion o_free_motion(x, w, body) -> ẇ     the same with no force and no torque
wrench     wrench(t, q, c, w, v, params)         the sum of the declared forces and torques:
           -> (F, τ_c)                           F in space, τ about the centre of mass in
                                                 the body (motion problems only)
r_load     r_load(array) -> w                    read the rate part of a state (the kind's
                                                 ``rate_load``: ω, 3 numbers)
r_store    r_store(out, row, w)                  write it into a 2-D array
r_axpy     r_axpy(w, h, k) -> w + h·k            tuple arithmetic of the rate's size
r_rk4      r_rk4(w, h, k1, k2, k3, k4)           w + h/6 (k1 + 2k2 + 2k3 + k4)
========== ===================================== =========================================

The batched loop (:func:`~ga_rotors.integrators.loops.batch_chunk`) reads and writes its
struct-of-arrays states through slots generated for the sizes at hand: ``chunk_load(x, w,
body, params, lo, hi)`` copies a block of bodies into one array ``s`` of rows
:data:`~.loops.BLOCK` apart (states, rates, bodies with what the kind stores per body,
parameters), ``chunk_store`` copies its states out; ``x_rows(s)`` the tuple of the
block's orientation rows, ``x_get(rows, i)`` body i's state as a tuple, ``x_put(rows, i,
x)`` written back; ``w_rows``, ``w_get``, ``w_put`` the same for the rates;
``body_rows``/``body_get`` the bodies (what the step receives as ``inertia``: the moments,
then what the kind stores per body) and ``param_rows(s, a, lo, hi)``/``param_get`` the
parameters (a tuple per body where every kernel reads its parameters one by one, else
the body's column of ``a`` as an array).
"""

from __future__ import annotations

from ..errors import GaRotorsError

__all__ = [
    "ALL_SLOTS",
    "BATCH_SLOTS",
    "GENERATED_SLOTS",
    "KIND_SLOTS",
    "PATH_SLOTS",
    "TemplateSlotError",
    "accel",
    "body_get",
    "body_rows",
    "chunk_load",
    "chunk_store",
    "limit",
    "loop",
    "o_axpy",
    "o_centre",
    "o_flow",
    "o_free_motion",
    "o_from_centre",
    "o_from_quat",
    "o_load",
    "o_motion",
    "o_normalize",
    "o_quat",
    "o_rate",
    "o_rk4",
    "o_store",
    "o_watch",
    "omega",
    "param_get",
    "param_rows",
    "r_axpy",
    "r_load",
    "r_rk4",
    "r_store",
    "step",
    "torque",
    "w_get",
    "w_put",
    "w_rows",
    "wrench",
    "x_get",
    "x_put",
    "x_rows",
]


#: Slot name -> the attribute of an orientation-path module that binds it.
PATH_SLOTS = {
    "o_rate": "rate",
    "o_axpy": "axpy",
    "o_rk4": "rk4_sum",
    "o_normalize": "normalize",
    "o_quat": "to_quat",
    "o_from_quat": "from_quat",
    "o_load": "load",
    "o_store": "store",
    "o_watch": "watch",
    "o_flow": "flow",
    "o_centre": "centre_of_mass",
    "o_from_centre": "from_centre_of_mass",
    "o_motion": "accel",
    "o_free_motion": "free_accel",
}

#: Slot name -> the attribute of a problem kind that binds it.
KIND_SLOTS = {
    "r_load": "rate_load",
    "r_store": "rate_store",
    "r_axpy": "rate_axpy",
    "r_rk4": "rate_rk4",
}

#: Slots of the batched loop, written for the sizes of one batch.
BATCH_SLOTS = ("chunk_load", "chunk_store", "x_rows", "x_get", "x_put", "w_rows", "w_get",
               "w_put", "body_rows", "body_get", "param_rows", "param_get")  # fmt: skip

#: Slots whose definition the code generator writes.
GENERATED_SLOTS = ("torque", "accel", "omega", "wrench", "step", "loop", "limit", *BATCH_SLOTS)


class TemplateSlotError(GaRotorsError, RuntimeError):
    """A template slot was called outside a generated module.

    Examples
    --------
    A step template run as plain Python reaches its first slot:

    >>> from ga_rotors.integrators.rk4 import rk4_step
    >>> rk4_step(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.1, (1.0, 1.0, 2.0), ())
    Traceback (most recent call last):
    ...
    ga_rotors.integrators.slots.TemplateSlotError: template slot 'o_rate' called directly; ...
    """


def _slot_examples(name: str) -> str:
    # Each slot's Examples: what binds it, and what calling it unbound does.
    if name in PATH_SLOTS:
        bound = (
            f"    >>> PATH_SLOTS[{name!r}]  # each path module's kernel of this name binds it\n"
            f"    {PATH_SLOTS[name]!r}\n"
        )
    elif name in KIND_SLOTS:
        bound = (
            f"    >>> KIND_SLOTS[{name!r}]  # the problem kind's kernel of this name binds it\n"
            f"    {KIND_SLOTS[name]!r}\n"
        )
    else:
        bound = (
            f"    >>> {name!r} in GENERATED_SLOTS  # the code generator writes its definition\n"
            "    True\n"
        )
    return (
        "\n\n    Examples\n    --------\n" + bound + f"    >>> {name}()\n"
        "    Traceback (most recent call last):\n    ...\n"
        f"    ga_rotors.integrators.slots.TemplateSlotError: template slot {name!r} called "
        "directly; ...\n"
    )


def _slot(name: str, doc: str):
    def slot(*args):
        raise TemplateSlotError(
            f"template slot {name!r} called directly; templates run only through the "
            "module ga_rotors.integrators generates for them (Integrator.run)"
        )

    slot.__name__ = slot.__qualname__ = name
    slot.__doc__ = doc + _slot_examples(name)
    slot.__module__ = __name__
    return slot


torque = _slot("torque", "τ = torque(t, q, w, params): declared torques, body frame.")
accel = _slot("accel", "ω̇ = accel(t, x, w, inertia, params): Euler's equations.")
omega = _slot("omega", "ω = omega(t, params): prescribed body angular velocity.")
step = _slot("step", "The integrator's step for the problem kind.")
loop = _slot("loop", "rows = loop(x0, w0, t0, h, first, nsteps, every, ...): the loop.")
limit = _slot("limit", "value, bound = limit(inertia, w, h, nsteps): the measured step limit.")
o_rate = _slot("o_rate", "ẋ = o_rate(x, w): the orientation path's kinematics.")
o_axpy = _slot("o_axpy", "x + h·k on the path's state.")
o_rk4 = _slot("o_rk4", "x + h/6 (k1 + 2 k2 + 2 k3 + k4) on the path's state.")
o_normalize = _slot("o_normalize", "x / |x| (unit-sphere paths).")
o_quat = _slot("o_quat", "q = o_quat(x): the orientation as a unit quaternion.")
o_from_quat = _slot("o_from_quat", "x = o_from_quat(q): a unit quaternion in path coordinates.")
o_load = _slot("o_load", "x = o_load(array): read a state.")
o_store = _slot("o_store", "o_store(out, row, x): write a state.")
o_watch = _slot("o_watch", "o_watch(t, x, w, h, stats): path diagnostics.")
o_flow = _slot("o_flow", "x' = o_flow(x, h, w): the exact flow of constant rates for h.")
o_centre = _slot("o_centre", "q, c, ω, v = o_centre(x, w, body): the centre of mass's state.")
o_from_centre = _slot("o_from_centre", "x, w = o_from_centre(q, c, ω, v, body): its inverse.")
o_motion = _slot("o_motion", "ẇ = o_motion(x, w, body, f): equations of motion, wrench f.")
o_free_motion = _slot("o_free_motion", "ẇ = o_free_motion(x, w, body): with no wrench.")
wrench = _slot("wrench", "F, τ = wrench(t, q, c, w, v, params): declared forces and torques.")
r_load = _slot("r_load", "w = r_load(array): read the rate part of a state.")
r_store = _slot("r_store", "r_store(out, row, w): write the rate part of a state.")
r_axpy = _slot("r_axpy", "w + h·k on the rate part of the state.")
r_rk4 = _slot("r_rk4", "w + h/6 (k1 + 2 k2 + 2 k3 + k4) on the rate part of the state.")
chunk_load = _slot("chunk_load", "s = chunk_load(x, w, body, params, lo, hi): a block's rows.")
chunk_store = _slot("chunk_store", "chunk_store(s, out_x, out_w, lo, hi): its states out.")
x_rows = _slot("x_rows", "rows = x_rows(s): the block's orientation rows.")
x_get = _slot("x_get", "x = x_get(rows, i): body i's orientation state.")
x_put = _slot("x_put", "x_put(rows, i, x): write body i's orientation state.")
w_rows = _slot("w_rows", "rows = w_rows(s): the block's rate rows.")
w_get = _slot("w_get", "w = w_get(rows, i): body i's rates.")
w_put = _slot("w_put", "w_put(rows, i, w): write body i's rates.")
body_rows = _slot("body_rows", "rows = body_rows(s): the block's bodies, stored values too.")
body_get = _slot("body_get", "inertia = body_get(rows, i): body i as its step receives it.")
param_rows = _slot("param_rows", "rows = param_rows(s, a, lo, hi): the block's parameters.")
param_get = _slot("param_get", "params = param_get(rows, i): body i's torque parameters.")

ALL_SLOTS = frozenset(PATH_SLOTS) | frozenset(KIND_SLOTS) | frozenset(GENERATED_SLOTS)
