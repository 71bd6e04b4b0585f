"""plxtools: linter, formatter, language server and physics checker for OpenPLX."""

__version__ = "0.1.0"

# Where the documentation site (built from docs/ with mkdocs) is published; the one place rule
# links come from. pyproject.toml's [project.urls] Documentation is the same (a test checks).
DOCS_BASE_URL = "https://plxtools.github.io/plxtools/"
