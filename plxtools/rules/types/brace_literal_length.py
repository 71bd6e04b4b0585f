"""A `{...}` literal has a different number of values than the model it builds (Vec3 takes 3, Quat 4,
Vec2 2, Matrix3x3 9).

## Why it matters

Brace literals are positional; a missing or extra value would shift every component.

## Example

```openplx
main_axis: {0, 1}
```

## Use instead

```openplx
main_axis: {0, 1, 0}
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.BraceLength,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"{f.model} takes {len(f.fields)} values ({', '.join(f.fields)}), this literal has {f.given}", f.span)
