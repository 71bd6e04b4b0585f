"""A function is called with a different number of arguments than its `fn` declaration, or an operator
is declared with the wrong number of parameters.

## Why it matters

The bundles declare every function's signature; the call cannot match it.

## Example

```openplx
x is Math.Vec3: Math.Vec3.from_xyz(1, 2)
```

## Use instead

```openplx
x is Math.Vec3: Math.Vec3.from_xyz(1, 2, 0)
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.OperatorArity, found.CallArity)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.OperatorArity):
            report(f"operator {f.op} takes {'1 or 2' if f.op == '-' else '2'} parameters, not {f.given}", f.span)
        else:
            report(f"{f.owner}.{f.method} takes {f.wanted} argument{'s' if f.wanted != 1 else ''}, {f.given} given",
                   f.span, help="signature: " + f.signature)
