"""The wire: LSP frames over stdio, read on a thread, dispatched on the server's event loop.

Owned here rather than left to pygls because every request must get an answer and a bad frame
must never leave the server deaf:

- a frame whose `Content-Length` is shorter than its body is dropped and reading resynchronises on
  the next `Content-Length` header, even one glued to the tail of the previous body;
- a request with params that do not fit its method is answered with -32602 (InvalidParams), one
  before `initialize` with -32002 (ServerNotInitialized), one after `shutdown` with -32600;
- `$/cancelRequest` is seen by the reader as soon as it arrives, so a request still queued behind
  a long one is answered with -32800 (RequestCancelled) without being computed, and one running
  has its result replaced by -32800; cancels for ids already answered are routine (debug log);
- the editor closing the pipe ends the server quietly.
"""

from __future__ import annotations

import json
import logging
import re
import threading
from collections import OrderedDict

log = logging.getLogger("plxtools.lsp")

PARSE_ERROR = -32700
INVALID_REQUEST = -32600
METHOD_NOT_FOUND = -32601
INVALID_PARAMS = -32602
SERVER_NOT_INITIALIZED = -32002
REQUEST_CANCELLED = -32800

MAX_BODY = 1 << 30  # a bigger Content-Length is a broken header, not a message
_CONTENT_LENGTH = re.compile(rb"Content-Length:[ \t]*(\d+)[ \t]*\r?\n?$", re.IGNORECASE)


class FrameReader:
    """Reads message bodies from a binary stream, skipping whatever is not a well-formed frame."""

    def __init__(self, stream):
        self.stream = stream

    def next_body(self) -> bytes | None:
        """The next body, or None at the end of the stream."""
        length: int | None = None
        while True:
            line = self.stream.readline()
            if not line:
                return None
            m = _CONTENT_LENGTH.search(line)
            if m is not None:
                if m.start() > 0:
                    log.warning("discarded %d bytes before a Content-Length header (bad frame)", m.start())
                n = int(m.group(1))
                length = n if n <= MAX_BODY else None
                continue
            if line.strip() == b"" and length is not None:
                body = self.stream.read(length)
                if len(body) < length:
                    return None
                return body
            if length is None and line.strip():
                log.warning("discarded %d bytes outside any frame", len(line))


class Writer:
    """Writes frames to a binary stream; a closed pipe (the editor quit) is not an error."""

    def __init__(self, stream):
        self.stream = stream
        self.closed = False
        self.lock = threading.Lock()

    def write(self, data: bytes) -> None:
        if self.closed:
            return
        with self.lock:
            try:
                self.stream.write(data)
                self.stream.flush()
            except (BrokenPipeError, ConnectionResetError, ValueError, OSError) as exc:
                self.closed = True
                log.info("the client closed the connection (%s)", type(exc).__name__)

    def close(self) -> None:
        self.closed = True
        try:
            self.stream.close()
        except OSError:
            pass


class Cancelled:
    """Ids of requests the client cancelled (bounded: routine cancels of answered ids age out)."""

    def __init__(self, limit: int = 4096):
        self._ids: OrderedDict = OrderedDict()
        self._lock = threading.Lock()
        self.limit = limit

    def add(self, msg_id) -> None:
        with self._lock:
            self._ids[_key(msg_id)] = True
            while len(self._ids) > self.limit:
                self._ids.popitem(last=False)

    def take(self, msg_id) -> bool:
        with self._lock:
            return self._ids.pop(_key(msg_id), None) is not None

    def __contains__(self, msg_id) -> bool:
        with self._lock:
            return _key(msg_id) in self._ids


def _key(msg_id):
    return (type(msg_id).__name__, msg_id) if isinstance(msg_id, (int, str)) else ("?", repr(msg_id))


def _valid_id(msg_id) -> bool:
    return isinstance(msg_id, str) or (isinstance(msg_id, int) and not isinstance(msg_id, bool))


PROMPT = frozenset({"textDocument/completion"})  # answered before a queued check runs, even when async


class Dispatcher:
    """Validates each decoded message and hands it to the pygls protocol, or answers it itself."""

    def __init__(self, server):
        self.server = server
        self.protocol = server.protocol
        self.cancelled = Cancelled()
        self.initialized = False
        self.inbox = 0  # messages read but not yet dispatched (the analysis scheduler yields to them)
        self.prompt = 0  # PROMPT requests dispatched and not answered yet (the scheduler yields to them too)
        self._inbox_lock = threading.Lock()

    # ------------------------------------------------------------------ answering

    def reply_error(self, msg_id, code: int, message: str) -> None:
        from lsprotocol.types import ResponseErrorMessage  # noqa: F401 - keeps lsprotocol's shape

        body = json.dumps({"jsonrpc": "2.0", "id": msg_id, "error": {"code": code, "message": message}})
        self.protocol._send_raw(body)

    # ------------------------------------------------------------------ reading side (reader thread)

    def received(self, raw) -> None:
        """Called on the reader thread for every decoded body, before it is queued."""
        if isinstance(raw, dict) and raw.get("method") == "$/cancelRequest":
            params = raw.get("params")
            if isinstance(params, dict) and _valid_id(params.get("id")):
                self.cancelled.add(params["id"])
        with self._inbox_lock:
            self.inbox += 1

    # ------------------------------------------------------------------ dispatching (event loop)

    def dispatch(self, raw) -> None:
        with self._inbox_lock:
            self.inbox -= 1
        try:
            self._dispatch(raw)
        finally:
            self._forget_finished()

    def _prompt_done(self, _fut) -> None:
        self.prompt -= 1

    def _forget_finished(self) -> None:
        """Drop the finished futures pygls keeps per message. A request's is removed when its reply
        is sent, but a notification's (pygls runs didOpen/didChange/didClose through a generator, under
        a fresh uuid) never is: one Future per keystroke, for as long as the server runs (issue 40.3)."""
        futures = getattr(self.protocol, "_request_futures", None)
        if futures:
            for key in [k for k, f in futures.items() if f.done()]:
                futures.pop(key, None)

    def _dispatch(self, raw) -> None:
        if not isinstance(raw, dict) or raw.get("jsonrpc") != "2.0":
            if isinstance(raw, dict) and "method" in raw and _valid_id(raw.get("id")):
                self.reply_error(raw["id"], INVALID_REQUEST, "not a JSON-RPC 2.0 message")
            else:
                log.warning("ignored a message that is not JSON-RPC 2.0")
            return
        method = raw.get("method")
        if method is None:
            self._response(raw)
        elif "id" in raw:
            self._request(raw, method)
        else:
            self._notification(raw, method)

    def _request(self, raw: dict, method) -> None:
        msg_id = raw["id"]
        if not _valid_id(msg_id) or not isinstance(method, str):
            self.reply_error(msg_id if _valid_id(msg_id) else None, INVALID_REQUEST, "invalid request")
            return
        if self.cancelled.take(msg_id):
            self.reply_error(msg_id, REQUEST_CANCELLED, f"request {msg_id!r} was cancelled")
            return
        if not self.initialized and method != "initialize":
            self.reply_error(msg_id, SERVER_NOT_INITIALIZED, f"{method}: the server is not initialized yet")
            return
        if self.initialized and method == "initialize":
            self.reply_error(msg_id, INVALID_REQUEST, "initialize: the server is already initialized")
            return
        if self.protocol._shutdown:
            self.reply_error(msg_id, INVALID_REQUEST, f"{method}: the server is shutting down")
            return
        typ = self.protocol.get_message_type(method)
        if typ is None and method not in self.protocol.fm.features:
            self.reply_error(msg_id, METHOD_NOT_FOUND, f"unknown method {method!r}")
            return
        try:
            from pygls.protocol.json_rpc import JsonRPCRequestMessage

            message = self.protocol._converter.structure(raw, typ or JsonRPCRequestMessage)
        except Exception as exc:  # noqa: BLE001 - cattrs raises a family of errors
            log.info("invalid params for %s (id %r): %s", method, msg_id, _short(exc))
            self.reply_error(msg_id, INVALID_PARAMS, f"invalid params for {method}: {_short(exc)}")
            return
        if method == "initialize":
            self.initialized = True
        self.protocol.handle_message(message)
        if method in PROMPT:
            fut = self.protocol._request_futures.get(msg_id)
            if fut is not None and not fut.done():
                # a coroutine handler starts on the next turn of the loop: a queued check must not
                # run first (the scheduler waits while `prompt` > 0); pygls' reply callback was added
                # before this one, so the count drops once the reply is sent
                self.prompt += 1
                fut.add_done_callback(self._prompt_done)

    def _notification(self, raw: dict, method) -> None:
        if method == "$/cancelRequest":
            params = raw.get("params")
            msg_id = params.get("id") if isinstance(params, dict) else None
            fut = self.protocol._request_futures.get(msg_id) if _valid_id(msg_id) else None
            if fut is not None and not fut.done():
                fut.cancel()  # a coroutine handler: cancelled at its next await
            log.debug("cancel for request %r", msg_id)
            return
        if not isinstance(method, str):
            log.warning("ignored a notification without a method name")
            return
        if not self.initialized and method != "exit":
            log.info("ignored %s before initialize", method)
            return
        typ = self.protocol.get_message_type(method)
        if typ is None and method not in self.protocol.fm.features and method not in self.protocol.fm.builtin_features:
            level = logging.DEBUG if method.startswith("$/") else logging.INFO
            log.log(level, "ignored notification %s (not supported)", method)
            return
        try:
            from pygls.protocol.json_rpc import JsonRPCNotification

            message = self.protocol._converter.structure(raw, typ or JsonRPCNotification)
        except Exception as exc:  # noqa: BLE001
            log.warning("ignored %s with invalid params: %s", method, _short(exc))
            return
        self.protocol.handle_message(message)

    def _response(self, raw: dict) -> None:
        try:
            message = self.protocol.structure_message(raw)
        except Exception as exc:  # noqa: BLE001
            log.warning("ignored a malformed response: %s", _short(exc))
            return
        self.protocol.handle_message(message)


def _short(exc: Exception) -> str:
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    subs = getattr(exc, "exceptions", None)
    if subs:
        text += ": " + "; ".join(_short(e) for e in subs[:3])
    return text[:300]


def serve(server, stdin, stdout, first=None, next_body=None, writer: Writer | None = None) -> int:
    """Run the server until `exit` or the end of input; returns the exit code. `first` is a body, or
    a list of bodies, read before the server existed (quickstart.py, early.py): handled before
    anything else is read; `next_body` replaces reading `stdin` (early.py's queue of frames)."""
    import asyncio  # here, not at the top: quickstart.py reads the first frame before this is needed

    writer = writer or Writer(stdout)
    server.protocol.set_writer(writer)
    server.writer = writer
    dispatcher = server.dispatcher
    next_body = next_body or FrameReader(stdin).next_body
    pending_bodies = list(first) if isinstance(first, list) else [first] if first is not None else []

    async def main() -> None:
        loop = asyncio.get_running_loop()
        server.loop = loop
        done = loop.create_future()

        def read_all() -> None:
            try:
                while True:
                    body = pending_bodies.pop(0) if pending_bodies else next_body()
                    if body is None:
                        break
                    try:
                        raw = json.loads(body)
                    except (ValueError, UnicodeDecodeError):
                        log.warning("ignored a frame that is not JSON (%d bytes)", len(body))
                        continue
                    dispatcher.received(raw)
                    loop.call_soon_threadsafe(_dispatch_safely, dispatcher, raw)
            except (OSError, ValueError) as exc:
                log.info("input closed: %s", exc)
            finally:
                loop.call_soon_threadsafe(lambda: done.done() or done.set_result(None))

        threading.Thread(target=read_all, name="plx-lsp-reader", daemon=True).start()
        await done

    try:
        asyncio.run(main())
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else 0
    except KeyboardInterrupt:
        return 0
    # the input ended without `exit`: 0 after `shutdown`, 1 otherwise (as for `exit`)
    return 0 if server.protocol._shutdown else 1


def _dispatch_safely(dispatcher: Dispatcher, raw) -> None:
    try:
        dispatcher.dispatch(raw)
    except (SystemExit, KeyboardInterrupt):
        raise
    except Exception:  # noqa: BLE001 - one message must never stop the server
        log.exception("failed to handle a message")
        msg_id = raw.get("id") if isinstance(raw, dict) else None
        if isinstance(raw, dict) and "method" in raw and _valid_id(msg_id):
            dispatcher.reply_error(msg_id, -32603, "internal error (see the server log)")
