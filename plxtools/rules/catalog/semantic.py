"""Semantic rules: names (N), types (T), model structure (M), bundles (B), conventions (C)."""

from plxtools.rules.catalog.pages import doc


doc("UNREADABLE_FILE",
    "A file given on the command line or found in a folder cannot be read.",
    "Permissions or a broken link stop plxtools from reading it; nothing in it is checked.")

# ---------------------------------------------------------------- names
# ---------------------------------------------------------------- types
# ---------------------------------------------------------------- model structure
# ---------------------------------------------------------------- bundles
doc("BUNDLES_UNAVAILABLE",
    "The language server could not load any OpenPLX bundles (shown once per file, instead of the "
    "model's diagnostics).",
    "Without the bundles no name can be resolved, so the editor shows only syntax errors until the "
    "setup is fixed: install `openplx-bundles`, or point `bundlePath` / `bundle-path` at a folder "
    "of bundles. The message says what failed.")
# ---------------------------------------------------------------- conventions and hygiene
doc("NAMING_CONVENTION",
    "A definition does not follow the naming conventions: models and traits PascalCase, attributes "
    "snake_case, globals snake_case or UPPER_CASE (const instances may be lowercase).",
    "Consistent names make models easier to read and match the official bundles.",
    example="Scene is Physics3D.System:\n    boxTruck is BoxTruck",
    use_instead="Scene is Physics3D.System:\n    box_truck is BoxTruck")
doc("MISALIGNED_INDENTATION",
    "Lines of one block are indented differently.",
    "OpenPLX accepts it (some official files do it), but it is easy to misread, and it is also what a "
    "missing `:` on the line above looks like. `plx fmt` aligns siblings.")
