"""`plx fmt`: the canonical OpenPLX formatter (style: docs/formatter.md).

`format_text` and `format_range` are the entry points for the language server; both import only
the syntax layer, never pygls, mujoco or rich.
"""

from plxtools.fmt.api import FormatError, FormatResult, format_bytes, format_text
from plxtools.fmt.ranges import format_range

__all__ = ["FormatError", "FormatResult", "format_bytes", "format_range", "format_text"]
