"""`is` declares an attribute that the model already inherits.

## Why it matters

Redeclaring would create a second attribute with the same name. To give it a value use `:`; to
narrow its type use `becomes`.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    is_dynamic is Bool: false
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    is_dynamic: false
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.Redeclared,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.in_model:
            report(f"'{f.name}' is already declared in {f.owner}; use 'becomes' to specialise it or ':' to give it "
                   "a value", f.span, help=f"'{f.name} becomes {f.written_type}'" if f.written_type else None)
        else:
            report(f"'{f.name}' already exists in {f.owner}; use ':' to give it a value or 'becomes' to specialise "
                   "it", f.span)
