"""The last model of a file outside any bundle (the model a runtime loads) is not a Physics3D.System, a rigid body or a material.

## Why it matters

agxViewer and other runtimes load the last model of a file: a System as a scene, a rigid body or a material (of the official bundles) as a library item. Reported when the last model is none of these, and when it is a body or material while a System above it is used by nothing (the scene was meant to be last).
"""

# Judged on the file's default root (the last model); a root chosen by name (`plx check --model`)
# is not "the last model" and is left alone. The System above the root that nothing uses is also
# what C003 (semantic/unused_model.py) does not report: the scene meant to be last is this
# finding's, not also an unused model.

from __future__ import annotations

from plxtools.model.completeness import root_model
from plxtools.model.program import Program
from plxtools.model.symbols import ModelSym


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    unit = facts.unit
    if unit.bundle is not None or facts.root is not None:
        return
    program = facts.program
    root = root_model(program, unit)
    if root is None:
        return
    stray = stray_system(program, unit, root, facts.used_names)
    if stray is not None:
        report(f"the root model '{root.name}' (the last model in the file) is not a Physics3D.System, "
               f"and the System '{stray.name}' above it is used by nothing", root.stmt.path.span,
               help=f"a scene is loaded from the last model; move '{stray.name}' to the end of the file")
    elif not _loadable_root(program, unit, root):
        report(f"the root model '{root.name}' (the last model in the file) is not a Physics3D.System, "
               f"a rigid body or a material", root.stmt.path.span,
               help="a scene is loaded from the last model; make it a Physics3D.System or move the scene last")


def stray_system(program: Program, unit, root: ModelSym, used_names) -> ModelSym | None:
    """The System above a root that is no System and that nothing in the file uses (the scene was
    meant to be last), or None."""
    system = program.lookup(["Physics3D", "System"], unit)
    if not isinstance(system, ModelSym) or program.is_subtype(root, system):
        return None
    used = used_models(unit, used_names)
    for sym in unit.locals.values():
        if isinstance(sym, ModelSym) and sym is not root and id(sym) not in used and program.is_subtype(sym, system):
            return sym
    return None


def used_models(unit, used_names) -> set[int]:
    """The ids of the file's top-level symbols that something in it names."""
    return {id(sym) for name, sym in unit.locals.items() if name in used_names}


def _loadable_root(program: Program, unit, root: ModelSym) -> bool:
    """What importers load from a file's last model: a System (a scene), a rigid body, or a
    material of an official bundle (a material library). Judged on the bundles in use, so it fits
    every version (materials moved from Physics.Charges to Physics.Geometries)."""
    kinds = [program.lookup(["Physics3D", "System"], unit), program.lookup(["Physics3D", "Bodies", "RigidBody"], unit)]
    if not any(isinstance(k, ModelSym) for k in kinds):
        return True  # the bundles in use do not say: do not guess
    if program.is_open(root):
        return True  # built on an imported file plx cannot read (or an unknown base, reported): unknown
    if any(isinstance(k, ModelSym) and program.is_subtype(root, k) for k in kinds):
        return True
    return any(m.name.endswith("Material") and m.unit is not None and m.unit.official
               for m in program.ancestors(root))
