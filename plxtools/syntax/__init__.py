"""Text to syntax tree: the bottom layer, which knows nothing about types or bundles."""

from plxtools.syntax.parser import parse_bytes, parse_file, parse_text

__all__ = ["parse_bytes", "parse_file", "parse_text"]
