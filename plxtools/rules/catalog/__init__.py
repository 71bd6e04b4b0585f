"""The pages of the rules not in the module form, one module per family (rules/registry.py holds
their codes, severities and stages)."""

from plxtools.rules.catalog import assembly, hygiene, pages, semantic, syntax  # noqa: F401
