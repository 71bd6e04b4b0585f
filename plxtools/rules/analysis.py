"""Every rule on one parsed file: the model's own findings (names, types), then the rules that
judge a resolved file (completeness, conventions), then config selection, suppressions, order.

lint, check, fmt's safety check and the editor all call this, so a file gets the same
diagnostics everywhere."""

from __future__ import annotations

import bisect
from dataclasses import replace

from plxtools.config import Config
from plxtools.diagnostics import Diagnostic, Severity
from plxtools.model.completeness import Versions, root_model, unset_values
from plxtools.model.reuse import fresh
from plxtools.model.symbols import ModelSym
from plxtools.model.workspace import FileAnalysis, workspace_for_cli
from plxtools.rules import registry
from plxtools.rules.consequences import Explained, drop_consequences, drop_owned, report_order
from plxtools.rules.engine import FileFacts, apply_severity, run_fact_rules, run_file_rules
from plxtools.rules.incremental import run_file_rules_again
from plxtools.rules.literals import literal_diagnostics
from plxtools.rules.style import style_diagnostics, style_of_file, style_of_statements, used_names
from plxtools.rules.suppress import apply
from plxtools.syntax import ast


def analyse_file(workspace, tree: ast.File, root_name: str | None = None, previous=None, keep: bool = False):
    """The model's analysis of `tree` with the rules' diagnostics added (a model FileAnalysis).

    `root_name` is the model a run instantiates (`plx check --model`); by default the file's last
    model. Completeness and the root rules judge that one. `keep` and `previous` (the last
    analysis of this file) let the language server re-use what did not change (model/reuse.py)."""
    snap = previous.snapshot if previous is not None else None
    fa = workspace.analyse(tree, snap, keep or previous is not None)
    root = _named_model(workspace.program, fa.unit, root_name) if root_name else None
    if fa.facts:  # the model's facts reported by their rule modules, before the rules that read them
        reported = run_fact_rules(FileFacts(workspace.program, fa, tree, root, found=fa.facts))
        fa = FileAnalysis(fa.unit, fa.diagnostics + reported, fa.lazy_occurrences, fa.snapshot, fa.plan)
    plan = fa.plan if fa.snapshot is not None and root_name is None else None
    if plan is None:
        unset = unset_values(workspace.program, fa.unit, root, explained=_explained(tree, fa))
        used = used_names(fa.unit, fa.occurrences)
        extra = style_diagnostics(fa.unit)
        extra += literal_diagnostics(tree, fa.occurrences, tree.path)
    else:
        unset = _unset_again(workspace.program, fa, tree, snap, plan)
        extra = _per_statement(fa, plan, "style", style_of_statements(fa.unit, plan.dirty))
        parts = fa.snapshot.parts
        used = set().union(*(p.uses for p in parts)) if fa.unit.bundle is None else set()
        extra += style_of_file(fa.unit)
        checked = [o for i in sorted(plan.dirty) for o in parts[i].occs]
        extra += _per_statement(fa, plan, "literals", literal_diagnostics(tree, checked, tree.path, plan.dirty))
    facts = FileFacts(workspace.program, fa, tree, root, unset=tuple(unset), used_names=frozenset(used))
    extra += run_file_rules(facts) if plan is None else run_file_rules_again(facts, fa, plan, snap)
    for d in extra:
        d.file = tree.path
    return FileAnalysis(fa.unit, fa.diagnostics + extra, fa.lazy_occurrences, fa.snapshot, fa.plan)


def _explained(tree: ast.File, fa) -> Explained:
    return Explained(tree, list(tree.diagnostics) + fa.diagnostics)


def _unset_again(program, fa, tree: ast.File, previous, plan) -> list:
    """The unset values of the last version (M007/M008's facts), moved, while the root's statements
    and the bundles are the same and neither version has a syntax error (a block that did not parse
    explains missing values by its position); otherwise they are found again."""
    root = root_model(program, fa.unit)
    key = None
    if root is not None:
        for i, s in enumerate(tree.statements):
            if s is root.stmt:
                key = plan.keys[i] if plan.keys else None
                break
    clean = not any(d.severity is Severity.ERROR for d in tree.diagnostics)
    found = None
    last = previous.extra.get("completeness") if previous is not None and plan.based else None
    if last is not None and key is not None and clean and last[0] == key:
        found = [_moved(u, plan) for u in last[1]]
        if any(u is None for u in found):
            found = None
    walks = previous.extra.get("walks") if previous is not None and plan.based else None
    versions = Versions(fa.unit, plan.regions, plan.serials, walks, plan.move_span)
    if found is None:
        found = unset_values(program, fa.unit, versions=versions, explained=_explained(tree, fa))
        fa.snapshot.extra["walks"] = versions.walked
    else:
        fa.snapshot.extra["walks"] = versions.carry_all()
    if key is not None and clean:
        fa.snapshot.extra["completeness"] = (key, found)
    return found


def _moved(u, plan):
    """An unset value of the last version with its anchor where its line now is (None: gone)."""
    anchor = plan.move_span(u.anchor)
    return None if anchor is None else replace(u, anchor=anchor)


def _per_statement(fa, plan, rule: str, new: list[Diagnostic]) -> list[Diagnostic]:
    """A rule's findings that each statement's own text decides: `new` for the statements checked
    again (kept on their parts for the next version), the re-used statements' moved with them."""
    out = []
    parts = fa.snapshot.parts
    if new:
        starts = [p.start for p in parts]
        mine: dict[int, list] = {}
        for d in new:
            mine.setdefault(bisect.bisect_right(starts, d.span.start.offset) - 1, []).append(d)
    for i, part in enumerate(parts):
        if i not in plan.reused:
            part.extra[rule] = [fresh(d) for d in mine.get(i, ())] if new else []
        out.extend(fresh(d) for d in part.extra.get(rule, ()))
    return out


def _named_model(program, unit, name: str):
    """The model `name` resolves to in this file (None when it is no model: check reports that)."""
    found = program.lookup(name.split("."), unit)
    return found if isinstance(found, ModelSym) and not found.is_trait else None


def analyse_tree(tree: ast.File, cfg: Config, workspace=None) -> list[Diagnostic]:
    """All diagnostics for a parsed file: syntax, then the semantic ones, filtered by config."""
    analysis = None
    if not is_binary(tree):
        if workspace is None:
            workspace = workspace_for_cli([], [], use_cache=True)
        analysis = analyse_file(workspace, tree)
    return final_diagnostics(tree, cfg, analysis)


def is_binary(tree: ast.File) -> bool:
    """S001: the file is not text, so there is nothing to analyse beyond saying so."""
    return any(d.code == registry.BINARY_FILE for d in tree.diagnostics)


def final_diagnostics(tree: ast.File, cfg: Config, analysis) -> list[Diagnostic]:
    """A file's diagnostics from its parse and an analysis already made (None: syntax only)."""
    diags = list(tree.diagnostics)
    if analysis is not None and not is_binary(tree):
        diags.extend(analysis.diagnostics)
    return finalize(tree, diags, cfg)


def finalize(tree: ast.File, diags: list[Diagnostic], cfg: Config) -> list[Diagnostic]:
    """The registry's severities, config selection, follow-on findings dropped (a layout error's, a
    code another on the same line owns), inline suppressions and ordering (syntax first): shared by
    lint, check and the server."""
    for d in diags:
        d.file = tree.path
    diags = [d for d in apply_severity(diags) if cfg.rule_enabled(d.code, tree.path)]
    diags = apply(tree, drop_owned(drop_consequences(diags)), report_unused=cfg.rule_enabled(registry.UNUSED_SUPPRESSION, tree.path))
    diags.sort(key=report_order)
    return diags
