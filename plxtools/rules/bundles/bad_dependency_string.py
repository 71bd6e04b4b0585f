"""A dependency is not a string that starts with a bundle name.

## Why it matters

A dependency names the bundle it needs; plx cannot tell which bundle is meant.

## Example

```openplx
dependencies: ["0.19.0"]
```

## Use instead

```openplx
dependencies: ["Physics==0.19.0"]
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.BadDependency,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.kind == "not-array":
            report("'dependencies' must be an array of strings", f.span)
        elif f.kind == "not-string":
            report('a dependency must be a string like "Physics==0.19.0"', f.span)
        else:
            report(f"malformed dependency '{f.value}'", f.span, help="write 'Name', 'Name==1.2.3' or 'Name@1.2.3'")
