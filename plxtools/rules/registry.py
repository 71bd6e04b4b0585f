"""The rule registry: one entry per diagnostic code, with the docs page that `plx rule` prints.

Every code any layer emits (syntax, semantic model, assembly checks, simulation) is registered
here, so docs, SARIF rule tables, `select`/`ignore` and the severity every command prints all come
from one list. A rule in the module form (`docs/architecture.md`, "The rule engine") is one line
in `MODULE_RULES` below: its code, name, severity, stage and module; its documentation is that
module's docstring and its findings are made by that module's `check`. The older form (a `rule()`
call with its documentation in `catalog/`) is being moved into that table one family at a time.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass, replace

from plxtools.diagnostics import Severity

E, W, I = Severity.ERROR, Severity.WARNING, Severity.INFO


@dataclass(frozen=True, slots=True)
class Rule:
    code: str
    name: str  # kebab-case
    severity: Severity
    summary: str
    why: str
    example: str = ""
    use_instead: str = ""
    fix: str = "none"  # "none" | "safe" | "unsafe"
    stage: str = "lint"  # "syntax" | "lint" | "check" | "simulate"
    # the rule module under plxtools/rules/ that makes this code's findings and holds its docs
    # ("assembly.shared_connector"); None for a rule still in the older form
    module: str | None = None
    tags: tuple[str, ...] = ()  # "deprecated", "unnecessary": how an editor may draw the finding
    # codes this one makes redundant: when both are reported on one line, only this one stands
    owns: tuple[str, ...] = ()
    # the severity of the code's graver form, when the raising site tells two forms apart (S003: a
    # tab that makes a line's block ambiguous is an error); None: one severity for every finding
    graver: Severity | None = None

    def page(self) -> str:
        """The rule's documentation page as Markdown."""
        out = [f"# {self.code} {self.name}", "", f"Default severity: **{self.severity.value}** · "
               f"stage: `{self.stage}` · fix: {self._fix_text()}", "", "## What it does", "",
               self.summary, "", "## Why it matters", "", self.why, ""]
        if self.example:
            out += ["## Example", "", "```openplx", self.example.rstrip(), "```", ""]
        if self.use_instead:
            out += ["## Use instead", "", "```openplx", self.use_instead.rstrip(), "```", ""]
        return "\n".join(out)

    def _fix_text(self) -> str:
        return {"none": "not fixable", "safe": "safe fix available", "unsafe": "unsafe fix available"}[self.fix]


RULES: dict[str, Rule] = {}


def rule(code: str, name: str, severity: Severity, summary: str = "", why: str = "", *, example: str = "",
         use_instead: str = "", fix: str = "none", stage: str = "lint", module: str | None = None,
         tags: tuple[str, ...] = (), owns: tuple[str, ...] = (), graver: Severity | None = None) -> Rule:
    if code in RULES:
        raise ValueError(f"duplicate rule code {code}")
    r = Rule(code, name, severity, summary, why, example, use_instead, fix, stage, module, tags, owns, graver)
    RULES[code] = r
    return r


# ---------------------------------------------------------------- rules in the module form
# One line per code. `module` is under plxtools/rules/; its docstring is the docs page and its
# `check(facts, report)` makes the findings (plxtools/rules/engine.py runs it for lint, check and
# the language server). Several tightly tied codes may share one module: it names the one it
# reports with `report(..., rule="their-name")`.
#
#     code    name                           severity  module                      stage, fix, tags, owns
MODULE_RULES = (
    ("A009", "instantiation-too-deep", E, "assembly.self_containing", dict()),
    ("A013", "connector-count", E, "assembly.controller_connectors", dict()),
    ("A015", "mate-same-body", E, "assembly.shared_connector", dict(fix="unsafe")),
    ("A022", "angle-probably-degrees", W, "assembly.angle_in_degrees", dict(fix="unsafe")),
    ("A043", "connector-used-by-two-mates", E, "assembly.shared_connector", dict(fix="unsafe")),
    ("A046", "controller-on-other-mate", W, "assembly.controller_connectors", dict()),
    ("A047", "explicit-zero-mass", W, "assembly.explicit_zero_mass", dict()),
    ("A048", "length-in-millimetres", W, "assembly.length_in_millimetres", dict()),
    ("M010", "assigned-twice", E, "semantic.assigned_twice", dict()),
)

_loaded = False


def _load() -> None:
    global _loaded
    if _loaded:
        return
    _loaded = True
    # importing the catalogues registers the rules of the older form
    from plxtools.rules import catalog  # noqa: F401

    for code, name, severity, module, more in MODULE_RULES:
        rule(code, name, severity, module=module, **more)
        RULES[code] = replace(RULES[code], **_docs_of(module))


def module_of(r: Rule):
    """The imported rule module of `r` (None for a rule in the older form)."""
    return importlib.import_module(f"plxtools.rules.{r.module}") if r.module else None


_SECTION = re.compile(r"^## (.+)$", re.M)
_CODE_BLOCK = re.compile(r"```openplx\n(.*?)```", re.S)


def _docs_of(module: str) -> dict[str, str]:
    """summary, why, example and use_instead read from a rule module's docstring: the paragraph(s)
    before its first `## ` heading, then `## Why it matters`, `## Example` and `## Use instead`."""
    doc = (importlib.import_module(f"plxtools.rules.{module}").__doc__ or "").strip()
    parts = _SECTION.split(doc)
    sections = dict(zip(parts[1::2], parts[2::2]))
    out = {"summary": _one_paragraph(parts[0]), "why": _one_paragraph(sections.get("Why it matters", ""))}
    for title, field in (("Example", "example"), ("Use instead", "use_instead")):
        block = _CODE_BLOCK.search(sections.get(title, ""))
        out[field] = block.group(1).rstrip("\n") if block else ""
    if not out["summary"] or not out["why"]:
        raise ValueError(f"rule module plxtools.rules.{module}: its docstring needs a summary and '## Why it matters'")
    return out


def _one_paragraph(text: str) -> str:
    return " ".join(text.split())


def severity_of(code: str, raised: Severity) -> Severity:
    """The severity every command reports `code` with: the registry's (`raised`, the raising site's,
    for an unknown code). A site may only say that a finding is the graver form of its code (a
    severity above the default) when the registry names that form (`graver`)."""
    _load()
    r = RULES.get(code)
    if r is None:
        return raised
    if r.graver is not None and raised.rank > r.severity.rank:
        return r.graver
    return r.severity


def all_rules() -> list[Rule]:
    _load()
    return sorted(RULES.values(), key=lambda r: r.code)


def code_of(name: str) -> str:
    """The code of the rule named `name` (kebab-case): how a layer that raises a rule of the module
    form (plx check's side of A009, A013, A015, A022) names it without writing the code."""
    r = get(name)
    if r is None or r.name != name:
        raise KeyError(f"no rule named {name!r}")
    return r.code


def get(code_or_name: str) -> Rule | None:
    _load()
    if code_or_name.upper() in RULES:
        return RULES[code_or_name.upper()]
    for r in RULES.values():
        if r.name == code_or_name:
            return r
    return None


def describe_codes(codes: set[str]) -> list[tuple[str, str, str]]:
    _load()
    return [(c, RULES[c].name, RULES[c].summary) for c in sorted(codes) if c in RULES]


def unknown_selectors(selectors) -> list[tuple[str, str | None]]:
    """The codes or prefixes in `selectors` that match no rule, each with the nearest real one.

    `N0002` in a `select` would otherwise silently select nothing, which reads as "all clear"."""
    selectors = [s for s in selectors if s.strip()]
    if not selectors:
        return []  # nothing to look up: the catalogue is not even loaded
    import difflib

    _load()
    prefixes = {code[:i] for code in RULES for i in range(1, len(code) + 1)}
    out = []
    for s in selectors:
        s = s.strip().upper()
        if not s or s == "ALL" or s in prefixes:
            continue
        near = difflib.get_close_matches(s, sorted(RULES) if len(s) >= 3 else sorted(prefixes), n=1, cutoff=0.6)
        out.append((s, near[0] if near else None))
    return out


def check_selectors(selectors, where: str) -> None:
    """Raise ValueError naming every unknown code or prefix in `selectors` (from `where`)."""
    bad = unknown_selectors(selectors)
    if bad:
        parts = [f"'{code}'" + (f" (did you mean '{near}'?)" if near else "") for code, near in bad]
        noun = "rule code or prefix" if len(bad) == 1 else "rule codes or prefixes"
        raise ValueError(f"{where}: unknown {noun} {', '.join(parts)}; `plx rule --all` lists them")
