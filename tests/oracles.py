"""Independent oracles and test data shared by the rotation tests (scipy is the oracle)."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

#: float64 unit round-off, 2**-53.
U = 2.0**-53


def to_scipy(q) -> Rotation:
    """scipy wants scalar-last (x, y, z, w)."""
    q = np.asarray(q, dtype=float)
    return Rotation.from_quat(np.concatenate([q[..., 1:], q[..., :1]], axis=-1))


def from_scipy(r: Rotation) -> np.ndarray:
    return r.as_quat(scalar_first=True)


def rotation_error(q, r: Rotation) -> np.ndarray:
    """Geodesic angle between our quaternions and scipy rotations, computed by scipy."""
    return (to_scipy(q).inv() * r).magnitude()


def random_unit(seed: int, n: int) -> np.ndarray:
    q = np.random.default_rng(seed).normal(size=(n, 4))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def random_axes(seed: int, n: int) -> np.ndarray:
    v = np.random.default_rng(seed).normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def half_turns(seed: int, n: int) -> np.ndarray:
    """Half-turns about random axes: w = 0 exactly (trace of the matrix = -1)."""
    return np.concatenate([np.zeros((n, 1)), random_axes(seed, n)], axis=-1)


component = st.floats(-1.0, 1.0, allow_nan=False)
unit_quaternions = (
    st.tuples(component, component, component, component)
    .filter(lambda q: sum(c * c for c in q) > 1e-3)
    .map(lambda q: np.array(q) / np.linalg.norm(q))
)
vectors = st.tuples(*(st.floats(-100.0, 100.0, allow_nan=False),) * 3).map(np.array)
