"""`plx migrate --to VERSION PATH...`: rewrite model files for another official OpenPLX version.

What is rewritten comes from the change list between the two versions (`model/apichanges.py`),
never from a list of names here: models that moved or were renamed (one to one, inferred from the
API index or recorded in the reviewed table) and renamed attributes. Type names are found with
the lexer's tokens (so comments and strings are never touched); attributes through the semantic
model of the file under the version it was written for, so `charges` is renamed only where it
means the attribute of a mate or interaction, also inside dotted paths.

A rewrite is kept only when the result parses, the formatter accepts it, and it lints with no
more errors under the target version than the untouched file would have there (partial migration:
the safe rewrites are applied, what needs a person is listed at its line). A file that was in the formatter's style stays in it (a
longer name may need a line split); any other file keeps its layout exactly, apart from the edits.
The errors that remain under the target version are handed back, located, for a person.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from plxtools.diagnostics import Edit, Severity, apply_edits
from plxtools.model.apichanges import MECHANICAL, changes
from plxtools.syntax import ast, parse_text
from plxtools.fmt import format_text
from plxtools.model.symbols import MemberSym
from plxtools.rules.analysis import analyse_file, final_diagnostics
from plxtools.syntax.dotted import dotted_runs


@dataclass(frozen=True)
class Plan:
    """The mechanical part of a migration between two versions."""

    from_version: str
    to_version: str
    types: dict[str, str]  # old qualified model name -> new one
    attrs: dict[tuple[str, str], str]  # (model that declares it, old attribute) -> new attribute


def plan(from_v: str, to_v: str) -> Plan:
    """The plan between two releases of plx's stored index."""
    return plan_of(from_v, to_v, changes(from_v, to_v))


def plan_of(from_label: str, to_label: str, cs) -> Plan:
    """The plan of a list of changes (`apichanges.changes` or `changes_over`): what is one to one."""
    types: dict[str, str] = {}
    attrs: dict[tuple[str, str], str] = {}
    for c in cs:
        if c.handling not in MECHANICAL:
            continue
        if c.kind in ("model-moved", "model-renamed") and c.old and c.new:
            types[c.old] = c.new
        elif c.kind == "attr-renamed" and c.old and c.new:
            attrs[(c.model, c.old)] = c.new
    return Plan(from_label, to_label, types, attrs)


@dataclass
class FileMigration:
    path: Path
    old_text: str
    new_text: str | None = None  # None: left unchanged (see `refused`)
    edits: int = 0
    refused: str | None = None
    errors_before: int = 0
    errors_after: int = 0
    notes: list[str] = field(default_factory=list)
    left: list = field(default_factory=list)  # errors under the target version a person must resolve
    reformatted: bool = False  # the input was formatted, so the result is formatted too

    @property
    def changed(self) -> bool:
        return self.new_text is not None and self.new_text != self.old_text


def type_edits(tree: ast.File, types: dict[str, str]) -> list[Edit]:
    """Qualified names that moved: the longest leading part of a dotted name found in `types`."""

    out: list[Edit] = []
    if not types:
        return out
    for run in dotted_runs(tree.text):
        parts = [str(t) for t in run]
        for n in range(len(parts), 1, -1):
            new = types.get(".".join(parts[:n]))
            if new is not None:
                out.append(Edit(run[0].start_pos, run[n - 1].end_pos, new))
                break
    return out


def attribute_edits(tree: ast.File, analysis, attrs: dict[tuple[str, str], str]) -> list[Edit]:
    """Renamed attributes, wherever the model resolves a name to that attribute."""

    out: dict[tuple[int, int], Edit] = {}
    if not attrs or analysis is None:
        return []
    for occ in analysis.occurrences:
        target = occ.target
        if not isinstance(target, MemberSym) or target.owner is None:
            continue
        new = attrs.get((target.owner.qname, target.name))
        a, b = occ.span.start.offset, occ.span.end.offset
        if new is not None and tree.text[a:b] == target.name:
            out[(a, b)] = Edit(a, b, new)
    return list(out.values())


def _errors(diags) -> int:
    return sum(1 for d in diags if d.severity is Severity.ERROR)


def _target_errors(path: Path, text: str, cfg, to_ws) -> tuple[list, object] | None:
    """The errors of `text` under the target version (None when it does not parse)."""

    tree = parse_text(text, str(path))
    if tree.has_errors_of_syntax():
        return None
    diags = final_diagnostics(tree, cfg, analyse_file(to_ws, tree))
    return [d for d in diags if d.severity is Severity.ERROR], tree


def _safe_subset(path: Path, text: str, edits: list[Edit], cfg, to_ws, limit: int) -> list[Edit]:
    """The edits that, added one by one, never add an error under the target version (at most
    `limit` errors in all): what can be applied when the whole rewrite would make things worse."""
    kept: list[Edit] = []
    current = limit
    for e in edits:
        got = _target_errors(path, apply_edits(text, kept + [e]), cfg, to_ws)
        if got is not None and len(got[0]) <= current:
            kept.append(e)
            current = len(got[0])
    return kept


def migrate_text(path: Path, text: str, p: Plan, cfg, from_ws, to_ws) -> FileMigration:
    """The migration of one file's text (nothing is written here).

    Partial migration: the rewrites are kept when they leave no more errors under the target
    version than the file has under its own version or would have untouched under the target; what still fails (a removed model, a changed
    type) is listed in `left` at its line for a person, instead of refusing the whole file. When the
    whole rewrite would add errors, the edits that add none are kept one by one.
    """

    fm = FileMigration(path, text)
    tree = parse_text(text, str(path))
    if tree.has_errors_of_syntax():
        fm.refused = "it has syntax errors; fix them first (`plx lint`)"
        return fm
    before = analyse_file(from_ws, tree)
    fm.errors_before = _errors(final_diagnostics(tree, cfg, before))
    edits = type_edits(tree, p.types) + attribute_edits(tree, before, p.attrs)
    untouched = _target_errors(path, text, cfg, to_ws)[0] if p.from_version != p.to_version else []
    if not edits:
        fm.new_text = text
        fm.errors_after = len(untouched) if p.from_version != p.to_version else fm.errors_before
        fm.left = untouched
        return fm
    new_text = apply_edits(text, edits)
    got = _target_errors(path, new_text, cfg, to_ws)
    if got is None:
        fm.refused = "the rewritten text would not parse (a bug in plx migrate; please report it)"
        return fm
    # the bar: no more errors than the file has under its own version, or would have untouched
    # under the target (where an old name's single error can hide what the new type requires)
    limit = max(fm.errors_before, len(untouched))
    if len(got[0]) > limit:
        kept = _safe_subset(path, text, edits, cfg, to_ws, limit)
        fm.notes.append(f"{len(edits) - len(kept)} of {len(edits)} rewrites would add errors under "
                        f"{p.to_version} and were not applied")
        edits = kept
        if not edits:
            fm.new_text = text
            fm.errors_after = len(untouched)
            fm.left = untouched
            return fm
        new_text = apply_edits(text, edits)
    formatted = format_text(new_text, str(path))
    if formatted.text is None:
        fm.refused = "the formatter refuses the rewritten text (a bug in plx migrate; please report it)"
        return fm
    if formatted.text != new_text and format_text(text, str(path)).text == text:
        new_text, fm.reformatted = formatted.text, True
    got = _target_errors(path, new_text, cfg, to_ws)
    if got is None:
        fm.refused = "the rewritten text would not parse (a bug in plx migrate; please report it)"
        return fm
    fm.left = got[0]
    fm.errors_after = len(fm.left)
    fm.new_text = new_text
    fm.edits = len(edits)
    return fm
