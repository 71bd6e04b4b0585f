"""Rule catalogues, one module per family; importing this package registers every rule."""

from plxtools.rules.catalog import assembly, hygiene, semantic, syntax  # noqa: F401
