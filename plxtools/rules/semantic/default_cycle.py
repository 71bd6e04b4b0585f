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
# statement (re-used for the statements the file's last version had too); check's evaluator meets it again while computing the values and leaves it to this
# finding (M006 owns A006).

from __future__ import annotations

from plxtools.model.resolve import symbol_of_top
from plxtools.model.symbols import ModelSym
from plxtools.model.value_cycles import cycles_of_models


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    unit = facts.unit
    models = [symbol_of_top(unit, s) for s in unit.tree.statements]
    stmts = [m.stmt for m in models if isinstance(m, ModelSym) and not m.is_trait]
    for cycles in cycles_of_models(facts.path, facts.tree.text, stmts):
        for cycle in cycles:
            report("these values depend on each other in a cycle: " + " -> ".join(cycle.ring), cycle.span,
                   help="give one of them a value that does not depend on the others")
