"""Something that is not an array is indexed, or the index is not an Int.

## Why it matters

Only arrays (`T[]`) can be indexed, and only with whole numbers.

## Example

```openplx
x is Real: geometry.radius[0]
```

## Use instead

```openplx
x is Real: geometry.radius
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.IndexNotInt, found.NotIndexable)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.IndexNotInt):
            report(f"an index must be an Int, not {f.type}", f.span)
        else:
            report(f"a value of type {f.type} cannot be indexed", f.span)
