"""See a rotation move: one light, self-contained, offline HTML page per run.

:class:`View` turns a run (a :class:`~ga_rotors.trajectory.Trajectory`, a scene, or a
saved result) into a page with the body drawn from its own geometry (the scene's disk, box,
cylinder, ..., or the uniform ellipsoid of its inertia) and its pivot, its axes, ω and L in
space, the rotor's bivector plane with its angle, the trace of the symmetry axis on the unit
sphere, a legend, a time slider with play/pause and live rotor, quaternion and z–y′–z″
readouts with the gimbal-lock flag; every orientation path of the run side by side. In
Jupyter a ``View`` displays itself inline. ``ga-rotors view SCENE_OR_RESULT`` writes the page.

The page draws itself with the package's own small script on a 2-D canvas: no plotting
library, no WebGL, nothing loaded from the network. :mod:`ga_rotors.view.diagrams` draws the
learning path's pictures (matplotlib).
"""

from __future__ import annotations

import html

import numpy as np

from .data import Line, ViewData, from_trajectory
from .geometry import Solid

__all__ = ["Line", "Solid", "View", "ViewData", "from_trajectory"]


class View:
    """An interactive page for one run.

    Parameters
    ----------
    data : ViewData
        What to show (:func:`from_trajectory` makes it from a Trajectory).

    Examples
    --------
    >>> from ga_rotors import simulate
    >>> tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.2, 0.0, 3.0], duration=2.0,
    ...               step=0.01, paths=("rotor", "quaternion"))
    >>> v = View.from_trajectory(tr, title="a wobbling disk")
    >>> v
    View('a wobbling disk', paths=rotor, quaternion, 201 samples)
    >>> v.html().startswith("<!DOCTYPE html>"), v._repr_html_().startswith("<iframe")
    (True, True)
    """

    def __init__(self, data: ViewData):
        self.data = data

    @classmethod
    def from_trajectory(cls, trajectory, body=None, **kwargs) -> View:
        """A view of a Trajectory; keywords as for :func:`from_trajectory`.

        Examples
        --------
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 1.0, 0.01], duration=1.0,
        ...               step=0.01)
        >>> View.from_trajectory(tr).data.symmetry_direction.tolist()   # I₃ stands apart
        [0.0, 0.0, 1.0]
        """
        return cls(from_trajectory(trajectory, body, **kwargs))

    @classmethod
    def from_scene(cls, scene, trajectory=None) -> View:
        """A view of a scene's run (run here unless ``trajectory`` is given), the body drawn
        from the scene's own geometry.

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> s = load_scene("spinning_disk").replace({"time.duration": 0.1})
        >>> v = View.from_scene(s)
        >>> v.data.title, v.data.description[:32], v.data.solid.kind
        ('spinning_disk', 'The physically consistent spinni', 'disk')
        """
        from .. import quaternion as Q
        from .geometry import from_scene

        if trajectory is None:
            from ..scene import run_scene

            trajectory = run_scene(scene)
        solid = from_scene(scene)  # in the frame the scene's file is written in
        p = np.asarray(scene.principal_rotation, dtype=np.float64)
        if _in_principal_frame(scene, trajectory):
            inertia, solid = scene.body.moments, solid.turned(Q.conjugate(p))
        else:
            r = Q.to_matrix(p)
            inertia = r @ np.diag(scene.body.moments) @ r.T
        return cls(
            from_trajectory(
                trajectory, inertia, title=scene.name, description=scene.description, solid=solid
            )
        )

    def html(self) -> str:
        """The page, self-contained (its data and its drawing script; nothing else to load)."""
        from .page import page_html

        return page_html(self.data)

    def save(self, path):
        """Write the page to ``path`` atomically; returns the path.

        Examples
        --------
        >>> import tempfile, pathlib
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.1,
        ...               step=0.01)
        >>> p = View.from_trajectory(tr).save(pathlib.Path(tempfile.mkdtemp()) / "v.html")
        >>> p.stat().st_size < 200_000         # a light page: data and a small script
        True
        """
        from ..files import write_text

        return write_text(path, self.html())

    def _repr_html_(self) -> str:
        # An iframe keeps each view's element ids and script apart from the notebook's; the
        # page carries no library, so a notebook of many views stays light.
        return (
            f'<iframe srcdoc="{html.escape(self.html(), quote=True)}" '
            'style="width: 100%; height: 820px; border: 0" '
            f'title="{html.escape(self.data.title)}"></iframe>'
        )

    def __repr__(self) -> str:
        paths = ", ".join(self.data.paths)
        return f"View({self.data.title!r}, paths={paths}, {self.data.t.shape[0]} samples)"


def _in_principal_frame(scene, trajectory) -> bool:
    """Whether ``trajectory``'s body frame is the scene's principal frame (the frame runs
    were integrated and written in) rather than the frame the scene's file is written in:
    runs that name their frame (``meta["body_frame"]``) are in the scene's own frame. The two
    are one frame for every scene whose inertia is diagonal as written."""
    identity = tuple(scene.principal_rotation) == (1.0, 0.0, 0.0, 0.0)
    return identity or "body_frame" not in trajectory.meta
