"""A bundle's config.openplx has no `config is BundleConfig:` or no name.

## Why it matters

The name is how other bundles depend on this one.

## Example

```openplx
config is BundleConfig:
    version: "0.1.0"
```

## Use instead

```openplx
config is BundleConfig:
    name: "MyBundle"
    version: "0.1.0"
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.ConfigWithoutName,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.declared:
            report("the bundle config has no 'name'", f.span, help='add name: "MyBundle"')
        else:
            report("config.openplx must declare 'config is BundleConfig:' with a name", f.span)
