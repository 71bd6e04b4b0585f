"""How a type, namespace or method given where a value is needed is reported: as a value
(T001) or as a call's argument (T005), the same words."""

from __future__ import annotations

from plxtools.diagnostics import Edit, Fix
from plxtools.model import facts as found


def describe(what: found.Named) -> str:
    """The start of "... is not a value" / "... cannot be called" for what a name stands for."""
    if what.kind in ("model", "type"):
        return f"'{what.qname}' is a type and"
    if what.kind == "namespace":
        return f"'{what.qname}' is a namespace and"
    if what.kind == "method":
        return f"method '{what.name}' must be called: it"
    return "this"


def report_not_a_value(f: found.NotAValue, report) -> None:
    """A model named as a value most often lacks `const`: say so, and offer to add it when the
    model is declared in this file."""
    what = f.what
    if what.kind != "model":
        report(f"{describe(what)} is not a value", f.span)
        return
    fix = None
    if f.declared_at is not None:
        at = f.declared_at.start.offset
        fix = Fix(f"declare {what.name} 'const'", (Edit(at, at, "const "),), safe=False)
    report(f"'{what.qname}' is a model, not a value: a model used as a value must be declared 'const' (or "
           "instantiated)", f.span, fix=fix,
           help=f"write 'const {what.name} ...' where it is defined, or declare an attribute 'name is {what.qname}' "
                "to create one")
