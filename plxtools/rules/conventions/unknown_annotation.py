"""An annotation name is not used by the official bundles and is not an `agx_` runtime setting.

## Why it matters

Annotations are free-form metadata, so any name is allowed; an unfamiliar one may be a typo.

## Example

```openplx
.dco: "A wheel"
```

## Use instead

```openplx
.doc: "A wheel"
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.UnknownAnnotation,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"unknown annotation '.{f.name}'", f.span,
               help="annotations are free-form metadata; this one is not used by the official bundles")
