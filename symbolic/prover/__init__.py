"""Prove a user's own geometric-algebra identities in any Cl(p, q, r).

``prove("(a^b)|c == a*(b|c) - b*(a|c)", signature=(1, 3), vectors="a,b,c")`` returns a
:class:`~.verdict.Verdict`: proved (exactly, by polynomial reduction), refuted (with an
exact counterexample) or undecided (with the reason).

Modules, each with one job:

* :mod:`.basis`: the blades of Cl(p, q, r), their names (e0 first in Cl(p, q, 1)) and
  multiplication table
* :mod:`.element`: multivectors over any coefficient ring, with every product, the
  complements, duals and the regressive product
* :mod:`.grammar`: the identity language, read with Python's precedence and the GA
  convention (refused where they differ), never ``eval``
* :mod:`.assumptions`: kinds of symbols and assumptions on them
* :mod:`.symbols`: each kind built from free parameters, reaching every element of it
* :mod:`.orthogonal`: the order and the cases that build orthogonal vectors exactly
* :mod:`.evaluate`: a parsed expression evaluated in a domain (inverse, norms, exp, log,
  the projective and conformal vocabulary, user definitions)
* :mod:`.domains`: polynomials, random draws, one exact point; the relations of normalisers,
  exps, reciprocals, roots and logs, and reduction modulo them
* :mod:`.prove`: the pre-check, the exact check and the proof
* :mod:`.verdict`: proved / refuted / undecided, as text and LaTeX
* :mod:`.catalogue`: classical identities and where they hold
* the ``ga-rotors prove`` command is :mod:`ga_rotors.cli.prove`

Examples
--------
>>> from ga_rotors.symbolic.prover import prove
>>> prove("R*~R == 1", signature=(3, 0, 1), rotors="R").status
'proved'
>>> prove("M >> (P & Q) == (M >> P) & (M >> Q)", signature=(3, 0, 1), motors="M",
...       points="P,Q").status
'proved'
"""

from .assumptions import Assumptions
from .prove import elements, prove
from .verdict import Counterexample, Verdict

__all__ = ["Assumptions", "Counterexample", "Verdict", "elements", "prove"]
