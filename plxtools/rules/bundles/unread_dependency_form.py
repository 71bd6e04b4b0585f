"""A dependency names a bundle but is not written as `Name`, `Name==1.2.3` or `Name@1.2.3`.

## Why it matters

These are the forms OpenPLX reads: `==` is what every official bundle's own config uses, `@` is the
form in openplx.org's documentation, and a bare name takes whatever version is loaded. plx reads the
string as the bare name, so it selects no official bundle version (see Bundle versions).

## Example

```openplx
dependencies: ["Physics>=0.19"]
```

## Use instead

```openplx
dependencies: ["Physics==0.19.0"]
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.UnreadDependencyForm,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        report(f"OpenPLX does not read the dependency form '{f.written}'; plx reads it as '{f.name}' and selects "
               "no bundle version from it", f.span, help=f"write '{f.name}' or an exact version: '{f.name}==0.19.0'")
