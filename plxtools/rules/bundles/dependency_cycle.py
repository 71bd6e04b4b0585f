"""Bundles depend on each other in a cycle.

## Why it matters

A bundle must be loadable after its dependencies.
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.DependencyCycle,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report("dependency cycle: " + " -> ".join(f.bundles), f.span)
