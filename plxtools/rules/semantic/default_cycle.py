"""Values of a model depend on each other in a ring (`a: b` and `b: a`).

## Why it matters

Defaults are evaluated late on the final object; a ring can never be evaluated.

## Example

```openplx
Box is Physics3D.System:
    a is Real: b
    b is Real: a
```

## Use instead

```openplx
Box is Physics3D.System:
    a is Real: 1
    b is Real: a
```
"""

# The ring is the model's fact (model/value_cycles.py), found in each top-level model's own
# statement; check's evaluator meets it again while computing the values and leaves it to this
# finding (M006 owns A006).

from __future__ import annotations

from plxtools.model.resolve import symbol_of_top
from plxtools.model.symbols import ModelSym
from plxtools.model.value_cycles import value_cycles


def check(facts, report) -> None:
    unit = facts.unit
    for stmt in unit.tree.statements:
        model = symbol_of_top(unit, stmt)
        if not isinstance(model, ModelSym) or model.is_trait:
            continue
        for cycle in value_cycles(model.stmt):
            report("these values depend on each other in a cycle: " + " -> ".join(cycle.ring), cycle.span,
                   help="give one of them a value that does not depend on the others")
