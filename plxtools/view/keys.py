"""Key codes and the keyboard-callback registry that controller scripts bind to.

The names mirror the AGX runtime's (``agxSDK.GuiEventListener.KEY_Up``,
``KeyboardCallback.bind(name=..., key=..., callback=...)``, a callback receiving an object with
``.down``) so the tutorial's controller class runs after changing its imports only.  The values
are GLFW key codes: what MuJoCo's viewer passes to its key callback, and what ``glfw.get_key``
polls to notice that a held key was released (the viewer reports presses only).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable


class GuiEventListener:
    """Key constants under the runtime's names (GLFW codes)."""

    KEY_Up = 265
    KEY_Down = 264
    KEY_Left = 263
    KEY_Right = 262
    KEY_Space = 32
    KEY_Return = 257
    KEY_Escape = 256
    KEY_BackSpace = 259
    KEY_Tab = 258
    KEY_Page_Up = 266
    KEY_Page_Down = 267
    KEY_Home = 268
    KEY_End = 269
    KEY_Insert = 260
    KEY_Delete = 261


for _c in "ABCDEFGHIJKLMNOPQRSTUVWXYZ":  # KEY_A..KEY_Z and the runtime's lower-case KEY_a..KEY_z
    setattr(GuiEventListener, f"KEY_{_c}", ord(_c))
    setattr(GuiEventListener, f"KEY_{_c.lower()}", ord(_c))
for _d in range(10):
    setattr(GuiEventListener, f"KEY_{_d}", ord(str(_d)))
for _f in range(1, 13):
    setattr(GuiEventListener, f"KEY_F{_f}", 289 + _f)

KEY_NAMES: dict[str, int] = {
    name[4:].lower(): code for name, code in vars(GuiEventListener).items() if name.startswith("KEY_")
}
KEY_NAMES.update({"pageup": 266, "pagedown": 267, "enter": 257, "esc": 256})


def key_code(name: str | int) -> int:
    """The code of a key written as in a binding table ("Up", "w", "F5", "Space") or a number."""
    if isinstance(name, int) and not isinstance(name, bool):
        return name
    if not isinstance(name, str):
        raise ValueError(f"a key is a name such as \"Up\" or \"w\", not {name!r}")
    code = KEY_NAMES.get(name.strip().lower().replace("_", "").replace(" ", "")) if len(name) > 1 \
        else KEY_NAMES.get(name.lower())
    if code is None:
        raise ValueError(f"unknown key {name!r}; keys are letters, digits, F1-F12, Up, Down, Left, Right, "
                         "Space, Return, Tab, Page_Up, Page_Down, Home, End, Insert, Delete")
    return code


def key_name(code: int) -> str:
    for name, c in vars(GuiEventListener).items():
        if name.startswith("KEY_") and c == code and not (len(name) == 5 and name[4].islower()):
            return name[4:]
    return str(code)


@dataclass(frozen=True)
class KeyEvent:
    """What a bound callback receives: ``down`` is True on press, False on release."""

    key: int
    down: bool

    @property
    def name(self) -> str:
        return key_name(self.key)


@dataclass
class _Binding:
    name: str
    key: int
    callback: Callable[[KeyEvent], Any]


class KeyboardCallback:
    """The bindings of the running view (class-level, as the runtime's): ``bind`` adds one,
    the viewer calls ``dispatch`` on every press and release of a bound key."""

    _bindings: dict[str, _Binding] = {}

    @classmethod
    def bind(cls, name: str, key: int | str, callback: Callable[[KeyEvent], Any]) -> None:
        if not callable(callback):
            raise TypeError(f"KeyboardCallback.bind({name!r}): the callback must be callable")
        cls._bindings[str(name)] = _Binding(str(name), key_code(key), callback)

    @classmethod
    def unbind(cls, name: str) -> None:
        cls._bindings.pop(name, None)

    @classmethod
    def clear(cls) -> None:
        cls._bindings.clear()

    @classmethod
    def keys(cls) -> set[int]:
        return {b.key for b in cls._bindings.values()}

    @classmethod
    def bindings(cls) -> list[tuple[str, int]]:
        return [(b.name, b.key) for b in cls._bindings.values()]

    @classmethod
    def dispatch(cls, key: int, down: bool) -> int:
        """Call every callback bound to ``key``; returns how many were called."""
        hit = [b for b in cls._bindings.values() if b.key == key]
        for b in hit:
            b.callback(KeyEvent(key, down))
        return len(hit)
