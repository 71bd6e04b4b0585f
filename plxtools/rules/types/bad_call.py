"""Something that is not a function is called, an instance method is called on a type, or (warning) a
static function is called through an instance.

## Why it matters

Static functions belong to the type (`Math.Vec3.from_xyz`), instance methods to a value
(`v.length()`); a const model is its own instance, so both work on it.

## Example

```openplx
x is Real: Math.Vec3.length()
```

## Use instead

```openplx
x is Real: Math.Vec3.X_AXIS().length()
```
"""

from __future__ import annotations

from plxtools.model import facts as found
from plxtools.rules.types.not_a_value import describe

FACTS = (found.MethodNotCalled, found.NotCallable, found.InstanceMethodOnType, found.StaticOnInstance)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.MethodNotCalled):
            report(f"method '{f.method}' must be called before '.{f.name}'", f.span)
        elif isinstance(f, found.NotCallable):
            what = describe(f.what) if f.what is not None else f"a value of type {f.type}"
            report(f"{what} cannot be called", f.span)
        elif isinstance(f, found.InstanceMethodOnType):
            report(f"'{f.method}' is an instance method of {f.owner}; call it on an instance, not on the type", f.span)
        else:
            report(f"'{f.method}' is a static function; call it on the type, {f.owner}.{f.method}(...)", f.span)
