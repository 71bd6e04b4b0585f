"""The pages of the rules not in the module form, keyed by their constant in rules/registry.py
(which reads them when a page is asked for: the catalogue does not import the registry back)."""

from __future__ import annotations

DOCS: dict[str, dict[str, str]] = {}


def doc(constant: str, summary: str, why: str, *, example: str = "", use_instead: str = "") -> None:
    """The documentation of the registry's `constant` (its name there, "UNRESOLVED_TYPE")."""
    if constant in DOCS:
        raise ValueError(f"two pages for {constant}")
    DOCS[constant] = {"summary": summary, "why": why, "example": example, "use_instead": use_instead}
