"""The source paper's gyroscope (RBEF 2016), reproduced: ``ga-rotors paper``.

* :mod:`ga_rotors.paper.models`: the paper's numbers, once, and its two bodies (the printed
  inertia and a consistent disk).
* :mod:`ga_rotors.paper.runs`: each body and initial nutation integrated on the rotor,
  quaternion and Euler-angle paths, measured against the exact solution; the summary table.
* :mod:`ga_rotors.paper.figures`: Figures 3–10 and the errors, redrawn.
* :mod:`ga_rotors.paper.digest`: the digest of the plotted data stored in every figure.
* :mod:`ga_rotors.paper.reproduce`: all of it written into a directory.
* ``python -m ga_rotors.paper._generate_scenes`` writes the bundled scene files of the
  paper from :mod:`ga_rotors.paper.models`.
"""

__all__: list[str] = []  # a namespace of submodules: nothing defined here
