"""Runs the rule modules: facts in, diagnostics out, with the code and severity the registry gives.

A rule module (`docs/architecture.md`, "The rule engine") never writes its code nor its severity:
it reads `FileFacts` and calls `report(message, span, ...)`; the reporter stamps the registry's
code and severity on the diagnostic. `rules/analysis.py` calls `run_file_rules` once per analysed
file, and lint, check and the language server all go through it, so a rule runs in one place.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

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
    unset: tuple = ()
    used_names: frozenset = frozenset()

    @property
    def unit(self):
        return self.analysis.unit

    @property
    def occurrences(self) -> list:
        """The resolved names of the file (built on first read: the server may not need them)."""
        return self.analysis.occurrences

    @property
    def path(self) -> str:
        return self.tree.path


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


def run_file_rules(facts: FileFacts) -> list[Diagnostic]:
    """Every lint-stage rule module's findings on one file."""
    out: list[Diagnostic] = []
    for module, rules in file_rule_modules("lint"):
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
