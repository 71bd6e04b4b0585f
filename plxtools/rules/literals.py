"""Physical limits of values written as literals (A030, A032, A036, A038), found by lint, so while
typing, rather than only by `plx check`.

An assignment's target is the member the model resolved for it (the checker's occurrences), so a
limit applies to `inertia.mass: -10`, to `radius: -0.2` in a Cylinder block and to `size.z: 0` or
`size: {1, 0, 1}` of a Box, whatever model the statement sits in.  Only numbers the file writes
(with a sign, in parentheses or in braces) are judged; anything computed is left to `plx check`,
which evaluates it.  check does not repeat a finding lint made on the same line."""

from __future__ import annotations

import math

from plxtools.diagnostics import Diagnostic, Severity
from plxtools.syntax import ast
from plxtools.rules import registry

# the codes this module raises (their home: `plx check` imports these names for its own findings)

# member qualified name -> (code, lowest allowed, inclusive?, highest allowed, what, help)
LIMITS: dict[str, tuple[str, float, bool, float, str, str]] = {
    "Physics3D.Bodies.Inertia.mass": (registry.NEGATIVE_MASS, 0.0, True, math.inf, "mass", "a mass of 0 means: compute it from "
                                      "the geometries"),
    "Physics3D.Geometries.Box.size": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "box size", "give the full edge lengths in "
                                      "metres"),
    "Physics3D.Geometries.Cylinder.radius": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "cylinder radius", ""),
    "Physics3D.Geometries.Cylinder.height": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "cylinder height", ""),
    "Physics3D.Geometries.Capsule.radius": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "capsule radius", ""),
    "Physics3D.Geometries.Capsule.height": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "capsule height", ""),
    "Physics3D.Geometries.Sphere.radius": (registry.NON_POSITIVE_SIZE, 0.0, False, math.inf, "sphere radius", ""),
    "Physics.Geometries.Material.density": (registry.NON_POSITIVE_DENSITY, 0.0, False, math.inf, "density", "a material that gives "
                                            "mass has a positive density (kg/m^3)"),
    "Physics.Interactions.Dissipation.DefaultDryFriction.coefficient": (registry.INVALID_CONTACT_PARAMETER, 0.0, True, math.inf,
                                                                        "friction coefficient", ""),
    "Physics.Interactions.SurfaceContact.Model.normal_restitution": (registry.INVALID_CONTACT_PARAMETER, 0.0, True, 1.0, "normal_restitution",
                                                                     ""),
    "Physics.Interactions.SurfaceContact.Model.tangential_restitution": (registry.INVALID_CONTACT_PARAMETER, 0.0, True, 1.0,
                                                                         "tangential_restitution", ""),
}
SEVERITY = {registry.NON_POSITIVE_SIZE: Severity.ERROR, registry.NEGATIVE_MASS: Severity.ERROR, registry.INVALID_CONTACT_PARAMETER: Severity.ERROR, registry.NON_POSITIVE_DENSITY: Severity.WARNING}


def literal(expr) -> float | list | None:
    """The number (or list of numbers, for braces) an expression writes, or None."""
    if isinstance(expr, ast.Number):
        try:
            v = float(expr.value)
        except OverflowError:  # an integer beyond the float range: A041's (check), not a limit's
            return None
        return v if math.isfinite(v) else None
    if isinstance(expr, ast.Paren):
        return literal(expr.inner)
    if isinstance(expr, ast.Unary) and expr.op in ("-", "+"):
        v = literal(expr.operand)
        return -v if expr.op == "-" and isinstance(v, float) else (v if isinstance(v, float) else None)
    if isinstance(expr, ast.Brace):
        items = [literal(i) for i in expr.items]
        return items if all(isinstance(i, float) for i in items) else None
    return None


# the attribute names LIMITS judges: an occurrence's target is named by the identifier it sits on,
# so a statement whose last two path parts are none of these cannot be judged (most statements)
_NAMES = frozenset(q.rsplit(".", 1)[1] for q in LIMITS)


def literal_diagnostics(tree: ast.File, occurrences, path: str, only: set[int] | None = None) -> list[Diagnostic]:
    """Values outside their attribute's limits (`only`: in these top-level statements alone)."""
    target: dict | None = None  # built on the first statement that needs it
    out: list[Diagnostic] = []

    def member(ident) -> str | None:
        nonlocal target
        if target is None:
            target = {(o.span.start.offset, o.span.end.offset): o.target for o in occurrences
                      if o.kind in ("attribute", "definition")}
        t = target.get((ident.span.start.offset, ident.span.end.offset))
        return getattr(t, "qname", None)

    def judge(qname: str, value, span, component: str = "") -> None:
        code, lo, lo_in, hi, what, help_ = LIMITS[qname]
        vals = value if isinstance(value, list) else [value]
        for v in vals:
            bad = (v < lo or (v == lo and not lo_in)) or v > hi
            if bad:
                rng = (f">= {lo:g}" if lo_in else f"> {lo:g}") + (f" and <= {hi:g}" if math.isfinite(hi) else "")
                out.append(Diagnostic(code, f"{what}{component} is {v:g}; it must be {rng}", span, SEVERITY[code],
                                      file=path, help=help_ or None))
                return

    # an explicit stack, not a self-calling closure: such a closure is a reference cycle that would
    # keep `target` (and through it the file's symbols and tree) alive until a collector pass, and
    # the language server freezes what a check leaves (plxtools/ide/runtime/collector.py: no_gc)
    stack = [tree.statements if only is None else [s for i, s in enumerate(tree.statements) if i in only]]
    while stack:
        for s in stack.pop() or ():
            value = getattr(s, "value", None)
            parts = s.path.parts if isinstance(s, (ast.Assignment, ast.Declaration)) else []
            if value is not None and parts and (parts[-1].name in _NAMES or (
                    len(parts) >= 2 and parts[-2].name in _NAMES)):
                v = literal(value)
                if v is not None:
                    q = member(parts[-1])
                    if q in LIMITS:
                        judge(q, v, value.span)
                    elif len(parts) >= 2 and isinstance(v, float):
                        parent = member(parts[-2])  # size.z: 0 -> Box.size, component z
                        if parent in LIMITS:
                            judge(parent, v, value.span, f" ({parts[-1].name})")
            stack.append(ast.body_of(s))
    out.sort(key=lambda d: d.span.start.offset)
    return out
