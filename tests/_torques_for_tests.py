"""Torque and ω(t) kernels used only by the tests (importable by generated modules)."""

from math import cos, sin

from ga_rotors._jit import jit


@jit
def counting_torque(t, q, w, p):
    """Counts its own evaluations in p[0]; returns the constant torque p[1:4]."""
    p[0] += 1.0
    return (p[1], p[2], p[3])


@jit
def tripwire_torque(t, q, w, p):
    """Must never run: the tests declare it nowhere."""
    raise AssertionError("an undeclared torque was evaluated")


@jit
def constant_body_torque(t, q, w, p):
    """A constant body-frame torque (p[0], p[1], p[2])."""
    return (p[0], p[1], p[2])


@jit
def linear_damping(t, q, w, p):
    """τ = -c ω."""
    c = p[0]
    return (-c * w[0], -c * w[1], -c * w[2])


@jit
def wobble(t, p):
    """ω(t) = (a cos νt, a sin νt, s): a prescribed coning motion."""
    a, nu, s = p[0], p[1], p[2]
    return (a * cos(nu * t), a * sin(nu * t), s)


@jit
def constant_omega(t, p):
    """ω(t) = (p0, p1, p2)."""
    return (p[0], p[1], p[2])


@jit
def turning_torque(t, q, w, p):
    """A body torque of time alone, turning about axis 3: p[0] (cos p[1]t, sin p[1]t, 0)."""
    return (p[0] * cos(p[1] * t), p[0] * sin(p[1] * t), 0.0)
