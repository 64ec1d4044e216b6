"""symbolic: exact geometric algebra in SymPy, and an audit of the sources.

The repository's ``symbolic/`` folder, installed as ``ga_rotors.symbolic``. Independent of
the numeric package (it imports nothing else of :mod:`ga_rotors`), so each can check the
other.

Modules, each with one job:

* :mod:`symbolic.algebra`: Cl(p, q) for any signature, with symbolic coefficients
* :mod:`symbolic.hamilton`: Hamilton quaternions from their defining rules
* :mod:`symbolic.trig`: deciding trigonometric identities exactly
* :mod:`symbolic.rotations`: axis rotations and Euler sequences (matrices, quaternions)
* :mod:`symbolic.isomorphisms`: Cl(0,0) ≅ ℝ, Cl(0,1) ≅ ℂ, Cl(0,2) ≅ ℍ, Cl(1,0), Cl(2,0),
  Cl⁺(3,0) ≅ ℍ (all 48 signed assignments)
* :mod:`symbolic.rotors`: rotor sandwich = quaternion operator; Ṙ = ½RΩ ⟺ q̇ = ½q(0,ω)
* :mod:`symbolic.audit`: every equation of the two source documents, checked
* :mod:`symbolic.prover`: prove a user's own identities in any Cl(p, q, r)
  (``ga-rotors prove``)
* the ``ga-rotors verify`` command is :mod:`ga_rotors.cli.verify`
"""

__all__: list[str] = []  # a namespace of submodules: nothing defined here
