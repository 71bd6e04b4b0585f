"""An assignment or a dotted path names an attribute that the object being configured does not have.

## Why it matters

A misspelt attribute would otherwise be silently ignored or rejected at load time; the message names
the model that was searched and suggests the closest attribute.

## Example

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mas: 10
```

## Use instead

```openplx
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 10
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.names.hints import broken_help
from plxtools.rules.suggestions import did_you_mean

FACTS = (found.UnknownAttribute,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.on_value:
            report(f"'{f.name}' cannot be set on a value of type {f.owner}", f.span)
        elif f.kind_of is not None:
            kind, qname, path, last = f.kind_of
            report(f"'{f.name}' is not an attribute of {f.owner}, but of {kind}, a kind of it", f.span,
                   help=f"use becomes to make '{path}' a {kind}: write '{last} becomes {qname}:' above")
        elif f.broken_line is not None:
            report(f"'{f.name}' is not an attribute of {f.owner}", f.span, help=broken_help(f.broken_line))
        else:
            help_, fix = did_you_mean(f.span, f.suggestion)
            report(f"'{f.name}' is not an attribute of {f.owner}", f.span, help=help_, fix=fix)
