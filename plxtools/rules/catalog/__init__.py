"""Rule catalogues, one module per family; importing this package registers every rule."""

from plxtools.rules.catalog import assembly, hygiene, migration, semantic, syntax  # noqa: F401
