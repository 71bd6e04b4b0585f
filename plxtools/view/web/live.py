"""The preview's state: one ViewSession stepped in real time on a thread, its events for the pages.

Everything the pages see goes through :class:`LivePreview`: a load (from disk, or from the editor's
unsaved text) sends ``scene`` and ``status``; each frame while running sends ``poses``; the editor's
cursor and a page's selection are relayed as ``cursor`` and ``reveal``.  The stepping is
``ViewSession.advance``, so the poses are those of ``plx check --simulate``'s own stepper.
"""

from __future__ import annotations

import json
import os
import queue
import shlex
import subprocess
import threading
import time
from typing import Any, Callable

from plxtools.view.session import ViewSession
from plxtools.view.web import scene_data

FRAME_S = 1 / 30  # poses sent per second while running
POLL_S = 0.1  # watched files looked at (a save shows within this plus a load)
MAX_CLIENT_BACKLOG = 120  # events queued for a page that does not read them: then it is dropped


class LivePreview:
    def __init__(self, session: ViewSession, *, editor_command: str | None = None,
                 say: Callable[[str], None] = lambda line: None):
        self.session = session
        self.editor_command = editor_command
        self.say = say
        self.lock = threading.RLock()
        self.clients: list[queue.Queue] = []
        self.scene: dict | None = None
        self.status: dict = {"ok": False, "loading": True, "error": None, "findings": [], "generation": 0}
        self.ids: list[tuple[int, str]] = []
        self.pending_text: tuple[bool, str | None] | None = None  # (set, text) from the editor, not yet loaded
        self.pending_open: tuple[str, str | None] | None = None
        self.reload_requested = False
        self.loads = 0  # loads tried (good or bad): tests and bench wait on it
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    # -- events ---------------------------------------------------------------------------------

    def subscribe(self) -> queue.Queue:
        q: queue.Queue = queue.Queue()
        with self.lock:
            if self.scene is not None:
                q.put(("scene", self.scene))
            q.put(("status", self.status))
            if self.scene is not None:
                q.put(("poses", self._poses()))
            self.clients.append(q)
        return q

    def unsubscribe(self, q: queue.Queue) -> None:
        with self.lock:
            if q in self.clients:
                self.clients.remove(q)

    def broadcast(self, event: str, data: Any) -> None:
        with self.lock:
            for q in list(self.clients):
                if q.qsize() > MAX_CLIENT_BACKLOG:
                    self.clients.remove(q)
                    q.put(None)
                else:
                    q.put((event, data))

    # -- the loop -------------------------------------------------------------------------------

    def start(self) -> None:
        self.load()
        self._thread = threading.Thread(target=self._run, name="plx-preview", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5)
        with self.lock:
            for q in self.clients:
                q.put(None)
            self.clients.clear()

    def _run(self) -> None:
        last = time.perf_counter()
        next_poll = last + POLL_S
        while not self._stop.is_set():
            t0 = time.perf_counter()
            try:
                last, next_poll = self._frame(t0, last, next_poll)
            except Exception as exc:  # noqa: BLE001 - a step or a key callback failed: say so, pause, go on
                self.say(f"stopped the simulation: {type(exc).__name__}: {exc}")
                with self.lock:
                    self.session.paused = True
                    self.status = {**self.status, "error": f"the simulation stopped: {exc}"}
                    self.broadcast("status", self.status)
            spare = FRAME_S - (time.perf_counter() - t0)
            if spare > 0:
                self._stop.wait(spare)

    def _frame(self, t0: float, last: float, next_poll: float) -> tuple[float, float]:
        """One turn of the loop: a pending load, the file check, the steps owed to the wall clock."""
        with self.lock:
            if self.pending_open is not None:
                self._open(*self.pending_open)
            if self.pending_text is not None or self.reload_requested:
                if self.pending_text is not None:
                    self.session.text = self.pending_text[1]
                self.pending_text, self.reload_requested = None, False
                self.load()
            elif t0 >= next_poll:
                next_poll = t0 + POLL_S
                moved = self.session.changed()
                if moved:
                    self.session.note_changes(moved)
                    self.load()
            now = time.perf_counter()
            stepped = self.session.advance(now - last)
            last = now
            if stepped:
                self.broadcast("poses", self._poses())
        return last, next_poll

    # -- loading --------------------------------------------------------------------------------

    def load(self) -> None:
        """(Re)load now; a failure keeps the last good scene and sends the located findings."""
        with self.lock:
            self.status = {**self.status, "loading": True}
            result = self.session.load()
            self.loads += 1
            sim = self.session.sim
            if result.ok and sim is not None:
                self._publish_scene()
                findings = [scene_data.finding_json(d) for d in sim.diagnostics]
            else:
                findings = self._failed_findings(result)
            self.status = {"ok": result.ok, "loading": False, "error": None if result.ok else result.message,
                           "findings": findings, "generation": self.session.generation, "file": os.path.abspath(
                               self.session.path), "model": sim.model_name if sim is not None else None,
                           "editorText": self.session.text is not None, "loadSeconds": round(result.seconds, 4),
                           "keys": self._keys()}
            self.broadcast("status", self.status)
            if sim is not None:
                self.broadcast("poses", self._poses())

    def _publish_scene(self) -> None:
        """Send the current simulation's scene (after a load, and after a reset: a new generation)."""
        from plxtools.check.mujoco.video import show_visuals

        sim = self.session.sim
        show_visuals(sim.model)  # collision geometry under a visual: group 3, as in plx view
        self.ids = scene_data.body_ids(sim)
        self.scene = scene_data.scene_json(sim, self.session.generation)
        self.broadcast("scene", self.scene)

    def _failed_findings(self, result: Any) -> list[dict]:
        """The failed load's located findings; without any (a MuJoCo or key-table error), its message."""
        found = [scene_data.finding_json(d) for d in self.session.diagnostics]
        return found or [{"file": "", "line": 0, "column": 0, "severity": "error", "code": "", "message": m}
                         for m in [result.message, *result.details]]

    def _keys(self) -> list[list]:
        from plxtools.view.keys import KeyboardCallback, key_name

        return [[name, code, key_name(code)] for name, code in KeyboardCallback.bindings()]

    def _open(self, path: str, model: str | None) -> None:
        self.pending_open = None
        s = self.session
        self.session = ViewSession(path, model, bundle_path=s.bundle_path, openplx_version=s.openplx_version,
                                   paused=s.paused, say=s.say)
        self.scene = None
        self.load()

    # -- what pages and editors ask ------------------------------------------------------------------

    def _poses(self) -> dict:
        s = self.session
        q = scene_data.poses(s.sim, self.ids) if s.sim is not None else []
        return {"t": round(s.sim.time, 6) if s.sim else 0.0, "rtf": round(s.realtime, 3), "paused": s.paused,
                "generation": s.generation, "q": q}

    def control(self, action: str, **kw: Any) -> dict:
        """play, pause, toggle, step (``steps``), reset, seek (``time``: paused there), reload."""
        with self.lock:
            s = self.session
            if action == "reload":
                self.reload_requested = True
                return {"ok": True}
            if s.sim is None:
                return {"ok": False, "error": "no scene is loaded"}
            if action in ("play", "pause", "toggle"):
                s.paused = (not s.paused) if action == "toggle" else action == "pause"
                s.owed = 0.0
            elif action == "step":
                s.paused = True
                s.sim.step(max(1, int(kw.get("steps", 1))) * s.sim.timestep)
            elif action == "reset":
                s.reset()
                self._publish_scene()
            elif action == "seek":
                target = float(kw.get("time", 0.0))
                s.paused = True
                if target < s.sim.time - 1e-12:
                    s.reset()
                    self._publish_scene()
                n = int(round((target - s.sim.time) / s.sim.timestep))
                if n > 0:
                    s.sim.step(n * s.sim.timestep)
            else:
                return {"ok": False, "error": f"unknown action {action!r}"}
            poses = self._poses()
            self.broadcast("poses", poses)
            return {"ok": True, **poses}

    def set_text(self, path: str, text: str | None) -> bool:
        """The editor's content of the previewed file (None: use the disk again); loaded by the loop."""
        if os.path.abspath(path) != os.path.abspath(self.session.path):
            return False
        with self.lock:
            if text != self.session.text or self.pending_text is not None:
                self.pending_text = (True, text)
        return True

    def open(self, path: str, model: str | None = None) -> None:
        with self.lock:
            if os.path.abspath(path) == os.path.abspath(self.session.path) and model == self.session.model:
                return
            self.pending_open = (path, model)

    def key(self, code: int, down: bool) -> str | None:
        """A key of the page: the model's bound keys first, then the view's own (as in plx view)."""
        from plxtools.view.keys import KeyboardCallback
        from plxtools.view.session import PAUSE_KEY, RELOAD_KEYS, RESET_KEY

        with self.lock:
            if code not in KeyboardCallback.keys() and down:
                if code in RELOAD_KEYS:
                    return self.control("reload") and "reload"
                if code == RESET_KEY:
                    return self.control("reset") and "reset"
                if code == PAUSE_KEY:
                    return self.control("toggle") and ("pause" if self.session.paused else "play")
            return self.session.key(code, down)

    def cursor(self, file: str, line: int) -> None:
        self.broadcast("cursor", {"file": os.path.abspath(file), "line": int(line)})

    def select(self, info: dict) -> dict:
        """A page selected an element: tell the editors (the extension listens), run the command."""
        out = {"file": str(info.get("file", "")), "line": int(info.get("line", 0) or 0),
               "column": int(info.get("column", 1) or 1), "path": str(info.get("path", ""))}
        self.broadcast("reveal", out)
        if self.editor_command and out["file"] and out["line"] > 0:
            argv = [a.format(**out) for a in shlex.split(self.editor_command)]
            try:
                subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL, start_new_session=True)
                out["editor"] = argv[0]
            except OSError as exc:
                out["editorError"] = f"{argv[0]}: {exc.strerror or exc}"
                self.say(f"--editor-command failed: {out['editorError']}")
        return out

    def state(self) -> dict:
        with self.lock:
            return {"status": self.status, "poses": self._poses(), "loads": self.loads,
                    "scene": {k: self.scene[k] for k in ("model", "file", "generation")} if self.scene else None}


def sse(event: str, data: Any) -> bytes:
    return f"event: {event}\ndata: {json.dumps(data, separators=(',', ':'))}\n\n".encode()
