"""Runs the rule modules: facts in, diagnostics out, with the code and severity the registry gives.

A rule module (`docs/architecture.md`, "The rule engine") never writes its code nor its severity:
it reads `FileFacts` and calls `report(message, span, ...)`; the reporter stamps the registry's
code and severity on the diagnostic. `rules/analysis.py` calls `run_file_rules` once per analysed
file, and lint, check and the language server all go through it, so a rule runs in one place.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cache

from plxtools.cache import reads
from plxtools.diagnostics import Diagnostic, Fix, Span
from plxtools.rules import registry
from plxtools.syntax import ast


@dataclass(frozen=True, slots=True)
class FileFacts:
    """What the model knows about one analysed file, for the rules that judge it.

    `program` answers lookups and types (plxtools/model/program.py); `analysis` is the model's
    FileAnalysis of the file (its unit and its facts: diagnostics, occurrences); `root` the model a
    run instantiates (None: the file's last model, or no run); `unset` the values and references
    what that model creates needs and nothing gives (model/completeness.py); `used_names` the
    file's top-level names that something in it names."""

    program: object
    analysis: object
    tree: ast.File
    root: object = None
    # the top-level statements to judge and their occurrences (None: the whole file); the language
    # server judges only the statements whose reads changed (rules/incremental.py)
    statements: tuple | None = None
    occs: list | None = None
    tables: dict = field(default_factory=dict)  # file-wide tables built once per analysis (`table`)
    unset: tuple = ()
    used_names: frozenset = frozenset()
    found: tuple | list = ()  # the model's facts about the file (plxtools/model/facts.py)

    def of(self, *kinds: type) -> list:
        """The model's facts of these kinds, in the order it found them."""
        return [f for f in self.found if isinstance(f, kinds)]

    @property
    def unit(self):
        return self.analysis.unit

    @property
    def judged(self) -> list:
        """The top-level statements a rule judges. A rule that also reads other statements (a
        file-wide table) says so with `read` (the value it read): re-use holds only while that
        value is the same."""
        return self.tree.statements if self.statements is None else self.statements

    @property
    def occurrences(self) -> list:
        """The resolved names of the judged statements (built on first read: the server may not
        need them)."""
        return self.analysis.occurrences if self.occs is None else self.occs

    def table_by_name(self, what: str, make) -> "ByName":
        """A table of the whole file keyed by top-level names (`make()`, once per analysis): reading
        an entry is recorded as reading that name, so only a change of that name's statement
        matters to the statements that read it."""
        got = self.tables.get(what)
        if got is None:
            got = self.tables[what] = ByName(make())
        return got

    def table_of_statements(self, what: str, of_statement) -> set:
        """The union of `of_statement(statement)` over the file's top-level statements, recorded as
        a file-wide read (`table`); each statement's share is kept by its text from one version to
        the next (`memo`, given by rules/incremental.py), so an edit computes only its own."""
        def make() -> set:
            memo = self.tables.get(MEMO)
            texts = self.tables.get(TEXTS)
            out: set = set()
            if memo is None or texts is None:
                for s in self.tree.statements:
                    out |= of_statement(s)
                return out
            now = self.tables.setdefault(NEXT_MEMO, {})
            for s, text in zip(self.tree.statements, texts):
                got = memo.get((what, text))
                if got is None:
                    got = frozenset(of_statement(s))
                now[(what, text)] = got
                out |= got
            return out

        return self.table(what, make)

    def table(self, what: str, make):
        """A table built from the whole file (`make()`, once per analysis, shared by every view of
        it), its read recorded in the open model recordings (plxtools.cache.reads): the findings of
        the judged statements depend on it."""
        got = self.tables.get(what, self.tables)
        if got is self.tables:
            got = self.tables[what] = make()
        if reads.model_active():
            reads.note_model(("v", what, got))
        return got

    @property
    def path(self) -> str:
        return self.tree.path


MEMO, TEXTS, NEXT_MEMO = "(memo)", "(texts)", "(next memo)"  # keys of FileFacts.tables kept by rules/incremental.py


class ByName(dict):
    """A file-wide table keyed by top-level names (`FileFacts.table_by_name`)."""

    def get(self, name, default=None):
        if reads.model_active():
            reads.note_model(("n", name))
        return super().get(name, default)


class Reporter:
    """`report(message, span, help=..., fix=..., related=...)`: one finding of a rule module.

    A module that holds several codes names the one it reports with `rule="its-name"`."""

    def __init__(self, rules: tuple[registry.Rule, ...], path: str):
        self._rules = {r.name: r for r in rules}
        self._default = rules[0] if len(rules) == 1 else None
        self._path = path
        self.found: list[Diagnostic] = []

    def __call__(self, message: str, span: Span, *, rule: str | None = None, help: str | None = None,
                 fix: Fix | None = None, related: list[tuple[str, Span, str]] | tuple = ()) -> Diagnostic:
        r = self._rules[rule] if rule is not None else self._default
        if r is None:
            raise ValueError(f"this module holds {sorted(self._rules)}: name the rule it reports")
        d = Diagnostic(r.code, message, span, r.severity, file=self._path, help=help, fix=fix,
                       related=list(related))
        self.found.append(d)
        return d


@cache
def file_rule_modules(stage: str = "lint") -> tuple[tuple[object, tuple[registry.Rule, ...]], ...]:
    """Each rule module of `stage` with the registry entries it reports, in code order."""
    by_module: dict[str, list[registry.Rule]] = {}
    for r in registry.all_rules():
        if r.module is not None and r.stage == stage:
            by_module.setdefault(r.module, []).append(r)
    return tuple((registry.module_of(rules[0]), tuple(rules)) for rules in by_module.values())


def run_fact_rules(facts: FileFacts) -> list[Diagnostic]:
    """The diagnostics of the model's facts: each rule module that reports a kind of fact (it
    names them in `FACTS`) turns those into its findings. They run before the rules that judge the
    file, which read the model's findings (a line with an error is that error's)."""
    if not facts.found:
        return []
    out: list[Diagnostic] = []
    kinds = {type(f) for f in facts.found}
    for module, rules in file_rule_modules("lint"):
        wanted = getattr(module, "FACTS", None)
        if wanted is None or kinds.isdisjoint(wanted):
            continue
        report = Reporter(rules, facts.path)
        module.check(facts, report)
        out.extend(report.found)
    return out


def run_file_rules(facts: FileFacts) -> list[Diagnostic]:
    """Every lint-stage rule module's findings on one file (the modules that report facts run
    before, in `run_fact_rules`)."""
    out: list[Diagnostic] = []
    for module, rules in file_rule_modules("lint"):
        if getattr(module, "FACTS", None) is not None:
            continue
        report = Reporter(rules, facts.path)
        module.check(facts, report)
        out.extend(report.found)
    return out


def apply_severity(diags: list[Diagnostic]) -> list[Diagnostic]:
    """Every diagnostic with its code's severity from the registry: the one place severity is set
    for what lint, check and the server print."""
    for d in diags:
        d.severity = registry.severity_of(d.code, d.severity)
    return diags
