"""`.brick` files: OpenPLX models from before 0.15, when the extension was `.brick`.

No `openplx-bundles` release is older than 0.15.0, so such a file is read as written for 0.15.0
once the renames OpenPLX declares before 0.15 (its migration list: model moves and renames, and
`Math.Vec3.fromXYZ` -> `from_xyz` style method renames) are applied where they cannot mean anything
else: the old name is in no indexed release (a name 0.15 has again, `DriveTrain.Gear`, is left for
a person with a note). Attribute renames before 0.15 need the old bundles to find their owner; what
they leave is listed like any error under the target version. The file then takes the `.openplx`
extension (the 0.14.0 -> 0.15.0 step of the same list).
"""

from __future__ import annotations

from dataclasses import dataclass, field

EXTENSION = ".brick"


@dataclass(frozen=True)
class BrickRenames:
    """The pre-0.15 renames plx can apply to a .brick file, and those it cannot tell."""

    names: dict[str, str]  # old qualified name (model, or Model.method) -> new
    ambiguous: dict[str, str] = field(default_factory=dict)  # old -> new, where 0.15 has the old name again
    first: str = ""  # the oldest release plx has


def renames() -> BrickRenames:
    from plxtools.model.apichanges import declared_renames
    from plxtools.model.apiindex import load, version_key, versions, where_defined

    first = versions()[0]
    idx = load(first)
    names: dict[str, str] = {}
    ambiguous: dict[str, str] = {}
    for d in declared_renames():
        if version_key(d.to) > version_key(first) or d.kind not in ("model", "method"):
            continue
        if d.kind == "model":
            (ambiguous if where_defined(d.old) else names)[d.old] = d.new
        else:
            owner = idx.models.get(d.model or "", {})
            (ambiguous if d.old in owner.get("fn", {}) else names)[f"{d.model}.{d.old}"] = f"{d.model}.{d.new}"
    # a name renamed twice before 0.15 goes straight to its last name
    for old, new in list(names.items()):
        seen = {old}
        while new in names and new not in seen:
            seen.add(new)
            new = names[new]
        names[old] = new
    return BrickRenames(names, ambiguous, first)


def pre_015_text(path: str, text: str) -> tuple[str, int, list[str]]:
    """The text with the unambiguous pre-0.15 renames applied (by the lexer's tokens: comments and
    strings are never touched), how many, and notes on names that 0.15 has again."""
    from plxtools.diagnostics import apply_edits
    from plxtools.migrate.rewrite import type_edits
    from plxtools.syntax import parse_text

    r = renames()
    tree = parse_text(text, path)
    edits = type_edits(tree, r.names)
    notes = [f"'{old}' is written here: OpenPLX renamed it '{new}' before 0.15, but {r.first} has a '{old}' "
             f"again; plx left it as it is (check which one is meant)"
             for old, new in sorted(r.ambiguous.items()) if type_edits(tree, {old: new})]
    return (apply_edits(text, edits) if edits else text), len(edits), notes
