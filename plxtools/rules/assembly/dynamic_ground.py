"""A rigid body named as the ground (`ground`, `floor`, `terrain`) that nothing makes static: no
`is_dynamic: false` in its model, its bases or the block that creates it. It falls under gravity
from the first step, and everything standing on it falls with it.

## Why it matters

A rigid body is dynamic unless told otherwise. A ground that falls together with the vehicle on it
looks like nothing happens until the positions are read: in the BoxTruck tutorial's scene, leaving
out the ground's `is_dynamic: false` makes the ground and the truck drop 4.9 m in the first second,
and `plx check --simulate` finds nothing wrong, because nothing collides, comes apart or gains
energy. A ground that is meant to move (a lift's floor, a tipping platform) is held by a mate or
given `is_dynamic: true`, and is left alone.

## Example

```openplx
Ground is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {20, 20, 0.1}

Scene is Physics3D.System:
    ground is Ground
```

## Use instead

```openplx
Ground is Physics3D.Bodies.RigidBody:
    geometry is Physics3D.Geometries.Box:
        size: {20, 20, 0.1}
    is_dynamic: false

Scene is Physics3D.System:
    ground is Ground
```
"""

# Judged on each body a model's block creates (`ground is Ground` in a system): the name says what
# it is meant to be (a word of it is ground, floor or terrain), the program says it is a rigid body,
# and the chain of models plus the creating block say whether `is_dynamic` is given any value (any
# value, even one computed, counts as the author's decision). A body a mate of the same block names
# (`connectors: [ground.hinge, ...]`) is a moving part and is left alone.

from __future__ import annotations

import re

from plxtools.model.completeness import assigned_paths
from plxtools.model.symbols import ModelSym
from plxtools.rules.blocks import declaration_blocks
from plxtools.syntax import ast

GROUND_WORD = re.compile(r"(?:^|_)(ground|floor|terrain)(?:$|_|[0-9])", re.I)
RIGID_BODY = ["Physics3D", "Bodies", "RigidBody"]
DYNAMIC = ("is_dynamic",)


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    program, unit, tree = facts.program, facts.unit, facts.tree
    if unit.bundle is not None:
        return
    body_model = None
    for _owner, block in declaration_blocks(tree.statements):
        for s in block:
            if not (isinstance(s, ast.Declaration) and s.keyword == "is" and len(s.path.parts) == 1
                    and s.value is None and s.type is not None and len(s.type.alternatives) == 1):
                continue
            name = s.path.parts[0].name
            if not GROUND_WORD.search(_snake(name)):
                continue
            if body_model is None:
                body_model = program.lookup(RIGID_BODY, unit)
                if not isinstance(body_model, ModelSym):
                    return  # the bundles in use have no rigid body: nothing to judge
            model = program.lookup([p.name for p in s.type.alternatives[0].name.parts], unit)
            if not isinstance(model, ModelSym) or not program.is_subtype(model, body_model):
                continue
            if DYNAMIC in assigned_paths(program, model, s.body, below=body_model) or _mated(tree, block, name):
                continue
            _report(report, unit, s, name, model)


def _report(report, unit, s: ast.Declaration, name: str, model: ModelSym) -> None:
    if model.unit is unit and model.stmt is not None and model.stmt.body and GROUND_WORD.search(_snake(model.name)):
        where = f"add 'is_dynamic: false' to {model.name} (line {model.stmt.header.start.line + 1})"
    else:
        where = f"add 'is_dynamic: false' in the block of '{name}'"
    report(f"'{name}' is a dynamic body: nothing sets is_dynamic: false, so this ground falls under gravity, "
           f"and everything on it falls with it", s.path.span,
           help=f"{where}; a ground meant to move is given 'is_dynamic: true'")


def _snake(name: str) -> str:
    """`GroundPlate` -> `ground_plate`: the words of a name, whichever convention it is written in."""
    return re.sub(r"(?<=[a-z0-9])([A-Z])", r"_\1", name)


def _mated(tree, block, name: str) -> bool:
    """Whether a `connectors:` list in `block` (or a block below it) names a connector of `name`."""
    text = tree.text
    prefix = re.compile(r"(?<![\w.])" + re.escape(name) + r"\.")
    stack = [block]
    while stack:
        for s in stack.pop():
            if isinstance(s, ast.Assignment) and s.path.parts and s.path.parts[-1].name == "connectors" \
                    and s.value is not None and prefix.search(text[s.value.span.start.offset:s.value.span.end.offset]):
                return True
            if getattr(s, "body", None):
                stack.append(s.body)
    return False
