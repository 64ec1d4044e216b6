"""Prove a user's own geometric-algebra identities in any Cl(p, q, r)."""

__all__: list[str] = []
