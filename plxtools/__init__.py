"""plxtools: linter, formatter, language server and physics checker for OpenPLX."""

__version__ = "0.1.0"
