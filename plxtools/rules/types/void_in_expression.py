"""A method declared without a return type is used in an expression.

## Why it matters

A method with no `->` cannot be called from OpenPLX (it is a runtime hook such as `on_init`).

## Example

```openplx
x is Real: this.on_init()
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.ReturnsNothing,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"{f.owner}.{f.method} returns nothing and cannot be used in an expression", f.span)
