"""What a plx diagnostic says in LSP terms, without pygls: the server's publishing and the early
phase before pygls has loaded (lsp/early.py) both build their diagnostics from these, so the two
cannot drift apart."""

from __future__ import annotations

from plxtools.rules import registry

SEVERITY = {"error": 1, "warning": 2, "info": 3}  # LSP DiagnosticSeverity by plx's Severity value
TAGS = {"unnecessary": 1, "deprecated": 2}  # LSP DiagnosticTag by the registry's tag


def message(d) -> str:
    """The message an editor shows: plx's message, then its help line."""
    return d.message + (f"\nhelp: {d.help}" if d.help else "")


def docs_href(d, rule_docs_url: str | None) -> str | None:
    """The rule's page (the `codeDescription` link), when a URL pattern is configured."""
    return rule_docs_url.replace("{code}", d.code) if rule_docs_url else None


def tags(d) -> list[int]:
    """The LSP tags of the diagnostic's rule (deprecated, unnecessary), from the registry."""
    rule = registry.RULES.get(d.code)
    return [TAGS[t] for t in (rule.tags if rule is not None else ()) if t in TAGS]


def fix_data(d) -> dict | None:
    """The `data` field carrying the fix to the code-action handler (None: no fix)."""
    if d.fix is None:
        return None
    return {"fix": {"message": d.fix.message, "safe": d.fix.safe,
                    "edits": [[e.start, e.end, e.text] for e in d.fix.edits]}}
