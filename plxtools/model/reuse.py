"""Re-using a file's check from its previous version (the language server checks on every edit).

What the checker finds in a top-level statement depends on the statement's own text and on the
statements it names: directly, or through those (a truck names its wheel, the wheel its material).
So each statement gets a key: the texts, in file order, of every statement in that closure (by the
plain words each text contains, an over-approximation), plus a key for the whole file (imports,
operators, lines that did not parse, the bundles and other files through the program's epoch).
A statement whose key is unchanged gets its findings back, moved to where the statement now is,
with their targets exchanged for the new version's symbols; the rest are checked again.

Anything this cannot map (a finding outside its statement, a target it cannot find again, a name
that is not a plain word, an import) means "check it again": re-use is an optimisation, never a
second answer. Tests compare it with a fresh check on random edits."""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field, replace

from plxtools.diagnostics import Diagnostic, Edit, Fix, Pos, Span
from plxtools.model.symbols import FileUnit, GlobalSym, MemberSym, MethodSym, ModelSym
from plxtools.syntax import ast

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PLAIN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


@dataclass(slots=True)
class Part:
    """One top-level statement's findings, as the checker (and rules on top of it) made them."""

    start: int  # the statement's region in the text it was checked in: offsets and first line
    end: int
    line: int
    diags: list  # as reported, before any later step added help to them (kept unchanged)
    occs: list | None  # in this version (None until asked for: built from `records`)
    positional: bool  # a finding names a line elsewhere in the file: valid only where it was
    extra: dict = field(default_factory=dict)  # findings of rules that run on top, by rule
    # the occurrences relative to the statement, their targets of this file named by (class, name,
    # serial of the statement holding the target, offset in it): the same in every version
    records: list | None = None
    uses: frozenset = frozenset()  # this file's top-level models it names (C003)
    names: frozenset | None = None  # a suggestion was looked for: the file's top-level names then
    # the statement's first line in the version its `extra` findings were made or last re-used in
    # (a rule's message may name a line: rules/incremental.py judges a moved statement again)
    was_line: int | None = None
    # what the rules' judgement of the statement read (rules/incremental.py): the top-level names
    # (None: not recorded, judged with the whole file) and the checker's findings it judged
    rule_reads: frozenset | None = None
    rule_sig: tuple | None = None


@dataclass(slots=True)
class Snapshot:
    """What the next version of the file needs to re-use this version's findings."""

    program: object
    path: str
    epoch: int  # the program's epoch right after this file was registered
    file_key: tuple
    keys: list  # per top-level statement
    parts: list  # Part per top-level statement
    unit: FileUnit  # the version these findings belong to (their targets are its symbols)
    serials: dict = field(default_factory=dict)  # statement key -> a small number, kept between versions
    words: dict = field(default_factory=dict)  # statement text -> its words (statement_keys)
    extra: dict = field(default_factory=dict)  # whole-file findings of rules on top, keyed as they need


@dataclass(slots=True)
class Plan:
    """Which statements of the new version to check, and how to move the others' findings."""

    keys: list
    regions: list  # (start, end, line) per top-level statement
    file_key: tuple
    reused: dict  # index -> Part, already moved to the new text (diags, occurrences, extra)
    dirty: set
    moves: list  # sorted (old start, old end, offset delta, line delta) of the re-used regions
    usable: bool  # False: nothing of this version may be kept for the next one
    based: bool = False  # the previous version was compared with this one (its findings may be used)
    serials: list = field(default_factory=list)  # per statement: the same number as the last version's
    # statement of the same key (so rules can key what they keep by it), else a new one
    table: dict = field(default_factory=dict)  # key -> serial, for the next version
    words: dict = field(default_factory=dict)  # statement text -> its words, for the next version
    names: frozenset = frozenset()  # the names the file's top-level statements define

    def number(self, previous: "Snapshot | None") -> None:
        old = previous.serials if previous is not None and self.based else {}
        top = max(old.values(), default=0)
        table = {}
        serials = []
        taken = set()
        for k in self.keys:
            got = old.get(k)
            if got is None or got in taken:  # a new statement, or a second one of the same key
                top += 1
                got = top
            taken.add(got)
            table.setdefault(k, got)
            serials.append(got)
        self.table = table
        self.serials = serials

    def move_span(self, span: Span) -> Span | None:
        """An old span in a re-used region, moved to the new text (None: not in one)."""
        return _move_span(self.moves, span)

    def move_diag(self, d: Diagnostic, path: str) -> Diagnostic | None:
        return _move_diag(self.moves, d, path)


def file_key(program, unit: FileUnit, known_annotations) -> tuple | None:
    """What every statement's check depends on besides the statements it names; None when the
    file has something this module does not follow (imports, names that are not plain words)."""
    tree = unit.tree
    operators, broken = [], []
    text = tree.text
    for s in tree.statements:
        if isinstance(s, ast.Import):
            return None  # an import binds symbols made per registration: not followed here
        if isinstance(s, ast.OperatorDecl):
            operators.append(text[s.span.start.offset:s.span.end.offset])
        elif isinstance(s, ast.ErrorStmt):
            broken.append((s.span.start.line, s.text))
        name = _defined(s)
        if name is not None and not _PLAIN.match(name):
            return None
    return (unit.path, unit.bundle, tuple(operators), tuple(broken), frozenset(known_annotations or ()))


def regions(tree: ast.File) -> list[tuple[int, int, int]]:
    """Each top-level statement's stretch of text: from the start of its line to the next one's
    (its indentation is part of it: findings keep their columns when it moves)."""
    stmts = tree.statements
    out = []
    n = len(stmts)
    starts = [s.span.start.offset - s.span.start.column for s in stmts]  # from the line's start
    for i, s in enumerate(stmts):
        end = starts[i + 1] if i + 1 < n else len(tree.text)
        out.append((starts[i], end, s.span.start.line))
    return out


def statement_keys(tree: ast.File, regs: list[tuple[int, int, int]], defined: list, words: dict | None = None
                   ) -> list[tuple]:
    """`defined`: the name each statement defines (or None); `words`: the words of each statement
    text seen before (text -> frozenset), kept between versions so only changed statements are
    scanned; it is updated to this version's texts."""
    text = tree.text
    texts = [text[a:b] for a, b, _ in regs]
    defs: dict[str, list[int]] = {}
    for i, name in enumerate(defined):
        if name is not None:
            defs.setdefault(name, []).append(i)
    seen_words = words if words is not None else {}
    now: dict[str, frozenset] = {}
    deps: list[set[int]] = []
    for t in texts:
        ws = seen_words.get(t)
        if ws is None:
            ws = frozenset(_WORD.findall(t))
        now[t] = ws
        mine: set[int] = set()
        for w in ws:
            got = defs.get(w)
            if got:
                mine.update(got)
        deps.append(mine)
    if words is not None:
        words.clear()
        words.update(now)
    keys = []
    for i in range(len(texts)):
        seen = {i}
        stack = [i]
        while stack:
            for k in deps[stack.pop()]:
                if k not in seen:
                    seen.add(k)
                    stack.append(k)
        keys.append(tuple(texts[k] for k in sorted(seen)))
    return keys


def defined(s: ast.Stmt) -> str | None:
    """The top-level name a statement defines (None: none)."""
    return _defined(s)


def _defined(s: ast.Stmt) -> str | None:
    if isinstance(s, ast.TraitDef):
        return s.name.name
    path = getattr(s, "path", None)
    if path is not None and path.parts:
        return path.parts[0].name
    return None


def plan(previous: Snapshot | None, program, unit: FileUnit, others: int, known_annotations) -> Plan:
    """`others`: the program's epoch without this file's own changes, before it was registered."""
    tree = unit.tree
    regs = regions(tree)
    fkey = file_key(program, unit, known_annotations)
    n = len(regs)
    if fkey is None:
        return Plan([], regs, (), {}, set(range(n)), [], False)
    defined = [_defined(s) for s in tree.statements]
    names = frozenset(name for name in defined if name is not None)
    words = previous.words if previous is not None and previous.path == unit.path else {}
    keys = statement_keys(tree, regs, defined, words)
    if previous is None or previous.program is not program or previous.epoch != others or previous.file_key != fkey:
        out = Plan(keys, regs, fkey, {}, set(range(n)), [], True, words=words, names=names)
        out.number(None)
        return out
    matched = _matched(previous, keys)
    moves = sorted((p.start, p.end, regs[i][0] - p.start, regs[i][2] - p.line) for i, p in matched.items())
    reused: dict[int, Part] = {}
    for i, p in matched.items():
        part = _moved_part(p, regs[i], moves, names, unit.path)
        if part is not None:
            reused[i] = part
    out = Plan(keys, regs, fkey, reused, set(range(n)) - set(reused), moves, True, True, words=words, names=names)
    out.number(previous)
    return out


def _matched(previous: Snapshot, keys: list) -> dict[int, Part]:
    """Each statement of this version whose key an earlier statement had: that statement's part
    (equal keys are paired in order)."""
    by_key: dict[tuple, list[int]] = {}
    for j, k in enumerate(previous.keys):
        by_key.setdefault(k, []).append(j)
    matched: dict[int, Part] = {}
    for i, k in enumerate(keys):
        olds = by_key.get(k)
        if olds:
            matched[i] = previous.parts[olds.pop(0)]
    return matched


def _moved_part(p: Part, region: tuple, moves: list, names: frozenset, path) -> Part | None:
    """An unchanged statement's earlier results at its new place, or None when they cannot be kept:
    a finding that names its line moved lines, the file's names changed under a suggestion, or a
    diagnostic points into text that changed."""
    start, end, line = region
    if p.positional and line != p.line or p.names is not None and p.names != names:
        return None
    diags = _moved_diags(p.diags, moves, path)
    if diags is None or p.records is None:
        return None
    extra = {}
    for rule, found in p.extra.items():
        moved = _moved_diags(found, moves, path)
        if moved is None:
            return None
        extra[rule] = moved
    return Part(start, end, line, diags, None, p.positional, extra, p.records, p.uses, p.names, p.line,
                p.rule_reads, p.rule_sig)


def moved_diags(diags: list, moves: list, path) -> list | None:
    """Diagnostics moved by `moves` (sorted (old start, old end, offset delta, line delta)); None
    when one points outside the moved regions."""
    return _moved_diags(diags, moves, path)


def _moved_diags(diags: list, moves: list, path) -> list | None:
    moved = [_move_diag(moves, d, path) for d in diags]
    return None if any(d is None for d in moved) else moved


def record(part: Part, occs: list, unit: FileUnit, regs: list, serials: list) -> None:
    """Keep a checked statement's occurrences in the form any later version can use (Part.records)."""
    starts = [r[0] for r in regs]
    start, line = part.start, part.line
    out = []
    uses = set()
    table = unit.locals if unit.bundle is None else None
    for o in occs:
        s, e = o.span
        target = o.target
        tt = type(target)
        if tt is ModelSym or tt is GlobalSym:
            home = target.unit
        elif tt is MemberSym or tt is MethodSym:
            home = target.owner.unit
        else:
            home = None
        if home is unit:
            if table is not None and o.kind != "definition" and tt is ModelSym and table.get(target.name) is target:
                uses.add(target.name)
            where = place(starts, serials, target.stmt) if target.stmt is not None else None
            if where is None:
                part.records = None
                return
            target = (tt, target.name, *where)
        out.append((s.offset - start, s.line - line, s.column, e.offset - start, e.line - line, e.column, o.kind,
                    target, home is unit))
    part.records = out
    part.uses = frozenset(uses)


class Occurrences:
    """A version's occurrences, built when first asked for (hover, references, tokens): the
    re-used statements' from their records, with the targets looked up among this version's
    symbols. A check does not pay for it, so diagnostics go out sooner."""

    __slots__ = ("parts", "unit", "program", "regs", "serials", "known", "occurrence", "_all")

    def __init__(self, parts: list, unit: FileUnit, program, regs: list, serials: list, known, occurrence):
        self.parts, self.unit, self.program, self.regs, self.serials = parts, unit, program, regs, serials
        self.known, self.occurrence = known, occurrence
        self._all = None

    def all(self) -> list:
        if self._all is None:
            index = None
            out = []
            for i, part in enumerate(self.parts):
                if part.occs is None:
                    if index is None:
                        index = _symbol_index(self.unit, self.regs, self.serials)
                    part.occs = self._build(part, index)
                    if part.occs is None:
                        part.occs = self._check_again(i)
                out.extend(part.occs)
            self._all = out
            self.parts = self.program = None  # what the list needed is done with
        return self._all

    def _build(self, part: Part, index: dict) -> list | None:
        start, line = part.start, part.line
        make = self.occurrence
        out = []
        for rs, rl, sc, re_, el, ec, kind, target, local in part.records:
            if local:
                target = index.get(target)
                if target is None:
                    return None
            out.append(make(_span(start + rs, line + rl, sc, start + re_, line + el, ec), target, kind))
        return out

    def _check_again(self, i: int) -> list:
        """A target not found again (not expected: the statement's closure is unchanged): the
        occurrences of that statement from the checker itself."""
        from plxtools.model.checker import Checker

        if self.program is None or self.program.units.get(self.unit.path) is not self.unit:
            return []  # a newer version replaced this one: nobody reads these any more
        checker = Checker(self.program, self.unit, self.known)
        checker.run({i})
        o0, o1 = checker.slices[i][2:4]
        return checker.occurrences[o0:o1]


def _span(so: int, sl: int, sc: int, eo: int, el: int, ec: int) -> Span:
    return _tuple_new(Span, (_tuple_new(Pos, (so, sl, sc)), _tuple_new(Pos, (eo, el, ec))))


_tuple_new = tuple.__new__


def _symbol_index(unit: FileUnit, regs: list, serials: list) -> dict:
    """This version's symbols by (class, name, serial of their statement, offset in it)."""
    starts = [r[0] for r in regs]
    out: dict = {}

    def put(sym, cls) -> None:
        where = place(starts, serials, sym.stmt)
        if where is not None:
            out[(cls, sym.name, *where)] = sym

    table = unit.locals if unit.bundle is None else unit.namespace.symbols
    stack = []
    for sym in table.values():
        if getattr(sym, "unit", None) is unit:
            if isinstance(sym, GlobalSym):
                put(sym, GlobalSym)
            elif isinstance(sym, ModelSym):
                stack.append(sym)
    while stack:
        m = stack.pop()
        if m.stmt is not None:
            put(m, ModelSym)
        for tbl in (m.members, *m.path_members.values()):
            for mem in tbl.values():
                put(mem, MemberSym)
                if mem.anon is not None:
                    stack.append(mem.anon)
        for meth in m.methods.values():
            put(meth, MethodSym)
    return out


def place(starts: list, serials: list, stmt) -> tuple[int, int] | None:
    """Where a symbol's statement is, in terms that survive moves: (serial of the top-level
    statement holding it, offset from that statement's start)."""
    at = stmt.span.start.offset
    k = bisect.bisect_right(starts, at) - 1
    return (serials[k], at - starts[k]) if k >= 0 else None


def _region(moves: list, offset: int):
    i = bisect.bisect_right(moves, (offset, float("inf"))) - 1
    if i >= 0:
        m = moves[i]
        if m[0] <= offset < m[1]:
            return m
    return None


def _move_span(moves: list, span: Span) -> Span | None:
    m = _region(moves, span.start.offset)
    if m is None or span.end.offset > m[1]:
        return None
    if m[2] == 0 and m[3] == 0:
        return span
    s, e = span
    do, dl = m[2], m[3]
    return _span(s.offset + do, s.line + dl, s.column, e.offset + do, e.line + dl, e.column)


def _move_diag(moves: list, d: Diagnostic, path: str) -> Diagnostic | None:
    if type(d) is not Diagnostic:  # a fact (model/facts.py): every place in it moves
        return d.moved(lambda span: _move_span(moves, span))
    span = _move_span(moves, d.span)
    if span is None:
        return None
    fix = d.fix
    if fix is not None:
        m = _region(moves, d.span.start.offset)
        edits = []
        for e in fix.edits:
            if not m[0] <= e.start <= e.end <= m[1]:
                return None
            edits.append(Edit(e.start + m[2], e.end + m[2], e.text))
        fix = Fix(fix.message, tuple(edits), fix.safe)
    related = []
    for item in d.related:
        where, rspan, msg = item
        if where in (path, "", None):
            rspan = _move_span(moves, rspan)
            if rspan is None:
                return None
        related.append((where, rspan, msg))
    return replace(d, span=span, fix=fix, related=related)


def fresh(d: Diagnostic) -> Diagnostic:
    """A copy later steps may change without changing what is kept for the next version (a fact
    cannot change: itself)."""
    return replace(d, related=list(d.related)) if type(d) is Diagnostic else d


def assemble(checker, plan: Plan, unit: FileUnit, program, known, occurrence):
    """The file's findings in the order a full check makes them (file-wide ones, then statement
    by statement), its occurrences (built when asked for), and the snapshot the next version
    re-uses. Diagnostics handed on are copies, which later steps may change."""
    first = min((sl[0] for sl in checker.slices.values()), default=len(checker.diags))
    diags = checker.diags[:first]
    parts: list = []
    for i, (start, end, line) in enumerate(plan.regions):
        part = plan.reused.get(i)
        if part is None:
            d0, d1, o0, o1, positional, suggests = checker.slices[i]
            part = Part(start, end, line, [fresh(d) for d in checker.diags[d0:d1]], checker.occurrences[o0:o1],
                        positional, names=plan.names if suggests else None)
            if plan.usable:
                record(part, part.occs, unit, plan.regions, plan.serials)
        parts.append(part)
        diags.extend(fresh(d) for d in part.diags)
    snap = None
    if plan.usable:
        snap = Snapshot(program, unit.path, program.epoch_without(unit.path), plan.file_key, plan.keys,
                        parts, unit, plan.table, plan.words)
    return diags, Occurrences(parts, unit, program, plan.regions, plan.serials, known, occurrence), snap
