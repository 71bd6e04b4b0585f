"""`becomes` gives an attribute a type that is not a subtype of its declared type (or of one
alternative of a union).

## Why it matters

Code written against the base model must still work with the specialised attribute.

## Example

```openplx
Contact is Physics.Interactions.SurfaceContact.Model:
    friction becomes Physics.Geometries.Material
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.BecomesIncompatible,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.name}' cannot become {f.new}: it is declared as {f.declared} in {f.owner}", f.span,
               help="the new type must be a subtype of the declared type or one of its alternatives")
