"""The rule modules on the next version of a file: only the statements whose reads changed are
judged again (the language server checks on every edit; a 20,000-line file has 16,000 statements).

A statement's findings depend on what its judgement read, and the judgement records it through
the cache layer's model recorder (`plxtools.cache.reads.model_recording`; the model notes every
name looked up and every model whose tables were read, model/program.py and model/resolve.py):

- the top-level names it read: a statement that defines one of them was added, removed or
  changed since, and the findings may differ;
- the checker's findings and resolved names of the statement itself (its diagnostics and
  occurrences, relative to it), which the rules read as facts;
- the file-wide tables a rule built (`FileFacts.table`), per rule: a table that changed makes the
  rule judge the whole file again (a table keyed by top-level names, `table_by_name`, is read
  entry by entry instead: reading an entry is reading that name).

A statement whose text, reads and checker facts are the same as a statement of the last version
gets that statement's findings back, moved to where it is now; a statement with findings that
moved lines is judged again (a message may name a line). A statement judged with the whole file
(the first analysis) has no reads of its own yet, so it is judged again whenever the model's
re-use plan checks it again (model/reuse.py). Tests compare the result with a fresh analysis on
random edits (tests/ide/test_reuse.py).

A module that judges the file as a whole (the root's unset values, the names used anywhere, the
scene a run builds) says `WHOLE_FILE = True` and is judged on the whole file every time."""

from __future__ import annotations

import bisect
from dataclasses import fields as dataclass_fields
from dataclasses import replace

from plxtools.cache.reads import model_recording
from plxtools.diagnostics import Diagnostic
from plxtools.model.facts import Fact
from plxtools.model.reuse import defined, fresh, moved_diags
from plxtools.model.symbols import GlobalSym, MemberSym, MethodSym, ModelSym
from plxtools.rules.engine import MEMO, NEXT_MEMO, TEXTS, FileFacts, Reporter, file_rule_modules, run_file_rules

ANY = "*"  # a read this module cannot name (a statement that defines no name): always changed


def run_file_rules_again(facts: FileFacts, fa, plan, previous) -> list[Diagnostic]:
    """Every lint-stage rule module's findings on `facts`'s file, re-using the last version's
    (`previous`: its snapshot) where nothing the judgement read changed. `fa` is the model's
    analysis with its snapshot (the parts of this version) and `plan` its re-use plan."""
    snap = fa.snapshot
    if snap is None:
        return run_file_rules(facts)
    tree = facts.tree
    parts = snap.parts
    stmts = tree.statements
    modules = file_rule_modules("lint")
    keys = ["rule " + m.__name__ for m, _r in modules]
    texts = [(defined(s), tree.text[p.start:p.end]) for s, p in zip(stmts, parts)]
    snap.extra["rule texts"] = texts
    facts.tables[TEXTS] = [t for _n, t in texts]
    facts.tables[MEMO] = previous.extra.get("rule memo") or {} if previous is not None else {}
    based = previous is not None and plan.based and "rule texts" in previous.extra
    judged = _to_judge(facts, fa, plan, previous, texts, keys) if based else set(range(len(parts)))
    alone = len(judged) < len(parts)
    out: list[Diagnostic] = []
    for (module, rules), key in zip(modules, keys):
        last = previous.extra.get(key) if based else None
        out.extend(_module_findings(module, rules, key, facts, snap, judged if alone else None, last))
    snap.extra["rule memo"] = facts.tables.get(NEXT_MEMO)
    if alone:
        for i in judged:
            _record_reads(facts, parts, i, stmts, modules)
    else:
        for p in parts:
            p.rule_reads = p.rule_sig = None
    return out


def _module_findings(module, rules, key: str, facts: FileFacts, snap, judged: set | None, last) -> list:
    """One module's findings on the file: judged on `judged` (None: the whole file) when the
    file-wide tables it reads are the `last` version's, else on the whole file; kept on the parts."""
    parts, stmts = snap.parts, facts.tree.statements
    starts = [p.start for p in parts]
    found = tables = None
    if getattr(module, "WHOLE_FILE", False):
        judged = None  # it reads whole-file facts (unset values, used names, the root): never alone
    if last is not None and judged is not None:
        found, tables = _judge(module, rules, facts, parts, sorted(judged), stmts)
        if tables != last or not _inside(found, starts, judged):
            found = None
    if found is None:
        judged = set(range(len(parts)))
        found, tables = _judge(module, rules, facts, parts, None, stmts)
    for i in judged:
        parts[i].extra[key] = []
    loose = []
    for d in found:
        i = bisect.bisect_right(starts, d.span.start.offset) - 1
        if i < 0:
            loose.append(d)  # before the first statement: kept by no part
        else:
            parts[i].extra[key].append(fresh(d))
    snap.extra[key] = tables if not loose else None
    out = list(loose)
    for p in parts:
        out.extend(fresh(d) for d in p.extra.get(key, ()))
    return out


def _to_judge(facts: FileFacts, fa, plan, previous, texts: list, keys: list) -> set[int]:
    """The statements whose judgement may differ from the last version's: the others get their
    findings back (moved) on their parts."""
    parts = fa.snapshot.parts
    changed = _changed_names(previous.extra["rule texts"], texts)
    if ANY in changed:  # a statement that defines no name (an import, a broken line) changed: it may
        return set(range(len(parts)))  # change what any name means, so everything is judged again
    old_texts = previous.extra["rule texts"]
    by_text: dict[str, list] = {}
    for (_name, text), p in zip(old_texts, previous.parts):
        by_text.setdefault(text, []).append(p)
    path = facts.path
    judged = set()
    for i, p in enumerate(parts):
        if i not in plan.reused:
            olds = by_text.get(texts[i][1])
            old = olds.pop(0) if olds else None
            if old is None or old.rule_reads is None or old.rule_sig != _signature(facts, parts, i):
                judged.add(i)
                continue
            moves = [(old.start, old.end, p.start - old.start, p.line - old.line)]
            for key in keys:
                moved = moved_diags(old.extra.get(key, []), moves, path)
                if moved is None:
                    judged.add(i)
                    break
                p.extra[key] = moved
            else:
                p.rule_reads, p.rule_sig, p.was_line = old.rule_reads, old.rule_sig, old.line
            if i in judged:
                continue
        if p.rule_reads is not None and (ANY in p.rule_reads or not p.rule_reads.isdisjoint(changed)):
            judged.add(i)
        elif p.line != p.was_line and any(p.extra.get(k) for k in keys):
            judged.add(i)
    return judged


def _changed_names(old: list, new: list) -> set[str]:
    """The top-level names whose definitions (their statements' texts, in order) differ."""
    def by_name(items):
        out: dict[str, list] = {}
        for name, text in items:
            out.setdefault(name if name is not None else ANY, []).append(text)
        return out

    a, b = by_name(old), by_name(new)
    return {n for n in a.keys() | b.keys() if a.get(n) != b.get(n)}


def _judge(module, rules, facts: FileFacts, parts: list, judged: list | None, stmts: list):
    """A module's findings on the judged statements (None: all) and the file-wide tables it read."""
    report = Reporter(rules, facts.path)
    if judged is not None:
        facts = replace(facts, statements=tuple(stmts[i] for i in judged),
                        occs=[o for i in judged for o in _occurrences(facts, parts[i])])
    with model_recording() as seen:
        module.check(facts, report)
    return report.found, [r for r in seen if r[0] == "v"]


def _record_reads(facts: FileFacts, parts: list, i: int, stmts: list, modules) -> None:
    """What judging statement `i` alone reads (every module), kept on its part for the next version."""
    view = replace(facts, statements=(stmts[i],), occs=_occurrences(facts, parts[i]))
    found = []
    with model_recording() as seen:
        for module, rules in modules:
            report = Reporter(rules, facts.path)
            module.check(view, report)
            found.extend(report.found)
    p = parts[i]
    if any(not p.start <= d.span.start.offset < p.end for d in found):
        # a finding about another statement (a ring blamed where it closes): such a judgement is
        # re-done whenever the model's plan checks the statement again, as the statements it reached
        # by name are then checked again too
        p.rule_reads = p.rule_sig = None
        return
    unit = facts.unit
    starts = [p.start for p in parts]
    names = set()
    for r in seen:
        if r[0] == "n":
            names.add(r[1])
        elif r[0] == "m":
            names.add(_top_name(r[1], unit, starts, stmts))
    for o in _occurrences(facts, parts[i]):
        names.add(_top_name(o.target, unit, starts, stmts))
    names.discard(None)
    parts[i].rule_reads = frozenset(names)
    parts[i].rule_sig = _signature(facts, parts, i)
    parts[i].was_line = parts[i].line


def _top_name(sym, unit, starts: list, stmts: list):
    """The top-level name of the statement of this file holding a symbol (None: not of this file)."""
    t = type(sym)
    if t is ModelSym or t is GlobalSym:
        home = sym.unit
    elif t is MemberSym or t is MethodSym:
        home = sym.owner.unit
    else:
        return None
    if home is not unit or sym.stmt is None:
        return None
    k = bisect.bisect_right(starts, sym.stmt.span.start.offset) - 1
    name = defined(stmts[k]) if k >= 0 else None
    return name if name is not None else ANY


def _signature(facts: FileFacts, parts: list, i: int) -> tuple:
    """The checker's facts of statement `i` as the rules read them, relative to the statement: its
    diagnostics and its resolved names (a symbol of this file by its place, another by identity)."""
    p = parts[i]
    unit, stmts = facts.unit, facts.tree.statements
    starts = [q.start for q in parts]
    diags = tuple(_finding_signature(d, p.start) for d in p.diags)
    occs = []
    for o in _occurrences(facts, p):
        target = o.target
        top = _top_name(target, unit, starts, stmts)
        if top is not None:
            stmt = target.stmt
            k = bisect.bisect_right(starts, stmt.span.start.offset) - 1
            where = (type(target).__name__, getattr(target, "name", None), top, stmt.span.start.offset - starts[k])
        else:
            where = id(target)
        occs.append((o.span.start.offset - p.start, o.span.end.offset - p.start, o.kind, where))
    return diags, tuple(occs)


def _finding_signature(d, base: int) -> tuple:
    """A diagnostic or a model fact (model/facts.py) as a rule reads it, places relative to `base`."""
    if isinstance(d, Fact):
        return (type(d).__name__,) + tuple(
            (v.start.offset - base, v.end.offset - base) if hasattr(v, "end") else v
            for v in (getattr(d, f.name) for f in dataclass_fields(d)))
    return d.code, d.message, d.severity, d.span.start.offset - base, d.span.end.offset - base


def _occurrences(facts: FileFacts, part) -> list:
    """A statement's occurrences (a re-used one's are built from its records on first need)."""
    if part.occs is not None:
        return part.occs
    return [o for o in facts.analysis.occurrences if part.start <= o.span.start.offset < part.end]


def _inside(found: list[Diagnostic], starts: list[int], judged: set) -> bool:
    return all(bisect.bisect_right(starts, d.span.start.offset) - 1 in judged for d in found)
