"""An operator is used on types for which no `operator` is declared (for example `Quat * Vec3`).

## Why it matters

Only + - * / on numbers and the operators the bundles declare exist.

## Example

```openplx
v is Math.Vec3: q * Math.Vec3.X_AXIS()
```

## Use instead

```openplx
v is Math.Vec3: q.rotate(Math.Vec3.X_AXIS())
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.NoOperator,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        ops = f.operands
        shown = f"{f.op}{ops[0]}" if len(ops) == 1 else f"{ops[0]} {f.op} {ops[1]}"
        report(f"no operator for {shown}", f.span, help="rotate a vector with q.rotate(v)" if f.quat_times else None)
