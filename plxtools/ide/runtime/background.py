"""Large loose documents checked in a forked process, so the server keeps answering meanwhile.

The child inherits the server's model (copy-on-write), runs the check the server gives it, writes
its result as JSON to a pipe and leaves without any cleanup. A newer version of the document, or
closing it, kills the child; a child that fails (a short read, bad JSON) is reported to the server,
which then checks in its own process. The child's analysis dies with it, so the server makes its own
once the child answered; from then on an edit is checked in the server, re-using that analysis for
what the edit did not touch (model/reuse.py, rules/incremental.py). A bundle file's symbols are seen by other files, so only
loose documents (in no bundle) are checked apart.
"""

from __future__ import annotations

import asyncio
import gc
import json
import logging
import os
from typing import Callable

from plxtools.ide.runtime.stats import Stats

log = logging.getLogger("plxtools.lsp")  # the language server's log, where these run

BACKGROUND_SIZE = 200_000  # characters: a loose document this large is checked in a forked process


def checked_apart(host, path: str, text: str, min_size: int, loop) -> bool:
    """Whether this document's check runs in a forked process."""
    if not hasattr(os, "fork") or len(text) < min_size or loop is None:
        return False
    ws = host._ws
    if ws is None or host.reusable(path, text):
        return False  # the server holds an analysis of it: re-using it is quicker than a fork's fresh check
    unit = ws.program.units.get(path)
    return unit is None or unit.bundle is None


class BackgroundCheck:
    """A forked process checking one version of a large document."""

    __slots__ = ("uri", "version", "text", "pid", "fd", "chunks", "waiters", "fallback")

    def __init__(self, uri: str, version, text: str, pid: int, fd: int):
        self.uri, self.version, self.text, self.pid, self.fd = uri, version, text, pid, fd
        self.chunks: list[bytes] = []
        self.waiters: list[asyncio.Future] = []
        self.fallback = False

    async def wait(self):
        fut = asyncio.get_running_loop().create_future()
        self.waiters.append(fut)
        return await fut

    def settle(self, result) -> None:
        for fut in self.waiters:
            if not fut.done():
                fut.set_result(result)
        self.waiters = []


class BackgroundChecks:
    """The forked checks running, one per document (by URI).

    `decode` turns the child's `diagnostics` back into the server's objects; `on_done(bg, diags)`
    receives them; `on_failed(bg)` is called when the child failed (the server checks in-process)."""

    def __init__(self, stats: Stats, decode: Callable, on_done: Callable, on_failed: Callable) -> None:
        self.running: dict[str, BackgroundCheck] = {}
        self.stats = stats
        self.decode, self.on_done, self.on_failed = decode, on_done, on_failed
        self.loop: asyncio.AbstractEventLoop | None = None

    def get(self, uri: str) -> BackgroundCheck | None:
        return self.running.get(uri)

    def start(self, uri: str, version, text: str, loop, check: Callable[[], dict]) -> BackgroundCheck:
        """Fork a child that runs `check()` (a JSON-able dict: `diagnostics`, `timing`)."""
        self.cancel(uri)
        self.loop = loop
        r, w = os.pipe()
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)  # fork with the reader thread alive
            pid = os.fork()
        if pid == 0:  # the child: check, write the diagnostics, exit without any cleanup
            status = 0
            try:
                os.close(r)
                gc.disable()
                view = memoryview(json.dumps(check()).encode("utf-8"))
                while view:
                    view = view[os.write(w, view):]
            except BaseException:  # noqa: BLE001 - the parent sees a short read and checks in-process
                status = 1
            finally:
                os._exit(status)
        os.close(w)
        os.set_blocking(r, False)
        bg = BackgroundCheck(uri, version, text, pid, r)
        self.running[uri] = bg
        self.stats.count("background-started")
        loop.add_reader(r, self._readable, bg)
        return bg

    def cancel(self, uri: str) -> None:
        bg = self.running.pop(uri, None)
        if bg is None:
            return
        self._end_child(bg, kill=True)
        self.stats.count("background-cancelled")
        bg.settle(None)

    def _end_child(self, bg: BackgroundCheck, kill: bool) -> None:
        import signal

        try:
            self.loop.remove_reader(bg.fd)
        except Exception:  # noqa: BLE001 - the loop may be closing
            pass
        try:
            os.close(bg.fd)
        except OSError:
            pass
        if kill:
            try:
                os.kill(bg.pid, signal.SIGKILL)
            except OSError:
                pass
        try:
            os.waitpid(bg.pid, 0)
        except ChildProcessError:
            pass

    def _read_all(self, bg: BackgroundCheck) -> bool:
        """Read what the child wrote so far; True once it closed the pipe."""
        while True:
            try:
                chunk = os.read(bg.fd, 1 << 20)
            except BlockingIOError:
                return False
            except OSError:
                chunk = b""
            if not chunk:
                return True
            bg.chunks.append(chunk)

    def _readable(self, bg: BackgroundCheck) -> None:
        if not self._read_all(bg):
            return
        if self.running.get(bg.uri) is bg:
            del self.running[bg.uri]
        self._end_child(bg, kill=False)
        try:
            got = json.loads(b"".join(bg.chunks))
            diags = self.decode(got["diagnostics"])
        except Exception:  # noqa: BLE001 - the child failed: check in the server itself
            log.warning("the background check of %s failed; checking it here", bg.uri)
            bg.settle(None)
            self.on_failed(bg)
            return
        bg.chunks = []
        self.stats.count("background-finished")
        timing = got.get("timing") or [0, 0]
        self.stats.add("check-background", float(timing[0]), float(timing[1]))
        self.on_done(bg, diags)
