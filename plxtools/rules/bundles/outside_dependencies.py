"""A file in a bundle names something from a bundle that is not among its (transitive) dependencies.

## Why it matters

A bundle sees only the bundles it depends on; the name would not resolve for users of the bundle.
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.OutsideDependencies,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.written}' is in bundle '{f.bundle}', which bundle '{f.home}' does not depend on", f.span,
               help=f"add \"{f.bundle}\" to the dependencies in config.openplx")
