"""The one ranking of "did you mean" suggestions: meaning first, spelling second.

lint's unknown names, attributes and types (model/checker.py), `plx check`'s and `plx test`'s
signal and scenario keys (check/signals.py `did_you_mean`) and the runtime API and controller
scripts (check/api.py) all ask `best` or `ranked`, so a slip gets the same answer everywhere.

A candidate ranks higher, in this order, when it
1. is the same name but for letter case (`Physics3d` -> `Physics3D`);
2. is what the name was renamed to (`renames`, from the bundles' API changes);
3. sits on the same owner (the part before the last dot of a dotted path);
4. is of the same family: it ends in the same role word (`_input`, `_output`, `_connector`,
   `_motor`...), so an input is never offered for an output;
5. is of the same kind, linear or rotational (an unqualified `velocity` is a linear one), and
   shares meaning with it: words in common, counting synonyms (`speed` ~ `velocity`), so
   `target_speed_input` finds `target_angular_velocity_input` before `torque_range_input`, and
   `velocity_output` finds `linear_velocity_world_output` before `angular_velocity_output`;
6. is spelt more like it (difflib's ratio, case-folded).
A candidate is offered only when one of 1-2 holds, when it is of the same family and shares
meaning, or when its spelling is close (ratio >= `cutoff`). The issue-45 tests hold one case per
family (signals, inputs, outputs, attributes, bundles).
"""

from __future__ import annotations

import difflib
import re

# words that mean the same quantity in the bundles' names (a signal's or an attribute's)
_SYNONYMS = (
    frozenset({"speed", "velocity", "rate"}),
    frozenset({"angle", "angular", "rotation", "rotational"}),
    frozenset({"position", "translation", "location", "pos"}),
    frozenset({"force", "effort", "push"}),
    frozenset({"torque", "moment"}),
    frozenset({"range", "limit", "limits", "bounds"}),
    frozenset({"acceleration", "accel"}),
)
_CANON = {w: min(group) for group in _SYNONYMS for w in group}
# the last word of a name that says what kind of thing it is: an input is no output
_ROLES = frozenset({"input", "output", "connector", "motor", "hinge", "joint", "range", "spring", "material",
                    "geometry", "body", "wheel", "signal", "value"})


def words(name: str) -> list[str]:
    """`target_speedInput` -> [target, speed, input]; `Physics3D` -> [physics3d]."""
    out = []
    for chunk in re.split(r"[^A-Za-z0-9]+", name):
        out += [w.lower() for w in re.findall(r"[A-Z]?[a-z0-9]+|[A-Z]+(?![a-z])", chunk) or [chunk] if w]
    return out


def _meaning(ws: list[str]) -> set[str]:
    return {_CANON.get(w, w) for w in ws}


def _role(ws: list[str]) -> str | None:
    return ws[-1] if ws and ws[-1] in _ROLES else None


def _score(name: str, option: str, renames: dict[str, str] | None) -> tuple:
    owner, _, last = name.rpartition(".")
    o_owner, _, o_last = option.rpartition(".")
    nw, ow = words(last), words(o_last)
    role = _role(nw)
    same_family = role is not None and role == _role(ow)
    shared = len((_meaning(nw) - {role}) & (_meaning(ow) - {role})) if same_family else 0
    spelling = difflib.SequenceMatcher(None, name.lower(), option.lower()).ratio()
    # an unqualified `velocity` is a linear one: a rotational option ranks after a linear one
    same_kind = ("angle" in _meaning(nw)) == ("angle" in _meaning(ow))
    return (name.lower() == option.lower(), bool(renames) and renames.get(name) == option,
            owner.lower() == o_owner.lower(), same_family and shared > 0, same_kind, shared, same_family, spelling)


def ranked(name: str, options, *, cutoff: float = 0.7, renames: dict[str, str] | None = None) -> list[str]:
    """The options worth offering for `name`, best first (see the module's docstring)."""
    scored = []
    for option in dict.fromkeys(options):
        if option == name:
            continue
        s = _score(name, option, renames)
        if s[0] or s[1] or s[3] or s[-1] >= cutoff:
            scored.append((s, option))
    scored.sort(key=lambda t: t[0], reverse=True)
    return [o for _s, o in scored]


def best(name: str, options, *, cutoff: float = 0.7, renames: dict[str, str] | None = None) -> str | None:
    """The one suggestion for `name` (None: nothing close in meaning or spelling)."""
    found = ranked(name, options, cutoff=cutoff, renames=renames)
    return found[0] if found else None
