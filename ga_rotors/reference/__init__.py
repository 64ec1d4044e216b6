"""Exact solutions that integrators and paths are measured against.

* :mod:`ga_rotors.reference.symmetric_top`: the torque-free symmetric top, closed form.
"""
