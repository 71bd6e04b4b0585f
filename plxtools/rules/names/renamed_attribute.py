"""An attribute is written with the name it had in an older OpenPLX version (`charges` before
`connectors`); the version in use renamed it.

## Why it matters

The index of every official version (or its reviewed table) records the rename and the models it
applies to. The fix is unsafe: plx knows which models renamed the attribute, and you confirm that
the object here is one of them. `plx migrate --to VERSION` renames it through the model, where the
owner is known.

## Example

```openplx
hinge is Physics3D.Interactions.Hinge:
    charges: [a.top, b.top]   # written for 0.17
```

## Use instead

```openplx
hinge is Physics3D.Interactions.Hinge:
    connectors: [a.top, b.top]
```
"""

from __future__ import annotations

from plxtools.diagnostics import Edit, Fix
from plxtools.model import facts as found

FACTS = (found.RenamedAttribute,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        d = report(f"'{f.written}' was renamed '{f.new}' in OpenPLX {f.since} (in {f.owners})", f.span,
                   help=f"write '{f.new}' if this is one of those models; {f.command} updates whole files",
                   fix=Fix(f"rename to '{f.new}'", (Edit(f.span.start.offset, f.span.end.offset, f.new),), safe=False))
        d.older_version = f.older_version
