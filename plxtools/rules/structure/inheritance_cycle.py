"""A model or trait inherits from itself, directly or through others.

## Why it matters

The model would have no base to stop at; nothing about it can be resolved.

## Example

```openplx
A is B
B is A
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.InheritanceCycle, found.TooDeepToCheck)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.InheritanceCycle):
            report(f"inheritance cycle: {' -> '.join(f.models)}", f.span)
        else:
            report("this definition nests or refers to itself too deeply to check", f.span)
