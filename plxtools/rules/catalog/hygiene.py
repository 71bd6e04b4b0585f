"""Hygiene rules about plxtools' own mechanisms (C0xx)."""

from plxtools.rules.catalog.pages import doc

doc("UNUSED_SUPPRESSION",
    "A `# plx: ignore[...]` comment suppresses nothing (or names a code that no longer occurs there).",
    "Suppressions outlive the problems they hid; a stale one would hide the next, real problem on that "
    "line.",
    example="mass: 10  # plx: ignore[T001]",
    use_instead="mass: 10")
