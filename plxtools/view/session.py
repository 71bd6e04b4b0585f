"""The view's state without a window: load, reload, keys, stepping in real time.

Everything a test needs to prove is here (a reload swaps the model, a model that stops compiling
keeps the last good one and says why, keys drive inputs), so the window layer (window.py) is a
thin loop over it.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from typing import Any, Callable

from plxtools.view import deps
from plxtools.view.keys import GuiEventListener as K
from plxtools.view.keys import KeyboardCallback

# The tutorial's agxViewer keys the view handles itself (MuJoCo's own viewer keys work as well).
RELOAD_KEYS = (K.KEY_1, K.KEY_F5)
PAUSE_KEY = K.KEY_E
GEOMS_KEY = K.KEY_G
RESET_KEY = K.KEY_R
MAX_FRAME_S = 0.25  # a slow frame does not try to catch up more than this much simulated time


@dataclass
class LoadResult:
    ok: bool
    message: str  # one line for the screen
    details: list[str]  # the findings, one per line (errors first)
    seconds: float


class ViewSession:
    """One model file in the view: the current simulation, what to watch, the key state."""

    def __init__(self, path: str, model: str | None = None, *, bundle_path: list[str] | tuple = (),
                 openplx_version: str | None = None, controller: str | None = None,
                 keymap: str | None = None, paused: bool = False,
                 say: Callable[[str], None] = lambda line: None):
        self.path = path
        self.model = model
        self.bundle_path = list(bundle_path)
        self.openplx_version = openplx_version
        self.controller = controller
        self.keymap = keymap
        self.paused = paused
        self.say = say
        self.sim: Any = None  # plxtools.check.api.Simulation of the last good load
        self.generation = 0  # how many good loads so far (the window swaps its model when it moves)
        self.error: str | None = None  # why the last load failed (None: it did not)
        self.show_collision = False  # G: collision geometry instead of the visuals
        self.stamps: dict[str, tuple[int, int] | None] = {}
        self.realtime = 1.0  # simulated seconds per wall second over the last frames
        self.held: set[int] = set()
        self.owed = 0.0  # wall-clock time not yet stepped (less than one step, or a frame's cap)
        self._wall = self._simulated = 0.0
        self.diagnostics: list = []  # the last load's findings (a failed load's located errors)
        self.text: str | None = None  # the editor's unsaved content of ``path`` (plx view --web), else the disk's
        self.waiting: str | None = None  # why the load started paused by itself (it would leave the view)

    # -- loading ----------------------------------------------------------------------------------

    def load(self) -> LoadResult:
        """(Re)load the model; on failure the current simulation stays and ``error`` says why."""
        from plxtools.check.api import ModelError, Simulation, prepare
        from plxtools.view.controller import ControllerError, run_controller
        from plxtools.view.keymap import KeymapError, bind_keymap, read_keymap

        t0 = time.perf_counter()
        watched = [self.path, *([self.controller] if self.controller else []),
                   *([self.keymap] if self.keymap else [])]
        before = {os.path.abspath(p): deps.stamp(p) for p in watched}  # a save during the load reloads again
        try:
            prepared = prepare(self.path, self.model, bundle_path=self.bundle_path,
                               openplx_version=self.openplx_version, text=self.text)
            sim = Simulation(prepared)
            watched += deps.files_read(prepared)
            KeyboardCallback.clear()
            if self.keymap:
                bind_keymap(read_keymap(self.keymap), sim)
            if self.controller:
                run_controller(self.controller, sim)
        except ModelError as exc:
            self.diagnostics = list(exc.diagnostics)
            return self._failed(str(exc), [_line(d) for d in exc.diagnostics], watched, before, t0)
        except (KeymapError, ControllerError) as exc:
            self.diagnostics = []
            return self._failed(str(exc).splitlines()[0], str(exc).splitlines()[1:], watched, before, t0)
        self._watch(watched + deps.config_candidates(self.path), before)
        self.sim = sim
        self.generation += 1
        self.error = None
        self.held.clear()
        self.diagnostics = list(sim.diagnostics)
        findings = [_line(d) for d in sim.diagnostics]
        msg = f"loaded {sim.model_name} from {self.path}" + (f" ({len(findings)} finding(s))" if findings else "")
        self.say(msg)
        for f in findings:
            self.say("  " + f)
        self._wait_if_leaving()
        return LoadResult(True, msg, findings, time.perf_counter() - t0)

    def _wait_if_leaving(self) -> None:
        """Start paused when the scene would leave the view at once (as the AGX viewer waits for E)."""
        from plxtools.view.forecast import leaves_view

        self.waiting = None
        if self.paused:
            return
        why = leaves_view(self.sim.model, self.sim.data)
        if why is not None:
            self.paused, self.waiting = True, why
            self.say(f"paused: {why} (E plays)")

    def _failed(self, message: str, details: list[str], watched: list[str], before: dict, t0: float) -> LoadResult:
        if self.sim is not None:  # keep watching what the good load read too
            watched += deps.files_read(self.sim.prepared)
        self._watch(watched + deps.config_candidates(self.path), before)
        self.error = message
        kept = "; still showing the last good scene" if self.sim is not None else ""
        self.say(f"cannot load: {message}{kept}")
        for d in details:
            self.say("  " + d)
        return LoadResult(False, message, details, time.perf_counter() - t0)

    def _watch(self, paths: list[str], before: dict[str, tuple[int, int] | None]) -> None:
        """Remember the files' stamps: those taken before the load where there is one."""
        self.stamps = {p: before[p] if p in before else deps.stamp(p)
                       for p in dict.fromkeys(os.path.abspath(p) for p in paths)}

    def changed(self) -> list[str]:
        """Watched files whose content may have changed since the last load."""
        return [p for p, st in self.stamps.items() if deps.stamp(p) != st]

    def note_changes(self, moved: list[str]) -> None:
        """Before reloading for ``moved`` files: say which, and let go of what they make stale."""
        self.say(f"changed: {', '.join(moved)}; reloading")
        if any(p != os.path.abspath(self.path) for p in moved):
            # a user bundle file (or a configuration) changed: the process's workspace holds the old one
            from plxtools.model.workspace import forget_cli_workspaces

            forget_cli_workspaces()

    def poll(self) -> LoadResult | None:
        """Reload when a watched file changed (None: nothing changed)."""
        moved = self.changed()
        if not moved:
            return None
        self.note_changes(moved)
        return self.load()

    # -- keys ------------------------------------------------------------------------------------

    def key(self, code: int, down: bool = True) -> str | None:
        """A key press or release; returns the view action it caused, if any."""
        if down:
            if code in self.held and code in KeyboardCallback.keys():
                return None  # a repeat of a held key
            self.held.add(code)
        else:
            self.held.discard(code)
        if KeyboardCallback.dispatch(code, down):
            return "bound"
        if not down:
            return None
        if code in RELOAD_KEYS:
            self.say("reload requested")
            self.load()
            return "reload"
        if code == PAUSE_KEY:
            self.paused, self.waiting = not self.paused, None
            return "pause" if self.paused else "play"
        if code == GEOMS_KEY:
            self.show_collision = not self.show_collision
            return "collision" if self.show_collision else "visuals"
        if code == RESET_KEY:
            self.reset()
            return "reset"
        return None

    def reset(self) -> None:
        """Back to the initial state of the current load (inputs as the model gives them)."""
        from plxtools.check.api import Simulation

        if self.sim is not None:
            self.sim = Simulation(self.sim.prepared)
            KeyboardCallback.clear()
            try:
                if self.keymap:
                    from plxtools.view.keymap import bind_keymap, read_keymap

                    bind_keymap(read_keymap(self.keymap), self.sim)
                if self.controller:
                    from plxtools.view.controller import run_controller

                    run_controller(self.controller, self.sim)
            except Exception as exc:  # noqa: BLE001 - shown, the view goes on
                self.say(f"cannot rebind keys after reset: {exc}")
            self.generation += 1

    # -- time ------------------------------------------------------------------------------------

    def advance(self, wall_seconds: float) -> int:
        """Step the simulation by ``wall_seconds`` of real time (none when paused); returns steps."""
        if self.sim is None or self.paused or wall_seconds <= 0:
            return 0
        # simulated time owed to the wall clock, stepped in whole steps (the rest is kept for the next frame)
        self.owed = min(self.owed + wall_seconds, MAX_FRAME_S)
        dt = self.sim.timestep
        n = int(self.owed / dt)
        before = self.sim.steps
        if n:
            self.sim.step(n * dt)
        self.owed -= (self.sim.steps - before) * dt
        # simulated seconds per wall second, over about a second: below 1 when the view cannot keep up
        self._wall += wall_seconds
        self._simulated += (self.sim.steps - before) * dt
        if self._wall >= 1.0:
            self.realtime = self._simulated / self._wall
            self._wall = self._simulated = 0.0
        return self.sim.steps - before

    # -- what the screen shows ------------------------------------------------------------------------

    def status(self, width: int = 64) -> list[str]:
        lines = []
        if self.error:
            lines += _error_lines(self.error, self.path, width - 2)
            if self.sim:
                lines.append("  (showing the last good scene)")
        if self.sim is None:
            return lines
        state = "paused (E plays)" if self.paused else "running"
        lines.append(f"{self.sim.model_name}  t={self.sim.time:.2f}s  {state}"
                     + ("" if self.realtime > 0.95 or self.paused else f"  slower than real time: x{self.realtime:.2f}"))
        if self.waiting and self.paused:
            lines.append(f"  waiting: {self.waiting}")
        for name, code in KeyboardCallback.bindings():
            from plxtools.view.keys import key_name

            lines.append(f"key {key_name(code)}: {name}")
        return lines

    def signals(self, width: int = 80) -> list[str]:
        """The scene's inputs and outputs with their current values, one per line of at most
        ``width`` characters (a long path loses its first parts)."""
        if self.sim is None:
            return []
        out = []
        for info in sorted(self.sim.prepared.signals, key=lambda i: i.direction != "input"):
            if info.path not in self.sim.runtime.bindings:
                continue
            b = self.sim.runtime.bindings[info.path]
            if info.direction == "input":
                # what was sent, not what the body does now: a motor's input read back as the joint's
                # velocity looked as if something were pushing it (issue 40.6)
                sent = getattr(self.sim, "sent", {}).get(info.path)
                if sent is not None:  # (an input nothing was sent to is left out)
                    value = _value_text(sent)
                    out.append(f"in  {_short_path(info.path, width - 8 - len(value))} <- {value}")
                continue
            if b.read is None:
                continue
            try:
                self.sim._fresh()
                v = b.read(self.sim.model, self.sim.data)
            except Exception:  # noqa: BLE001 - a value that cannot be read is left out
                continue
            value = _value_text(v)
            out.append(f"out {_short_path(info.path, width - 7 - len(value))} = {value}")
        return [line if len(line) <= width else line[: width - 3] + "..." for line in out]  # a long value


def _short_path(path: str, room: int) -> str:
    """A long dotted path in ``room`` characters: first without its leading parts (the root is the
    same for all), keeping at least the owner and the signal (`...front_left_drive_motor.target_speed_input`,
    left and right stay apart), then without the signal's `_input`/`_output` (the line's `in`/`out`
    says it), then cut at the front. ASCII only: MuJoCo's overlay font has no "…" (it drew a box)."""
    room = max(room, 12)
    if len(path) <= room:
        return path
    parts = path.split(".")
    for i in range(1, max(1, len(parts) - 1)):
        tail = "..." + ".".join(parts[i:])
        if len(tail) <= room:
            return tail
    last = parts[-1]
    for suffix in ("_input", "_output"):
        if last.endswith(suffix) and len(last) > len(suffix):
            last = last[: -len(suffix)]
            break
    tail = ".".join([*parts[-2:-1], last])
    return tail if len(tail) <= room else "..." + tail[-(room - 3):]


def _value_text(v: Any) -> str:
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return _num(float(v))
    if isinstance(v, (tuple, list)):
        return "(" + ", ".join(_num(float(x)) if isinstance(x, (int, float)) else str(x) for x in v) + ")"
    return str(v)


def _error_lines(error: str, path: str, width: int = 64) -> list[str]:
    """LOAD FAILED, where (file:line:col, once) and why, wrapped: MuJoCo's overlay cuts a long line at
    the window's edge."""
    import re
    import textwrap

    text = error
    for prefix in (f"{path}: ", f"{os.path.abspath(path)}: "):
        if text.startswith(prefix):
            text = text[len(prefix):]
    m = re.search(r"(\S+?):(\d+):(\d+): ", text)
    where = os.path.basename(path)
    if m is not None:
        where = f"{os.path.basename(m.group(1))}:{m.group(2)}:{m.group(3)}"
        text = text[:m.start()] + text[m.end():]
    return [f"LOAD FAILED at {where}:"] + ["  " + ln for ln in textwrap.wrap(text, width)]


def _num(x: float) -> str:
    return "0" if abs(x) < 5e-4 else f"{x:.3g}"


def _line(d: Any) -> str:
    sev = getattr(getattr(d, "severity", None), "name", "").lower()
    if getattr(d, "span", None) is not None and getattr(d, "file", None):
        return f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {sev} {d.code} {d.message}"
    return str(d)
