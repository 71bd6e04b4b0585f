"""The rule registry: one entry per diagnostic code, with the docs page that `plx rule` prints.

Every code any layer emits (syntax, semantic model, assembly checks, simulation) is registered
here, so docs, SARIF rule tables and `select`/`ignore` all see the same list.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.diagnostics import Severity


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


def rule(code: str, name: str, severity: Severity, summary: str, why: str, *, example: str = "",
         use_instead: str = "", fix: str = "none", stage: str = "lint") -> Rule:
    if code in RULES:
        raise ValueError(f"duplicate rule code {code}")
    r = Rule(code, name, severity, summary, why, example, use_instead, fix, stage)
    RULES[code] = r
    return r


def _load() -> None:
    # importing the catalogues registers their rules
    from plxtools.rules import catalog  # noqa: F401


def all_rules() -> list[Rule]:
    _load()
    return sorted(RULES.values(), key=lambda r: r.code)


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
