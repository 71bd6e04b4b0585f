"""Key bindings from a small TOML table: the common case of driving inputs with held keys.

::

    # drive.keys.toml: while a key is held, each input named under it gets its value
    [keys.Up]
    "box_truck.front_left_motor.target_angular_velocity_input" = 3.0
    "box_truck.front_right_motor.target_angular_velocity_input" = -3.0

    [released]   # what an input goes back to when its key is released (0 when not listed)
    "box_truck.front_left_motor.target_angular_velocity_input" = 0.0

A table is checked against the loaded scene (unknown paths get a did-you-mean), so a typo is a
located message when the view opens, not a key that silently does nothing.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plxtools.view.keys import KeyboardCallback, KeyEvent, key_code


class KeymapError(ValueError):
    """A key-binding table that cannot be used (the message names the file and the entry)."""


@dataclass
class Keymap:
    path: str
    held: dict[int, dict[str, Any]] = field(default_factory=dict)  # key -> input path -> value
    released: dict[str, Any] = field(default_factory=dict)  # input path -> value on release
    names: dict[int, str] = field(default_factory=dict)  # key -> the key as written


def read_keymap(path: str | Path) -> Keymap:
    p = Path(path)
    try:
        data = tomllib.loads(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise KeymapError(f"{p}: cannot read: {exc.strerror or exc}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise KeymapError(f"{p}: invalid TOML: {exc}") from None
    unknown = set(data) - {"keys", "released"}
    if unknown:
        raise KeymapError(f"{p}: unknown table(s) {', '.join(sorted(unknown))}; expected [keys.<KEY>] and [released]")
    km = Keymap(str(p))
    keys = data.get("keys", {})
    if not isinstance(keys, dict) or not keys:
        raise KeymapError(f"{p}: no [keys.<KEY>] table (for example [keys.Up])")
    for name, table in keys.items():
        try:
            code = key_code(name)
        except ValueError as exc:
            raise KeymapError(f"{p}: [keys.{name}]: {exc}") from None
        if not isinstance(table, dict) or not table:
            raise KeymapError(f"{p}: [keys.{name}] must map input paths to values")
        km.held[code] = dict(table)
        km.names[code] = name
    rel = data.get("released", {})
    if not isinstance(rel, dict):
        raise KeymapError(f"{p}: [released] must map input paths to values")
    km.released = dict(rel)
    return km


def bind_keymap(km: Keymap, sim: Any) -> None:
    """Check every path against ``sim`` and bind the keys (press: held values, release: released)."""
    from plxtools.check.api import PlxApiError

    paths = {path for table in km.held.values() for path in table} | set(km.released)
    for path in sorted(paths):
        try:
            obj = sim.get_object(path)
        except PlxApiError as exc:
            raise KeymapError(f"{km.path}: {exc}") from None
        if type(obj).__name__ != "Input":
            raise KeymapError(f"{km.path}: {path} is not an input signal ({obj.type})")
    # every value is checked against its input's kind now, not at the first key press
    for code, table in km.held.items():
        for path, value in table.items():
            _check_value(km, sim, path, value, f"[keys.{km.names[code]}]")
    for path, value in km.released.items():
        _check_value(km, sim, path, value, "[released]")

    for code, table in km.held.items():
        def on_key(ev: KeyEvent, table: dict = table) -> None:
            for path, value in table.items():
                sim.set(path, value if ev.down else km.released.get(path, _zero(value)))

        KeyboardCallback.bind(name=f"keymap:{km.names[code]}", key=code, callback=on_key)


def _zero(value: Any) -> Any:
    return [0.0] * len(value) if isinstance(value, list) else 0.0


def _check_value(km: Keymap, sim: Any, path: str, value: Any, where: str) -> None:
    from plxtools.check.api import PlxApiError
    from plxtools.check.signals import SignalValueError, coerce

    try:
        info = sim._signal(path, "input")
        coerce(info, value)
    except (SignalValueError, PlxApiError, TypeError, ValueError) as exc:
        raise KeymapError(f"{km.path}: {where} {path}: {exc}") from None
