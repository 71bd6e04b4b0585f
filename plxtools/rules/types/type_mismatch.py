"""A value does not fit the declared type: a String where a Real is expected, a number where a Bool is
expected, an object of the wrong model, an array where a single value is expected.

## Why it matters

OpenPLX is strictly typed; the value would be rejected when the model is loaded.

## Example

```openplx
Ground is Physics3D.Bodies.RigidBody:
    is_dynamic: 0
```

## Use instead

```openplx
Ground is Physics3D.Bodies.RigidBody:
    is_dynamic: false
```
"""

from __future__ import annotations

from plxtools.diagnostics import Edit, Fix
from plxtools.model import facts as found
from plxtools.model.symbols import NUMERIC
from plxtools.rules.types.not_a_value import report_not_a_value

FACTS = (found.TypeMismatch, found.NotAValue, found.ModelForValue, found.BraceForPrimitive)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.TypeMismatch):
            help_, fix = _hint(f)
            report(f"expected {f.expected}, found {f.found}", f.span, help=help_, fix=fix)
        elif isinstance(f, found.NotAValue):
            if not f.argument:
                report_not_a_value(f, report)
        elif isinstance(f, found.ModelForValue):
            report(f"'{f.model}' is a model, not a value; it is a kind of {f.attribute_type}, the attribute's type",
                   f.span, help=f"use becomes to make the attribute a {f.name}: write '<attribute> becomes {f.model}' "
                                "(its settings in an indented block below)")
        else:
            report(f"a {{...}} literal cannot be a {f.primitive}", f.span)


def _hint(f: found.TypeMismatch) -> tuple[str | None, Fix | None]:
    """What the value most likely meant: a positional model in braces, a Bool without quotes, a
    const named by its string; else a word on the literal."""
    start, end = f.span.start.offset, f.span.end.offset
    if f.braces is not None:
        kind, names, inner = f.braces
        fix = None
        if inner is not None:
            fix = Fix("write it in braces", (Edit(start, end, "{ " + inner + " }"),), safe=True)
        return (f"a {kind} is written in braces, {{ {', '.join(names)} }}, or as a block with one line per field; "
                "[ ] makes an array"), fix
    if f.unquoted is not None:
        word = f.unquoted
        return (f"write {word} without quotes: a {f.expected_primitive} is not a string",
                Fix(f"write {word}", (Edit(start, end, word),), safe=False))
    if f.const is not None:
        name, value, attr = f.const
        return (f"did you mean {name}? (\"{value}\" is its {attr}; give the const itself, without quotes)",
                Fix(f"replace with '{name}'", (Edit(start, end, name),), safe=False))
    if f.expected_primitive == "Bool" and f.found_primitive in NUMERIC:
        return "use true or false", None
    if f.expected_primitive in NUMERIC and f.found_primitive == "String":
        return "remove the quotes", None
    return None, None
