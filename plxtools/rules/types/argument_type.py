"""A function argument does not fit the parameter's declared type.

## Why it matters

Arguments are checked against the `fn` declaration in the bundle.

## Example

```openplx
x is Real: Math.Functions.sin("0.5")
```

## Use instead

```openplx
x is Real: Math.Functions.sin(0.5)
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.types.not_a_value import report_not_a_value

FACTS = (found.ArgumentType, found.NotAValue)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.ArgumentType):
            report(f"argument of {f.method}: expected {f.expected}, found {f.found}", f.span,
                   help="signature: " + f.signature)
        elif f.argument:
            report_not_a_value(f, report)
