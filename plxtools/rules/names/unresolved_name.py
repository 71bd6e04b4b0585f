"""A name in an expression is neither an attribute of the model being defined nor a global name (const
model, global attribute, type or namespace).

## Why it matters

In OpenPLX the scope of a right-hand side is the outermost model where it is written, then the
global names; a name outside both cannot be evaluated.

## Example

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    inertia.mass: chassis_mass
```

## Use instead

```openplx
Chassis is Physics3D.Bodies.RigidBody:
    chassis_mass is Real: 1000
    inertia.mass: chassis_mass
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.names.hints import broken_help, bundle_help
from plxtools.rules.suggestions import did_you_mean

FACTS = (found.UnknownName,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        said = f"'{f.name}' is not in namespace {f.namespace}" if f.namespace is not None else f"unknown name '{f.name}'"
        if f.broken_line is not None:
            report(said, f.span, help=broken_help(f.broken_line))
            continue
        help_, fix = did_you_mean(f.span, f.suggestion)
        report(said, f.span, help=help_ or bundle_help(f.bundle), fix=fix)
