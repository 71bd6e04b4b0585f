"""A model or trait is written with the name it had in an older OpenPLX version; the version in use has
it under another name (it moved to another namespace, or was renamed one to one).

## Why it matters

The change comes from plx's index of every official `openplx-bundles` version, or from its reviewed
table of renames, so the new name is the same model. The safe fix writes it; `plx migrate --to
VERSION` does it for whole files, together with renamed attributes.

## Example

```openplx
geometry is Physics3D.Charges.Box:   # written for 0.17
```

## Use instead

```openplx
geometry is Physics3D.Geometries.Box:
```
"""

from __future__ import annotations

from plxtools.diagnostics import Edit, Fix
from plxtools.model import facts as found

FACTS = (found.OlderName,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        declared = " (a rename OpenPLX's own migration list declares)" if f.declared else ""
        d = report(f"'{f.written}' was renamed '{f.new}' (OpenPLX {f.older} -> {f.using})", f.span,
                   help=f"write '{f.new}'{declared}; {f.command} updates whole files",
                   fix=Fix(f"replace with '{f.new}'", (Edit(f.span.start.offset, f.span.end.offset, f.new),), safe=True))
        d.older_version = f.older
