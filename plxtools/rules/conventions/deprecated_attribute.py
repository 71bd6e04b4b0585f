"""An attribute that its bundle marks as deprecated (in its model's documentation or a comment) is
used.

## Why it matters

Deprecated attributes are removed in later bundle versions.

## Example

```openplx
Scene is Physics3D.System:
    kinematically_controlled: [ground]
```

## Use instead

```openplx
Ground is Physics3D.Bodies.RigidBody:
    is_dynamic: false
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.DeprecatedMember,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.name}' is deprecated: {f.note}", f.span)
