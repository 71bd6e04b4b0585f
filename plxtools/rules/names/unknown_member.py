"""`.name` is used on a value whose type has no attribute or method of that name.

## Why it matters

Member access is checked against the declared types, through bases and traits.

## Example

```openplx
x is Real: Math.Vec3.Z_AXIS().lenght()
```

## Use instead

```openplx
x is Real: Math.Vec3.Z_AXIS().length()
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.suggestions import did_you_mean

FACTS = (found.NoMemberOnValue, found.NoStaticFunction, found.NoAttributeOrMethod)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.NoMemberOnValue):
            report(f"a value of type {f.type} has no member '{f.name}'", f.span)
            continue
        what = "static function" if isinstance(f, found.NoStaticFunction) else "attribute or method"
        help_, fix = did_you_mean(f.span, f.suggestion)
        report(f"{f.model} has no {what} '{f.name}'", f.span, help=help_, fix=fix)
