"""The preview's HTTP server: the page and its scripts, the scene, a Server-Sent Events stream.

Standard library only (``http.server``), bound to 127.0.0.1.  The page, its script and style are
public; everything that tells about the model or changes it (``scene``, ``events``, ``api/...``)
needs the server's token, which is in the URL printed at start and nowhere in what the server
sends, so another web site (or one that rebinds its name to 127.0.0.1) cannot read the model or
drive the preview.  Every URL the page uses is relative, so the page also works behind a path
prefix (VS Code's port forwarding in code-server: ``/proxy/PORT/``).
"""

from __future__ import annotations

import hmac
import json
import queue
import secrets
import threading
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any
from urllib.parse import parse_qs, urlsplit

from plxtools.view.web.live import LivePreview, sse

STATIC = {"": ("index.html", "text/html; charset=utf-8"), "index.html": ("index.html", "text/html; charset=utf-8"),
          "preview.js": ("preview.js", "text/javascript; charset=utf-8"),
          "render.js": ("render.js", "text/javascript; charset=utf-8"),
          "preview.css": ("preview.css", "text/css; charset=utf-8")}
KEEPALIVE_S = 15.0
MAX_BODY = 16 * 1024 * 1024  # an editor's text


def static_file(name: str) -> bytes:
    return resources.files("plxtools.view.web").joinpath("static", name).read_bytes()


class PreviewServer(ThreadingHTTPServer):
    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, live: LivePreview, port: int = 0, host: str = "127.0.0.1"):
        self.live = live
        self.token = secrets.token_urlsafe(18)
        super().__init__((host, port), _Handler)

    @property
    def url(self) -> str:
        host, port = self.server_address[:2]
        return f"http://{host}:{port}/?t={self.token}"

    def serve_in_thread(self) -> threading.Thread:
        t = threading.Thread(target=self.serve_forever, kwargs={"poll_interval": 0.2}, name="plx-preview-http",
                             daemon=True)
        t.start()
        return t


class _Handler(BaseHTTPRequestHandler):
    server: PreviewServer
    protocol_version = "HTTP/1.1"

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 - the base class's name
        """Quiet: the terminal shows plx's own lines."""

    # -- helpers -----------------------------------------------------------------------------------

    def _send(self, status: int, body: bytes, ctype: str = "application/json", extra: dict | None = None) -> None:
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        for k, v in (extra or {}).items():
            self.send_header(k, v)
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(body)

    def _json(self, data: Any, status: int = 200) -> None:
        self._send(status, json.dumps(data, separators=(",", ":")).encode())

    def _authorised(self, query: dict) -> bool:
        given = self.headers.get("X-Plx-Token") or (query.get("t") or [""])[0]
        return hmac.compare_digest(given.encode(), self.server.token.encode())

    def _body(self) -> dict | None:
        try:
            n = int(self.headers.get("Content-Length") or 0)
        except ValueError:
            n = -1
        if n < 0 or n > MAX_BODY:
            self._json({"error": "bad Content-Length"}, HTTPStatus.REQUEST_ENTITY_TOO_LARGE)
            return None
        try:
            data = json.loads(self.rfile.read(n) or b"{}")
        except (ValueError, UnicodeDecodeError):
            self._json({"error": "the body is not JSON"}, HTTPStatus.BAD_REQUEST)
            return None
        if not isinstance(data, dict):
            self._json({"error": "the body must be a JSON object"}, HTTPStatus.BAD_REQUEST)
            return None
        return data

    # -- GET ---------------------------------------------------------------------------------------

    def do_HEAD(self) -> None:  # noqa: N802
        self.do_GET()

    def do_GET(self) -> None:  # noqa: N802
        url = urlsplit(self.path)
        name = url.path.lstrip("/")
        query = parse_qs(url.query)
        if name in STATIC:
            file, ctype = STATIC[name]
            self._send(200, static_file(file), ctype,
                       {"Content-Security-Policy": "default-src 'self'; style-src 'self'; script-src 'self'; "
                                                   "connect-src 'self'; img-src 'self' data:; frame-ancestors *"})
            return
        if name == "favicon.ico":
            self._send(HTTPStatus.NO_CONTENT, b"", "image/x-icon")
            return
        if name not in ("scene", "events", "api/state"):
            self._json({"error": f"no such page: /{name}"}, HTTPStatus.NOT_FOUND)
            return
        if not self._authorised(query):
            self._json({"error": "this URL needs the preview's token (the ?t=... printed by plx view --web)"},
                       HTTPStatus.FORBIDDEN)
            return
        live = self.server.live
        if name == "scene":
            self._json(live.scene)
        elif name == "api/state":
            self._json(live.state())
        else:
            self._events()

    def _events(self) -> None:
        live = self.server.live
        q = live.subscribe()
        self.send_response(200)
        self.send_header("Content-Type", "text/event-stream")
        # no-transform: a proxy on the way (code-server's /proxy/PORT/) must not compress, and so hold back, the stream
        self.send_header("Cache-Control", "no-store, no-transform")
        self.send_header("X-Accel-Buffering", "no")
        self.send_header("Connection", "close")
        self.end_headers()
        self.close_connection = True
        try:
            self.wfile.write(b"retry: 500\n\n")
            self.wfile.flush()
            while True:
                try:
                    item = q.get(timeout=KEEPALIVE_S)
                except queue.Empty:
                    self.wfile.write(b": keep-alive\n\n")
                    self.wfile.flush()
                    continue
                if item is None:
                    return
                chunk = sse(*item)
                while True:  # send what has piled up in one write (a slow page gets the latest poses)
                    try:
                        more = q.get_nowait()
                    except queue.Empty:
                        break
                    if more is None:
                        self.wfile.write(chunk)
                        return
                    chunk += sse(*more)
                self.wfile.write(chunk)
                self.wfile.flush()
        except (BrokenPipeError, ConnectionResetError, OSError):
            pass
        finally:
            live.unsubscribe(q)

    # -- POST --------------------------------------------------------------------------------------

    def do_POST(self) -> None:  # noqa: N802
        url = urlsplit(self.path)
        name = url.path.lstrip("/")
        if not self._authorised(parse_qs(url.query)):
            self._json({"error": "this URL needs the preview's token"}, HTTPStatus.FORBIDDEN)
            return
        data = self._body()
        if data is None:
            return
        live = self.server.live
        try:
            if name == "api/control":
                kw = {k: v for k, v in data.items() if k in ("steps", "time")}
                self._json(live.control(str(data.get("action", "")), **kw))
            elif name == "api/text":
                text = data.get("text")
                ok = live.set_text(str(data.get("file", "")), text if isinstance(text, str) else None)
                self._json({"ok": ok} if ok else {"ok": False, "error": "not the previewed file"})
            elif name == "api/cursor":
                live.cursor(str(data.get("file", "")), int(data.get("line", 0)))
                self._json({"ok": True})
            elif name == "api/select":
                self._json(live.select(data))
            elif name == "api/key":
                self._json({"ok": True, "action": live.key(int(data["code"]), bool(data.get("down", True)))})
            elif name == "api/open":
                live.open(str(data["file"]), data.get("model") or None)
                self._json({"ok": True})
            else:
                self._json({"error": f"no such action: /{name}"}, HTTPStatus.NOT_FOUND)
        except (KeyError, TypeError, ValueError) as exc:
            self._json({"error": f"bad request: {exc}"}, HTTPStatus.BAD_REQUEST)
