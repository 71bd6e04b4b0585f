"""A one-part type name that no file plx reads defines, in a file that imports a file plx cannot read
(an `.agx` archive, a URDF): `ExtendedRod is PendulumScene_rod` after `import @"pendulum.agx"`.

## Why it matters

An AGX archive's bodies and systems keep their AGX names, which only the runtime can read from the
archive. plx takes the name as an opaque model (no N001, no missing-attribute errors) and says so
here; `plx check` lists what is built on it as not analysed (A042). A name close to one in scope is
still reported as N001 with the suggestion (a typo).

## Example

```openplx
import @"pendulum.agx"

ExtendedRod is PendulumScene_rod
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.OpaqueImportName,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"'{f.written}' is defined in no file plx reads; it can only come from {f.source}, which plx "
               "cannot read, so it is taken as an opaque model", f.span,
               help="its attributes are not checked; `plx check` does not analyse what is built on it")
