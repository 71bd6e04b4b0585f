"""A name is defined twice: two top-level definitions in one namespace (across all files of a bundle),
or two attributes with the same name in one model.

## Why it matters

Only one of them can be used; which one is undefined.
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.DeclaredTwice, found.DefinedTwice)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.DeclaredTwice):
            report(f"'{f.name}' is declared twice in {f.owner}", f.span,
                   help=f"the first declaration is at line {f.first_line + 1}")
            continue
        where = ""
        if f.first_line is not None:
            line = f.first_line + 1
            where = f" (first defined in {f.first_path}:{line})" if f.first_path else f" (first defined at line {line})"
        report(f"'{f.name}' is already defined in this namespace{where}", f.span)
