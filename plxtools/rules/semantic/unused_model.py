"""A model or trait defined in a file outside any bundle is never used in that file and is not its root model.

## Why it matters

Dead definitions are often leftovers of a rename.
"""

# Whichever root `plx check --model` chose, the file's findings (and the suppressions written for
# them) stay those of a plain check (issue 40.7). The System that C007 says was meant to be last is
# that finding's, not also an unused model.

from __future__ import annotations

from plxtools.model.completeness import root_model
from plxtools.model.symbols import ModelSym
from plxtools.rules.semantic.root_not_system import stray_system, used_models
from plxtools.syntax import ast


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    unit = facts.unit
    if unit.bundle is not None:
        return
    program = facts.program
    default_root = root_model(program, unit)
    stray = None
    if default_root is not None and facts.root is None:
        stray = stray_system(program, unit, default_root, facts.used_names)
    used = used_models(unit, facts.used_names)
    for name, sym in unit.locals.items():
        if isinstance(sym, ModelSym) and sym is not default_root and id(sym) not in used and sym is not stray:
            _unused(report, name, sym, unit)


def _unused(report, name: str, sym: ModelSym, unit) -> None:
    span = sym.stmt.name.span if isinstance(sym.stmt, ast.TraitDef) else sym.stmt.path.span
    if sym.kind != "import":
        report(f"{'trait' if sym.is_trait else 'model'} '{name}' is defined but never used in this file", span,
               help="use it, move it into a bundle, or remove it")
        return
    if getattr(sym, "opaque", False) and any(getattr(a, "import_stmt", None) is sym.import_stmt
                                             for a in (getattr(unit, "archive", None) or {}).values()):
        return  # names from the archive are used (model/program.py archive_name)
    report(f"imported name '{name}' is never used in this file", span, help="use it or remove the import")
