"""A type name after `is`, `becomes`, `with`, in a parameter or a return type does not resolve.

## Why it matters

Names are looked up from the current namespace outwards and then from the bundles (spec C.2). A
misspelt or missing type leaves the attribute untyped, so nothing about it can be checked.

## Example

```openplx
geometry is Physics3D.Geometries.Bx
```

## Use instead

```openplx
geometry is Physics3D.Geometries.Box
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.names.hints import bundle_help, version_note
from plxtools.rules.suggestions import did_you_mean

FACTS = (found.UnknownType,)
_SAYS = {"unknown": "unknown type '{}'", "namespace": "'{}' is a namespace, not a type",
         "global": "'{}' is a global value, not a type"}


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        help_, fix = did_you_mean(f.span, f.suggestion)
        if help_ is None and f.listing is not None:
            ns, names, more = f.listing
            help_ = f"{ns} has: " + ", ".join(names) + (" ..." if more else "")
        help_ = help_ or bundle_help(f.bundle)
        note = version_note(f)
        if note is not None:
            help_ = f"{note}; {help_}" if help_ else note
        report(_SAYS[f.kind].format(f.written), f.span, help=help_, fix=fix)
