"""An object that the file's root model creates has a non-optional Real, Int, Bool or String attribute with no value anywhere (base, model, trait or instance block).

## Why it matters

OpenPLX refuses to load an incomplete model ("Missing assignment ..., owning model is not complete"). Library models may stay incomplete; only what the root model instantiates is checked.

## Example

```openplx
Scene is Physics3D.System:
    ball is Physics3D.Bodies.RigidBody:
        geometry is Physics3D.Geometries.Sphere
```

## Use instead

```openplx
Scene is Physics3D.System:
    ball is Physics3D.Bodies.RigidBody:
        geometry is Physics3D.Geometries.Sphere:
            radius: 0.1
```
"""

# The values are the model's facts (model/completeness.py `Unset`, computed once per analysis by
# rules/analysis.py into FileFacts.unset); check's evaluator meets the same missing values while
# computing and leaves them to this finding (M007 owns A004).

from __future__ import annotations


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    for u in facts.unset:
        if not u.reference:
            report(f"missing assignment {u.path} ({u.type}){instances(u)}: the model is not complete", u.anchor,
                   help=f"give it a value, e.g. '{u.name}: ...' (declared without a default in {u.owner})")


def instances(u) -> str:
    """` in 4 instances (a, b, c, d)` for a value several objects of one model lack (else "")."""
    if not u.instances:
        return ""
    owners = u.instances
    shown = ", ".join(owners[:6]) + (f" and {len(owners) - 6} more" if len(owners) > 6 else "")
    return f" in {len(owners)} instances ({shown})"
