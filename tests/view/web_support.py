"""Helpers of the `plx view --web` tests: start the real command, read its URL, drive Chromium.

The browser is Debian's chromium, driven by playwright-core from npm (tests/view/browser/, the
same package and version the VS Code end-to-end test uses); ``npm ci`` there installs it.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

BROWSER_DIR = Path(__file__).resolve().parent / "browser"
CHROMIUM = os.environ.get("PLX_CHROMIUM", "/usr/bin/chromium")
URL = re.compile(r"(http://127\.0\.0\.1:\d+/\?t=[A-Za-z0-9_\-]+)")


class PlxWeb:
    """``plx view --web FILE --no-open`` in a process of its own; ``url`` once it printed it."""

    def __init__(self, path: str | Path, *extra: str, cwd: str | Path | None = None, env: dict | None = None):
        self.started = time.perf_counter()
        self.proc = subprocess.Popen([sys.executable, "-m", "plxtools", "view", "--web", str(path), "--no-open", *extra],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd,
                                     env={**os.environ, **(env or {})})
        line = self.proc.stdout.readline()
        m = URL.search(line)
        if not m:
            self.stop()
            raise AssertionError(f"plx view --web printed no URL: {line!r} {self.proc.stderr.read()!r}")
        self.url = m.group(1)
        self.base, self.token = self.url.split("/?t=")

    def get(self, name: str) -> dict:
        req = urllib.request.Request(f"{self.base}/{name}", headers={"X-Plx-Token": self.token})
        with urllib.request.urlopen(req, timeout=10) as r:
            return json.loads(r.read())

    def post(self, name: str, body: dict) -> dict:
        req = urllib.request.Request(f"{self.base}/{name}", data=json.dumps(body).encode(), method="POST",
                                     headers={"X-Plx-Token": self.token, "Content-Type": "application/json"})
        with urllib.request.urlopen(req, timeout=10) as r:
            return json.loads(r.read())

    def wait_loaded(self, loads: int = 1, timeout: float = 30.0) -> dict:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            st = self.get("api/state")
            if st["loads"] >= loads and not st["status"].get("loading"):
                return st
            time.sleep(0.05)
        raise AssertionError(f"no load {loads} within {timeout} s")

    def stop(self) -> str:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        return self.proc.stderr.read() if self.proc.stderr else ""


def browser_missing() -> str | None:
    """Why the browser tests cannot run here, or None."""
    if not os.path.exists(CHROMIUM):
        return f"no chromium at {CHROMIUM} (Debian: apt-get install chromium)"
    if shutil.which("node") is None:
        return "no node"
    if not (BROWSER_DIR / "node_modules" / "playwright-core").is_dir():
        return f"playwright-core is not installed (cd {BROWSER_DIR} && npm ci)"
    return None


class Browser:
    """Headless Chromium through tests/view/browser/driver.mjs (one JSON line per command)."""

    def __init__(self) -> None:
        self.proc = subprocess.Popen(["node", str(BROWSER_DIR / "driver.mjs")], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True, cwd=BROWSER_DIR,
                                     env={**os.environ, "CHROMIUM": CHROMIUM})
        self.n = 0
        ready = json.loads(self.proc.stdout.readline())
        assert ready["result"] == "ready", ready

    def call(self, op: str, **kw):
        self.n += 1
        self.proc.stdin.write(json.dumps({"id": self.n, "op": op, **kw}) + "\n")
        self.proc.stdin.flush()
        reply = json.loads(self.proc.stdout.readline())
        if not reply["ok"]:
            raise AssertionError(f"browser {op}: {reply['error']} (page log: {reply.get('logs')})")
        return reply["result"]

    def goto(self, url: str, width: int = 800, height: int = 600) -> None:
        self.call("goto", url=url, width=width, height=height)

    def eval(self, expr: str):
        return self.call("evaluate", expr=expr)

    def wait_for(self, expr: str, timeout: float = 10.0):
        return self.call("waitFor", expr=expr, timeout=int(timeout * 1000))

    def screenshot(self, path: str | Path) -> Path:
        self.call("screenshot", path=str(path))
        return Path(path)

    def close(self) -> None:
        try:
            self.call("close")
        except Exception:  # noqa: BLE001 - the process is ended below anyway
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()


def png_pixels(path: str | Path):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB/RGBA PNG, read with zlib only."""
    import struct
    import zlib

    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    w = h = 0
    ctype = 2
    while pos < len(data):
        n = struct.unpack(">I", data[pos:pos + 4])[0]
        tag = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + n]
        if tag == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), (depth, ctype)
        elif tag == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows
