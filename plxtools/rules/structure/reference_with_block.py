"""A `reference` attribute is given a block.

## Why it matters

A block creates and configures a new object, which contradicts `reference`.
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.ReferenceWithBlock,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.name}' is a reference; a block would create a new object", f.span,
               help="give it an existing object with ':' instead")
