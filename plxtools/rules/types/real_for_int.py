"""A Real is given where an Int is declared.

## Why it matters

The documentation accepts it, but whether the value is truncated or rounded is not specified.

## Example

```openplx
count is Int: 2.5
```

## Use instead

```openplx
count is Int: 2
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.RealForInt,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report("a Real is given where an Int is expected", f.span,
               help="write a whole number, or use Math.Functions.round/floor/ceil")
