"""Comments that steer the formatter: `# plx: fmt: off`, `# plx: fmt: on`, `# plx: fmt: skip`.

Spelled like the linter's `# plx: ignore[...]` so that one prefix marks every plxtools comment.
"""

from __future__ import annotations

import re

from plxtools.rules import suppress

_DIRECTIVE = re.compile(r"#\s*plx:\s*fmt:\s*(off|on|skip)\s*$")


def directive(comment_text: str) -> str | None:
    """ "off", "on" or "skip" when the comment is exactly that directive, else None."""
    m = _DIRECTIVE.match(comment_text.strip())
    return m.group(1) if m else None


def is_line_suppression(comment_text: str) -> bool:
    """A `# plx: ignore[...]` comment: it covers one line, so what it covers must not move."""
    sc = suppress.parse(comment_text)
    return sc is not None and not sc.file_wide
