"""`plx fmt`: the canonical OpenPLX formatter (style: docs/formatter.md).

`format_text` and `format_range` are the entry points for the language server; both import only
the syntax layer, never pygls, mujoco or rich. They are loaded on first use (PEP 562), so
`plx fmt` on files it remembers as formatted imports neither the formatter nor the parser.
"""

from __future__ import annotations

__all__ = ["FormatError", "FormatResult", "format_bytes", "format_range", "format_text"]

_FROM = {"FormatError": "api", "FormatResult": "api", "format_bytes": "api", "format_text": "api",
         "format_range": "ranges"}


def __getattr__(name: str):
    where = _FROM.get(name)
    if where is None:
        raise AttributeError(f"module 'plxtools.fmt' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f"plxtools.fmt.{where}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
