"""The rule modules on the next version of a file: only the statements whose reads changed are
judged again (the language server checks on every edit; a 20,000-line file has 16,000 statements).

A rule module's findings on a top-level statement depend on what its judgement read: the
statement itself, the symbols it resolved (the model's re-use plan, model/reuse.py, already says
which statements' resolution may have changed: those are `plan.dirty`), and the file-wide tables
it built from other statements, which it records with `FileFacts.read` through the cache layer's
recorder (`plxtools.cache.reads.recording`). So a module runs on the dirty statements, with its
reads recorded; when the recorded reads differ from the last version's, or a finding lands
outside the statements judged, it runs on the whole file instead. Findings are kept on each
statement's part (`Part.extra`, moved with it); a statement with findings that moved lines is
judged again (a message may name a line). Tests compare the result with a fresh analysis on
random edits (tests/ide/test_reuse.py)."""

from __future__ import annotations

import bisect
from dataclasses import replace

from plxtools.cache.reads import recording
from plxtools.diagnostics import Diagnostic
from plxtools.model.reuse import fresh
from plxtools.rules.engine import FileFacts, Reporter, file_rule_modules, run_file_rules


def run_file_rules_again(facts: FileFacts, fa, plan, previous) -> list[Diagnostic]:
    """Every lint-stage rule module's findings on `facts`'s file, re-using the last version's
    (`previous`: its snapshot) where nothing the judgement read changed. `fa` is the model's
    analysis with its snapshot (the parts of this version) and `plan` its re-use plan."""
    snap = fa.snapshot
    if snap is None:
        return run_file_rules(facts)
    parts = snap.parts
    stmts = facts.tree.statements
    starts = [p.start for p in parts]
    out: list[Diagnostic] = []
    for module, rules in file_rule_modules("lint"):
        key = "rule " + module.__name__
        last = previous.extra.get(key) if previous is not None and plan.based else None
        judged = set(plan.dirty)
        for i, p in plan.reused.items():
            if p.extra.get(key) and p.line != p.was_line:
                judged.add(i)
        found, reads = None, None
        if last is not None:
            found, reads = _judge(module, rules, facts, parts, sorted(judged), stmts)
            if reads != last or not _inside(found, starts, judged):
                found = None
        if found is None:
            judged = set(range(len(parts)))
            found, reads = _judge(module, rules, facts, parts, None, stmts)
        for i in judged:
            parts[i].extra[key] = []
        loose = []
        for d in found:
            i = bisect.bisect_right(starts, d.span.start.offset) - 1
            if i < 0:
                loose.append(d)  # before the first statement: kept by no part
            else:
                parts[i].extra[key].append(fresh(d))
        snap.extra[key] = reads if not loose else None
        out.extend(loose)
        for p in parts:
            out.extend(fresh(d) for d in p.extra.get(key, ()))
    return out


def _judge(module, rules, facts: FileFacts, parts: list, judged: list | None, stmts: list):
    """A module's findings on the judged statements (None: all) and the reads it recorded."""
    report = Reporter(rules, facts.path)
    if judged is not None:
        occs = []
        for i in judged:
            occs.extend(parts[i].occs if parts[i].occs is not None else _occurrences_in(facts, parts[i]))
        facts = replace(facts, statements=tuple(stmts[i] for i in judged), occs=occs)
    with recording() as reads:
        module.check(facts, report)
    return report.found, reads


def _occurrences_in(facts: FileFacts, part) -> list:
    """A re-used statement's occurrences (built from its records on first need)."""
    return [o for o in facts.analysis.occurrences if part.start <= o.span.start.offset < part.end]


def _inside(found: list[Diagnostic], starts: list[int], judged: set) -> bool:
    return all(bisect.bisect_right(starts, d.span.start.offset) - 1 in judged for d in found)
