"""`$"..."` strings: their `{VAR}` parts are read from the environment (the runtime finds AGX's data
folder this way). One reading for the checker, `plx check` and lint's result cache, which must not
import the parser, so this sits below every layer."""

from __future__ import annotations

import re

_VAR = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)\}")


def variables(value: str) -> list[str]:
    """The variables ``value`` reads, each once, in order."""
    return list(dict.fromkeys(_VAR.findall(value)))


# Whether messages may show what a `$"..."` string expands to. Off unless `plx check --show-env`:
# a model in a pull request can name any variable, and CI logs are public, so by default a message
# shows the expression as written (`$"{AGX_DATA_DIR}/x.obj"`), never a variable's value.
_show_values = False


def show_values(on: bool) -> None:
    """Let messages show expanded values (`plx check --show-env`); the process's whole run."""
    global _show_values
    _show_values = bool(on)


def shown(raw: str, expanded: str) -> str:
    """How a message names a `$"..."` string: its source text, with its value only when allowed."""
    return f"{expanded!r} (from {raw})" if _show_values else raw


def expand(value: str) -> tuple[str, list[str]]:
    """(``value`` with every `{VAR}` replaced by its value, "" when unset; the unset variables)."""
    from plxtools.cache import reads  # each variable read is noted: a cached answer depends on it

    got = {v: reads.env(v) for v in variables(value)}
    unset = [v for v, x in got.items() if x is None]
    return _VAR.sub(lambda m: got.get(m.group(1)) or "", value), unset
