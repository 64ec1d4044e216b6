"""Exact solutions that integrators and paths are measured against.

* :mod:`ga_rotors.reference.symmetric_top`: the torque-free symmetric top, closed form.
* :mod:`ga_rotors.reference.asymmetric_top`: the torque-free asymmetric top (Jacobi elliptic
  functions, elliptic integral of the third kind).
* :mod:`ga_rotors.reference.heavy_top`: the heavy symmetric (Lagrange) top.
* :mod:`ga_rotors.reference.rigid_motion`: rotation with translation: free flight under
  uniform gravity, a spring at the centre of mass (any body-frame origin).
* :mod:`ga_rotors.reference.elliptic`: the elliptic functions and integrals they share.
"""

__all__: list[str] = []  # a namespace of submodules: nothing defined here
