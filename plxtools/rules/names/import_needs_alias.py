"""An `import` without `as` names a file whose stem is not a valid OpenPLX name (`my-robot.urdf`,
`2wheels.obj`), so it binds no name.

## Why it matters

Without an alias the imported name is the file's stem; a stem with a dash, a space or a leading
digit cannot be written as a name, so nothing in the file can use the import.

## Example

```openplx
import @"my-robot.urdf"
```

## Use instead

```openplx
import @"my-robot.urdf" as MyRobot
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.ImportBindsNoName,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"the file name {f.stem!r} is not a valid OpenPLX name, so the import binds no name", f.span,
               help=f"name it with 'as': import {f.source} as {f.hint}")
