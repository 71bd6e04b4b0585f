"""A model is used where a trait is needed (after `with`) or a trait is inherited with `is`.

## Why it matters

Models inherit from one model; traits are applied with `with`. Mixing them up changes what the
object is.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody with Physics3D.Geometries.Box
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.WrongKindOfType,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.wanted == "trait":
            report(f"'{f.type}' is a model, not a trait", f.span, help="only traits can be applied with 'with'")
        else:
            report(f"'{f.type}' is a trait; a model cannot inherit from it with 'is'", f.span,
                   help=f"inherit from a model and apply the trait with 'with {f.written}'")
