"""See a rotation move: one self-contained, offline HTML page per run.

:class:`View` turns a run (a :class:`~ga_rotors.trajectory.Trajectory`, a scene, or a
saved result) into a page with the body (the uniform ellipsoid of its principal moments),
the rotor's bivector plane, ω and L in space, the trace of the symmetry axis on the unit
sphere, a time slider with play/pause and live rotor, quaternion and z–y′–z″ readouts
with the gimbal-lock flag; every orientation path of the run side by side. In Jupyter a
``View`` displays itself inline. ``ga-rotors view SCENE_OR_RESULT`` writes the page.

Needs plotly (its plotly.js is inlined, so the page loads nothing from the network):
``pip install "ga-rotors[view]"``. :mod:`ga_rotors.view.diagrams` draws the learning
path's pictures (matplotlib only).
"""

from __future__ import annotations

import html

from .data import ViewData, from_trajectory

__all__ = ["View", "ViewData", "from_trajectory"]


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
    def from_trajectory(cls, trajectory, **kwargs) -> View:
        """A view of a Trajectory; keywords as for :func:`from_trajectory`.

        Examples
        --------
        >>> from ga_rotors import simulate
        >>> tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 1.0, 0.01], duration=1.0,
        ...               step=0.01)
        >>> View.from_trajectory(tr).data.axis    # the moment that stands apart: I₁ or I₃
        2
        """
        return cls(from_trajectory(trajectory, **kwargs))

    @classmethod
    def from_scene(cls, scene, trajectory=None) -> View:
        """A view of a scene's run (run here unless ``trajectory`` is given).

        Examples
        --------
        >>> from ga_rotors.scene import load_scene
        >>> s = load_scene("spinning_disk").replace({"time.duration": 0.1})
        >>> v = View.from_scene(s)
        >>> v.data.title, v.data.description[:32]
        ('spinning_disk', 'The physically consistent spinni')
        """
        if trajectory is None:
            from ..scene import run_scene

            trajectory = run_scene(scene)
        # A scene's trajectory holds the principal frame's orientation (ga_rotors.scene).
        return cls.from_trajectory(trajectory, moments=scene.body.moments, title=scene.name,
                                   description=scene.description)  # fmt: skip

    def html(self) -> str:
        """The page, self-contained (plotly.js inlined)."""
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
        >>> p.stat().st_size > 1_000_000       # plotly.js travels with the page
        True
        """
        from ..files import write_text

        return write_text(path, self.html())

    def _repr_html_(self) -> str:
        # An iframe keeps each view's element ids and script apart from the notebook's.
        return (
            f'<iframe srcdoc="{html.escape(self.html(), quote=True)}" '
            'style="width: 100%; height: 820px; border: 0" '
            f'title="{html.escape(self.data.title)}"></iframe>'
        )

    def __repr__(self) -> str:
        paths = ", ".join(self.data.paths)
        return f"View({self.data.title!r}, paths={paths}, {self.data.t.shape[0]} samples)"
