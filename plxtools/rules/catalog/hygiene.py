"""Hygiene rules about plxtools' own mechanisms (C0xx)."""

from plxtools.diagnostics import Severity
from plxtools.rules.registry import rule

rule("C002", "unused-suppression", Severity.WARNING,
     "A `# plx: ignore[...]` comment suppresses nothing (or names a code that no longer occurs there).",
     "Suppressions outlive the problems they hid; a stale one would hide the next, real problem on that "
     "line.", example="mass: 10  # plx: ignore[T001]", use_instead="mass: 10", fix="safe")
