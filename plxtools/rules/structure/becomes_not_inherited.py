"""`becomes` names an attribute that is not inherited.

## Why it matters

`becomes` specialises an existing attribute's type; there is nothing to specialise.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    shape becomes Physics3D.Geometries.Box
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    shape is Physics3D.Geometries.Box
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.BecomesNotInherited,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.name}' is not inherited by {f.where}, so it cannot 'become' another type", f.span,
               help=f"did you mean '{f.suggestion}'?" if f.suggestion else f"declare it with '{f.name} is ...'")
