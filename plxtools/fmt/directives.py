"""Comments that steer the formatter: `# plx: fmt: off`, `# plx: fmt: on`, `# plx: fmt: skip`.

Spelled like the linter's `# plx: ignore[...]` so that one prefix marks every plxtools comment.
"""

from __future__ import annotations

import re

_DIRECTIVE = re.compile(r"#\s*plx:\s*fmt:\s*(off|on|skip)\s*$")


def directive(comment_text: str) -> str | None:
    """ "off", "on" or "skip" when the comment is exactly that directive, else None."""
    m = _DIRECTIVE.match(comment_text.strip())
    return m.group(1) if m else None
