"""`plx lsp`: the OpenPLX language server (pygls glue only).

Every feature is a call into `plxtools.ide` (offsets in, data out); this module converts positions
(`convert.Positions`, the one place that knows the client's encoding), shapes LSP objects to the
client's capabilities, schedules checks without a fixed delay and keeps errors inside the request that
caused them. The wire (framing, validation, cancellation) is `transport.py`; the text model is
`convert.py` plus `documents.py`.
"""

from __future__ import annotations

import asyncio
import gc
import json
import logging
import os
import sys
import time

from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol
from pygls.protocol.language_server import lsp_method
from pygls.uris import from_fs_path, to_fs_path

from plxtools import __version__, ide
from plxtools.diagnostics import Diagnostic, Severity
from plxtools.ide.host import AnalysisHost, Settings
from plxtools.lsp.convert import Positions
from plxtools.lsp.documents import Documents
from plxtools.lsp import watching

log = logging.getLogger("plxtools.lsp")

CONFIG_SECTION = "openplx"
CONFIG_FILES = ("plx.toml", "pyproject.toml", "config.openplx")  # a change may choose another bundle set


class RequestFailed(JsonRpcException):
    """LSP's RequestFailed (-32803): the request was valid but cannot be answered."""

    CODE = -32803


class ServerCancelled(JsonRpcException):
    """LSP's ServerCancelled (-32802): the server dropped the request (a newer version arrived)."""

    CODE = -32802


MAX_DOCUMENT_SIZE = 1_000_000  # characters: above it a document is not analysed (maxDocumentSize)
BACKGROUND_SIZE = 200_000  # characters: a loose document this large is checked in a forked process


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


def memory_report() -> dict:
    from plxtools.syntax import ast

    gc.unfreeze()  # frozen objects are invisible to gc.get_objects(); freezing again is constant time
    try:
        trees = [{"path": o.path, "chars": len(o.text)} for o in gc.get_objects() if type(o) is ast.File]
    finally:
        gc.freeze()
    rss = 0
    try:
        with open(f"/proc/{os.getpid()}/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    rss = int(line.split()[1])
    except OSError:
        pass
    import tracemalloc

    traced = tracemalloc.get_traced_memory()[0] // 1024 if tracemalloc.is_tracing() else None
    return {"trees": trees, "rss_kb": rss, "python_kb": traced, "frozen": gc.get_freeze_count()}


# ------------------------------------------------------------------ protocol: tolerate odd clients


class PlxProtocol(LanguageServerProtocol):
    """pygls' protocol with the server's own text model (`Documents`), quiet writes and cancellation
    of requests that were running when the client cancelled them."""

    init_replay = None  # quickstart.InitReplay: the first initialize, maybe answered from the cache

    def _send_raw(self, body: str) -> None:
        if self.writer is None:
            return
        replay = self.init_replay
        if replay is not None and '"id"' in body:
            drop = replay.filter(body)
            if not isinstance(replay.msg_id, (int, str)):
                self.init_replay = None  # the initialize reply went by: no more filtering
            if drop:
                return
        data = body.encode("utf-8")
        self.writer.write(b"Content-Length: %d\r\n\r\n" % len(data) + data)

    def _send_data(self, data) -> None:
        if not data:
            return
        import json

        try:
            body = json.dumps(data, default=self._serialize_message)
        except Exception:  # noqa: BLE001 - an unserialisable result is a bug in a handler
            log.exception("could not serialise a message")
            msg_id = data.get("id") if isinstance(data, dict) else getattr(data, "id", None)
            if msg_id is not None:
                self._send_raw(json.dumps({"jsonrpc": "2.0", "id": msg_id,
                                           "error": {"code": -32603, "message": "internal error"}}))
            return
        self._send_raw(body)

    def _send_handler_result(self, future, *, msg_id):
        dispatcher = getattr(self._server, "dispatcher", None)
        if dispatcher is not None and dispatcher.cancelled.take(msg_id):
            self._request_futures.pop(msg_id, None)
            if not future.cancelled() and future.exception() is not None:
                log.debug("request %r failed after it was cancelled: %s", msg_id, future.exception())
            dispatcher.reply_error(msg_id, -32800, f"request {msg_id!r} was cancelled")
            return
        if not future.cancelled() and isinstance(future.exception(), JsonRpcException):
            # an expected refusal (RequestFailed, InvalidParams): the reply says it, no traceback
            exc = future.exception()
            self._request_futures.pop(msg_id, None)
            log.info("request %r refused: %s", msg_id, exc)
            self._send_response(msg_id, error=exc.to_response_error())
            return
        super()._send_handler_result(future, msg_id=msg_id)

    @lsp_method(types.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(self, params: types.DidOpenTextDocumentParams):
        td = params.text_document
        self._server.documents.open(td.uri, td.text, td.version)
        if (handler := self.fm.features.get(types.TEXT_DOCUMENT_DID_OPEN)) is not None:
            yield handler, (params,), None

    @lsp_method(types.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(self, params: types.DidChangeTextDocumentParams):
        """Edits are applied by `convert.apply_change` (LSP's line breaks, clamping). An edit to a
        document that was never opened is ignored (or, if it carries the whole text, treated as an
        open)."""
        if not self._server.documents.change(params.text_document.uri, params.text_document.version,
                                             params.content_changes, self._server.encoding):
            return
        if (handler := self.fm.features.get(types.TEXT_DOCUMENT_DID_CHANGE)) is not None:
            yield handler, (params,), None

    @lsp_method(types.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(self, params: types.DidCloseTextDocumentParams):
        self._server.documents.close(params.text_document.uri)
        if (handler := self.fm.features.get(types.TEXT_DOCUMENT_DID_CLOSE)) is not None:
            yield handler, (params,), None


# ------------------------------------------------------------------ the server


class PlxServer(LanguageServer):
    def __init__(self) -> None:
        super().__init__("plx", __version__, protocol_cls=PlxProtocol,
                         text_document_sync_kind=types.TextDocumentSyncKind.Incremental)
        from plxtools.lsp.transport import Dispatcher

        self.host = AnalysisHost()
        self.documents = Documents()
        self.dispatcher = Dispatcher(self)
        self.loop: asyncio.AbstractEventLoop | None = None
        self.writer = None
        self.rule_docs_url: str | None = None
        self.init_options: dict = {}
        self.diagnostic_mode = "auto"
        self.pull_diagnostics = False  # decided in `initialize` (client support and `diagnosticMode`)
        self.uris: dict[str, str] = {}  # path -> the client's URI for open documents
        self._dirty: dict[str, bool] = {}  # uri -> cascade: documents waiting for a check, oldest first
        self._check_pending = False
        self._published: dict[str, tuple] = {}  # uri -> (version, diagnostics) last pushed
        self._positions: dict[str, Positions] = {}
        self._completion_keys: list = []
        self._shown: set[str] = set()
        self.timings: dict[str, list[tuple[float, float]]] = {}  # kind -> recent (wall ms, CPU ms)
        self.max_document_size = MAX_DOCUMENT_SIZE  # characters; 0: no limit (setting maxDocumentSize)
        self.background_size = int(os.environ.get("PLX_LSP_BACKGROUND_SIZE") or BACKGROUND_SIZE)
        self._background: dict[str, BackgroundCheck] = {}  # uri -> the forked check running for it
        self._migration: tuple | None = None  # (path, text, migrate_action.Migration | None) last computed
        self.counters: dict[str, int] = {}  # background checks started, finished, cancelled (plx/stats)
        # set while `initialized` loads the bundles in a thread (issue 32.12): completion is answered
        # at once meanwhile (nothing yet, ask again), checks wait for the load, and a request that
        # needs the model (hover, go-to) waits for it (the host's lock) rather than loading it twice
        self.warming: asyncio.Future | None = None

    def report_server_error(self, error: Exception, source) -> None:
        """Errors outside a request (a failing notification, a bad message) are logged; the editor is
        told once per distinct error, and the server keeps running."""
        if getattr(source, "__name__", "") == "FeatureRequestError":
            return  # the request's own error reply says it; its handler logged what deserved logging
        log.error("server error (%s): %s", getattr(source, "__name__", source), error)
        key = f"{type(error).__name__}: {error}"
        if key in self._shown:
            return
        self._shown.add(key)
        try:
            self.window_log_message(types.LogMessageParams(type=types.MessageType.Error,
                                                           message=f"plx: internal error: {key}"))
        except Exception:  # noqa: BLE001 - reporting must never raise
            pass

    # -------------------------------------------------------------- paths and positions

    def path_of(self, uri: str) -> str:
        if uri.startswith("file:"):
            fs = to_fs_path(uri)
            if fs:
                return os.path.realpath(fs)
        return uri  # untitled: and other schemes: the URI names the buffer

    def uri_of(self, path: str) -> str:
        got = self.uris.get(path)
        if got is not None:
            return got
        if os.path.isabs(path):
            return from_fs_path(path) or path
        return path

    @property
    def encoding(self):
        try:
            return self.workspace.position_encoding
        except RuntimeError:
            return types.PositionEncodingKind.Utf16

    def positions(self, path: str, st=None) -> Positions:
        """Position conversions for the text a result was computed on (cached per text)."""
        if st is not None:
            text, index = st.tree.text, st.tree.index
        else:
            tree = self.host.tree_of(path)
            text, index = (tree.text, tree.index) if tree is not None else (self.host.text_of(path) or "", None)
        got = self._positions.get(path)
        if got is not None and got.text is text and got.encoding == Positions("", self.encoding).encoding:
            return got
        got = Positions(text, self.encoding, index)
        if path in self.host.docs:
            self._positions[path] = got
        return got

    def cap(self, dotted: str, default=None):
        """A client capability by dotted attribute path (None-safe)."""
        cur = self.client_capabilities
        for part in dotted.split("."):
            cur = getattr(cur, part, None)
            if cur is None:
                return default
        return cur

    def markup(self, text: str) -> types.MarkupContent:
        formats = self.cap("text_document.hover.content_format") or [types.MarkupKind.PlainText]
        if types.MarkupKind.Markdown in formats:
            return types.MarkupContent(kind=types.MarkupKind.Markdown, value=text)
        return types.MarkupContent(kind=types.MarkupKind.PlainText, value=_plain(text))

    def doc_markup(self, text: str):
        formats = self.cap("text_document.completion.completion_item.documentation_format") or []
        if types.MarkupKind.Markdown in formats:
            return types.MarkupContent(kind=types.MarkupKind.Markdown, value=text)
        return _plain(text)

    # -------------------------------------------------------------- state

    def sync(self, uri: str) -> str | None:
        """Hand the host the buffer's current text; returns the document's path (None if not open)."""
        doc = self.documents.get(uri)
        path = self.path_of(uri)
        if doc is None:
            return None
        if self.too_big(doc):
            self.forget_analysis(path)  # the text alone is kept; nothing is parsed
            return None
        if path not in self.host.docs:
            self.uris[path] = uri
            self.host.open_document(path, doc.text, doc.version)
        elif self.host.docs[path].text is not doc.text or self.host.docs[path].version != doc.version:
            self.host.update_document(path, doc.text, doc.version)
        return path

    def state(self, uri: str, quick: bool = False):
        """The analysis of a document; `quick` (completion, signature help) skips the checker when the
        buffer changed since the last check, so typing does not wait for the diagnostics."""
        doc = self.documents.get(uri)
        if doc is not None and self.too_big(doc):
            self.forget_analysis(self.path_of(uri))
            return None
        path = self.sync(uri) or self.path_of(uri)
        return self.host.quick_state(path) if quick else self.host.state(path)

    def line_view(self, uri: str, line: int):
        """host.line_view for an open document within the size limit (None otherwise)."""
        doc = self.documents.get(uri)
        if doc is None or self.too_big(doc):
            return None
        path = self.sync(uri)
        return self.host.line_view(path, line) if path is not None else None

    # -------------------------------------------------------------- migrate this file

    def migrate_action(self, st, only) -> types.CodeAction | None:
        """`source.migrate.plx` (migrate_action.py): computed when asked for source actions or when
        the file has U001/U002 diagnostics, once per version of the text."""
        from plxtools.lsp import migrate_action as ma

        if not ma.wanted(only):
            return None
        if only is None and not any(d.code in ("U001", "U002") for d in st.diagnostics):
            return None
        cached = self._migration
        if cached is not None and cached[0] == st.path and cached[1] is st.text:
            m = cached[2]
        else:
            try:
                m = ma.migration(self.host, st)
            except Exception:  # noqa: BLE001 - the other actions are still answered
                log.exception("migrating %s failed", st.path)
                m = None
            self._migration = (st.path, st.text, m)
        if m is None:
            return None
        if m.new_text is None:
            if not self.cap("text_document.code_action.disabled_support"):
                return None
            return types.CodeAction(title=m.title, kind=ma.KIND,
                                    disabled=types.CodeActionDisabled(reason=m.reason or "refused"))
        pos = self.positions(st.path, st)
        edit = types.TextEdit(range=pos.offsets_range(0, len(st.text)), new_text=m.new_text)
        return types.CodeAction(title=m.title, kind=ma.KIND,
                                edit=types.WorkspaceEdit(changes={self.uri_of(st.path): [edit]}))

    # -------------------------------------------------------------- large documents

    def too_big(self, doc) -> bool:
        return bool(self.max_document_size) and len(doc.text) > self.max_document_size

    def forget_analysis(self, path: str) -> None:
        """Drop the host's buffer, tree and analysis of a document (kept by the server as text only)."""
        self._positions.pop(path, None)
        if path in self.host.docs:
            self.host.close_document(path)

    def size_diagnostic(self, doc) -> types.Diagnostic:
        size = len(doc.text)
        message = (f"not analysed: this document has {size:,} characters, over the language server's limit of "
                   f"{self.max_document_size:,} (setting maxDocumentSize; 0 lifts it); `plx lint` checks it")
        key = f"size:{doc.uri}"
        if key not in self._shown:
            self._shown.add(key)
            name = doc.uri.rsplit("/", 1)[-1]
            self.window_show_message(types.ShowMessageParams(type=types.MessageType.Warning,
                                                             message=f"plx: {name}: {message}"))
        return types.Diagnostic(range=types.Range(start=types.Position(line=0, character=0),
                                                  end=types.Position(line=0, character=0)),
                                message=message, severity=types.DiagnosticSeverity.Warning, source="plx")

    def in_background(self, uri: str, doc) -> bool:
        """A large loose document is checked in a forked process: the server keeps answering, and a
        newer version or closing the document kills that process (a bundle file's symbols are seen
        by other files, so it is checked in the server itself)."""
        if not hasattr(os, "fork") or len(doc.text) < self.background_size or self.loop is None:
            return False
        ws = self.host._ws
        if ws is None:
            return False
        unit = ws.program.units.get(self.path_of(uri))
        return unit is None or unit.bundle is None

    def start_background(self, uri: str, doc) -> "BackgroundCheck":
        self.cancel_background(uri)
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
                got = self.diagnostics_of(uri, background=False)
                diags = got[1] if got is not None else []
                data = json.dumps({"diagnostics": self.protocol._converter.unstructure(diags),
                                   "timing": self.timings.get("check", [[0, 0]])[-1]}).encode("utf-8")
                view = memoryview(data)
                while view:
                    view = view[os.write(w, view):]
            except BaseException:  # noqa: BLE001 - the parent sees a short read and checks in-process
                status = 1
            finally:
                os._exit(status)
        os.close(w)
        os.set_blocking(r, False)
        bg = BackgroundCheck(uri, doc.version, doc.text, pid, r)
        self._background[uri] = bg
        self._count("background-started")
        self.loop.add_reader(r, self._background_readable, bg)
        return bg

    def cancel_background(self, uri: str) -> None:
        bg = self._background.pop(uri, None)
        if bg is None:
            return
        self._end_child(bg, kill=True)
        self._count("background-cancelled")
        bg.settle(None)

    def _end_child(self, bg: "BackgroundCheck", kill: bool) -> None:
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

    def _background_readable(self, bg: "BackgroundCheck") -> None:
        while True:
            try:
                chunk = os.read(bg.fd, 1 << 20)
            except BlockingIOError:
                return
            except OSError:
                chunk = b""
            if not chunk:
                break
            bg.chunks.append(chunk)
        if self._background.get(bg.uri) is bg:
            del self._background[bg.uri]
        self._end_child(bg, kill=False)
        try:
            got = json.loads(b"".join(bg.chunks))
            diags = self.protocol._converter.structure(got["diagnostics"], list[types.Diagnostic])
        except Exception:  # noqa: BLE001 - the child failed: check in the server itself
            log.warning("the background check of %s failed; checking it here", bg.uri)
            bg.settle(None)
            doc = self.documents.get(bg.uri)
            if doc is not None and doc.text is bg.text:
                bg.fallback = True
                self._check_one(bg.uri, False, background=False)
            return
        bg.chunks = []
        self._count("background-finished")
        timing = got.get("timing") or [0, 0]
        rec = self.timings.setdefault("check-background", [])
        rec.append((float(timing[0]), float(timing[1])))
        del rec[:-200]
        doc = self.documents.get(bg.uri)
        if doc is None or doc.text is not bg.text:
            bg.settle(None)
            return  # superseded (normally cancelled before it got here)
        bg.settle((bg.version, diags))
        if not self.pull_diagnostics:
            self._push(bg.uri, bg.version, diags)
        self.notify_messages()

    def _count(self, name: str) -> None:
        self.counters[name] = self.counters.get(name, 0) + 1

    def notify_messages(self) -> None:
        while self.host.messages:
            msg = self.host.messages.pop(0)
            if msg in self._shown:
                continue
            self._shown.add(msg)
            log.warning("%s", msg)
            self.window_show_message(types.ShowMessageParams(type=types.MessageType.Warning, message=f"plx: {msg}"))

    # -------------------------------------------------------------- diagnostics

    def lsp_diagnostic(self, d: Diagnostic, pos: Positions) -> types.Diagnostic:
        sev = {Severity.ERROR: types.DiagnosticSeverity.Error, Severity.WARNING: types.DiagnosticSeverity.Warning,
               Severity.INFO: types.DiagnosticSeverity.Information}[d.severity]
        message = d.message + (f"\nhelp: {d.help}" if d.help else "")
        out = types.Diagnostic(range=pos.range(d.span), message=message, severity=sev, code=d.code, source="plx")
        if self.rule_docs_url and self.cap("text_document.publish_diagnostics.code_description_support"):
            out.code_description = types.CodeDescription(href=self.rule_docs_url.replace("{code}", d.code))
        tags = []
        if d.code == "C004":
            tags.append(types.DiagnosticTag.Deprecated)
        if d.code == "C002":
            tags.append(types.DiagnosticTag.Unnecessary)
        if tags and self.cap("text_document.publish_diagnostics.tag_support"):
            out.tags = tags
        if d.related and self.cap("text_document.publish_diagnostics.related_information"):
            rel = []
            for file, span, msg in d.related:
                p = file or ""
                rel.append(types.DiagnosticRelatedInformation(
                    location=types.Location(uri=self.uri_of(p), range=self.positions(p).range(span)), message=msg))
            out.related_information = rel
        if d.fix is not None:
            out.data = {"fix": {"message": d.fix.message, "safe": d.fix.safe,
                                "edits": [[e.start, e.end, e.text] for e in d.fix.edits]}}
        return out

    def diagnostics_of(self, uri: str, background: bool = False):
        """(version, LSP diagnostics) of a document's current text, checked now (or, with
        `background`, the BackgroundCheck started for a large document)."""
        doc = self.documents.get(uri)
        if doc is None:
            return None
        if self.too_big(doc):
            self.forget_analysis(self.path_of(uri))
            return doc.version, [self.size_diagnostic(doc)]
        if background and self.in_background(uri, doc):
            bg = self._background.get(uri)
            if bg is not None and bg.text is doc.text:
                return bg
            return self.start_background(uri, doc)
        t0, c0 = time.perf_counter(), time.process_time()
        with no_gc():
            st = self.state(uri)
            if st is None:
                return None
            pos = self.positions(st.path, st)
            diags = [self.lsp_diagnostic(d, pos) for d in st.diagnostics]
            self._record("check", t0, c0)
        watching.refresh_import_watchers(self)  # the files its imports name: watched from now on
        return doc.version, diags

    def publish(self, uri: str, background: bool = True) -> None:
        """Check a document now and push its diagnostics for the version they were computed for;
        the same diagnostics for the same version are not sent twice."""
        doc = self.documents.get(uri)
        if doc is not None and background and self.pull_diagnostics and not self.too_big(doc) \
                and self.in_background(uri, doc):
            return  # the editor pulls them: its request starts the check in another process
        got = self.diagnostics_of(uri, background=background)
        if got is None or isinstance(got, BackgroundCheck):
            return  # a large document: its check runs in another process (_background_readable)
        version, diags = got
        if self.pull_diagnostics:
            self.notify_messages()
            return
        self._push(uri, version, diags)
        self.notify_messages()

    def _push(self, uri: str, version, diags) -> None:
        key = (version, [(d.range, d.code, d.message, d.severity) for d in diags])
        if self._published.get(uri) != key:
            self._published[uri] = key
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, version=version, diagnostics=diags))

    def _record(self, kind: str, t0: float, c0: float) -> None:
        got = self.timings.setdefault(kind, [])
        got.append(((time.perf_counter() - t0) * 1000, (time.process_time() - c0) * 1000))
        del got[:-200]

    # -------------------------------------------------------------- the analysis scheduler

    def schedule(self, uri: str, delay: float | None = None, cascade: bool = True) -> None:
        """Queue a document for checking. No fixed delay: the check runs as soon as no message is
        waiting to be handled, so a burst of edits is checked once, at its last version (older
        versions are superseded before they start), and requests are answered first."""
        if self.documents.get(uri) is None:
            return
        self._dirty[uri] = self._dirty.pop(uri, False) or cascade
        self._wake()

    def _wake(self) -> None:
        if self._check_pending or self.loop is None:
            if self.loop is None:
                self._drain_now()
            return
        self._check_pending = True
        self.loop.call_soon(self._run_checks)

    def _drain_now(self) -> None:
        while self._dirty:
            uri, cascade = next(iter(self._dirty.items()))
            del self._dirty[uri]
            self._check_one(uri, cascade)

    def _run_checks(self) -> None:
        """One document per turn of the event loop; messages that arrived meanwhile go first."""
        self._check_pending = False
        if not self._dirty or self.warming is not None:
            return  # (the bundles' loader wakes the checks when it is done)
        if self.dispatcher.inbox > 0:
            # edits and requests are waiting: handle them first (a newer version supersedes this)
            self._check_pending = True
            self.loop.call_soon(self._run_checks)
            return
        uri, cascade = next(iter(self._dirty.items()))
        if self._parse_ahead(uri):
            self._wake()  # the analysis next turn, after the messages that arrived while parsing
            return
        del self._dirty[uri]
        self._check_one(uri, cascade)
        if self._dirty:
            self._wake()

    def _parse_ahead(self, uri: str) -> bool:
        """A check in two halves, parse then analysis, with waiting messages handled in between:
        a completion typed right after an edit waits for one half, not for the whole check."""
        doc = self.documents.get(uri)
        if doc is None or self.too_big(doc) or self.in_background(uri, doc):
            return False
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            with no_gc():
                done = self.host.parse_ahead(self.sync(uri) or self.path_of(uri))
            if done:
                self._record("parse", t0, c0)
            return done
        except Exception:  # noqa: BLE001 - the check itself reports what went wrong
            log.exception("parsing %s failed", uri)
            return False

    def _check_one(self, uri: str, cascade: bool, background: bool = True) -> None:
        try:
            self.publish(uri, background)
            if cascade:
                self.schedule_dependents(self.path_of(uri))
        except Exception:  # noqa: BLE001 - a failing check must not stop the server
            log.exception("checking %s failed", uri)

    def schedule_dependents(self, path: str, deps: list[str] | None = None) -> None:
        deps = self.host.dependents(path) if deps is None else deps
        if self.pull_diagnostics:
            if deps and self.cap("workspace.diagnostics.refresh_support"):
                self.workspace_diagnostic_refresh(None)
            return
        for dep in deps:
            dep_uri = self.uri_of(dep)
            if dep_uri not in self._dirty:
                self.schedule(dep_uri, cascade=False)

    def recheck_all(self) -> None:
        if self.pull_diagnostics:
            if self.cap("workspace.diagnostics.refresh_support"):
                self.workspace_diagnostic_refresh(None)
            return
        for uri in list(self.documents):
            self.schedule(uri, cascade=False)

    # -------------------------------------------------------------- settings

    def _resolve_setting_path(self, p: str) -> str:
        root = self.host.root if self.host.root and os.path.isabs(self.host.root) else os.getcwd()
        p = os.path.expanduser(p.strip().replace("${workspaceFolder}", root))
        return p if os.path.isabs(p) else os.path.normpath(os.path.join(root, p))

    def apply_settings(self, raw: dict | None) -> None:
        merged = dict(self.init_options)
        for k, v in (raw or {}).items():
            if v is None or v == "":
                continue  # an unset editor setting does not override initializationOptions
            if k == "bundlePath" and self.init_options.get("bundlePath"):
                continue  # the client resolved this one already (VS Code expands ${workspaceFolder})
            merged[k] = v
        s = Settings()
        bp = merged.get("bundlePath") or merged.get("bundle_path") or []
        if isinstance(bp, str):
            bp = [p for p in bp.split(os.pathsep) if p.strip()]
        s.bundle_paths = [self._resolve_setting_path(str(p)) for p in bp if isinstance(p, str)]
        version = merged.get("openplxVersion") or merged.get("openplx_version")
        s.openplx_version = version.strip() if isinstance(version, str) and version.strip() else None
        sel = merged.get("select")
        if isinstance(sel, str):
            sel = [c.strip() for c in sel.split(",") if c.strip()]
        s.select = [c.upper() for c in sel] if sel else None
        ign = merged.get("ignore") or []
        if isinstance(ign, str):
            ign = [c.strip() for c in ign.split(",") if c.strip()]
        s.ignore = [c.upper() for c in ign]
        mode = merged.get("diagnosticMode")
        self.diagnostic_mode = mode if mode in ("auto", "push", "pull") else "auto"
        size = merged.get("maxDocumentSize")
        if isinstance(size, (int, float)) and not isinstance(size, bool) and size >= 0:
            self.max_document_size = int(size)
        elif size is not None:
            self.host.messages.append(f"maxDocumentSize must be a number of characters (0: no limit), not {size!r}")
            self.max_document_size = MAX_DOCUMENT_SIZE
        else:
            self.max_document_size = MAX_DOCUMENT_SIZE
        url = merged.get("ruleDocsUrl")
        self.rule_docs_url = url if isinstance(url, str) and url else None
        if self.host.configure(s):  # a new bundle path: the old model is garbage now
            gc.unfreeze()
            _ = self.host.workspace
            freeze_loaded()


class no_gc:
    """No cyclic garbage collection while a file is checked (or completed while typing) and the
    result is sent, and none forced after it either.

    A check allocates ~10^5 objects per 2,000 lines (the new tree and symbols), and it leaves no
    reference cycles behind (the checker uses no self-calling closures, and a replaced file's
    symbols are taken apart by Program.remove_unit), so reference counting frees the previous
    version at once. What the check built is then frozen (`gc.freeze()`, constant time): the
    collector never rescans it, so the automatic passes between requests only walk what was
    allocated since, and no request waits for a pass over a 20,000-line tree. Anything cyclic
    that still slipped into the frozen generation is swept when the editor has been idle
    (`_idle_sweep`), never on a request's path."""

    def __enter__(self):
        gc.disable()

    def __exit__(self, *exc):
        _settle_gc()


IDLE_SWEEP_AFTER = 10.0  # seconds without a check before the sweep
IDLE_SWEEP_EVERY = 120.0  # at most one sweep per this many seconds
_sweep_handle = None
_last_sweep = 0.0
_checks_since_sweep = 0


def _settle_gc() -> None:
    """After a check: freeze what it built, resume automatic (now small) passes, and (re)arm the
    idle sweep."""
    global _sweep_handle, _checks_since_sweep
    gc.freeze()
    gc.enable()
    _checks_since_sweep += 1
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        return
    if _sweep_handle is not None:
        _sweep_handle.cancel()
    _sweep_handle = loop.call_later(IDLE_SWEEP_AFTER, _idle_sweep)


def _idle_sweep() -> None:
    """One full collection over everything, frozen objects included, when nobody is waiting."""
    global _sweep_handle, _last_sweep, _checks_since_sweep
    _sweep_handle = None
    now = time.monotonic()
    if not _checks_since_sweep:
        return
    if now - _last_sweep < IDLE_SWEEP_EVERY:
        try:
            _sweep_handle = asyncio.get_running_loop().call_later(IDLE_SWEEP_EVERY - (now - _last_sweep), _idle_sweep)
        except RuntimeError:
            pass
        return
    _last_sweep = now
    _checks_since_sweep = 0
    gc.unfreeze()
    gc.collect()
    gc.freeze()


def freeze_loaded() -> None:
    """Move everything loaded so far (the bundles' trees and symbols, which live as long as the
    server) out of the collector's sight, so collections only walk what edits create."""
    gc.collect()
    gc.freeze()


def _plain(markdown: str) -> str:
    return markdown.replace("```openplx\n", "").replace("```\n", "").replace("```", "")


def _section(obj) -> dict | None:
    if not isinstance(obj, dict):
        return None
    for key in ("openplx", "plx"):
        if isinstance(obj.get(key), dict):
            return obj[key]
    return obj


KIND = {
    "model": types.CompletionItemKind.Class,
    "trait": types.CompletionItemKind.Interface,
    "constant": types.CompletionItemKind.Constant,
    "namespace": types.CompletionItemKind.Module,
    "attribute": types.CompletionItemKind.Field,
    "method": types.CompletionItemKind.Method,
    "keyword": types.CompletionItemKind.Keyword,
    "value": types.CompletionItemKind.Value,
    "type": types.CompletionItemKind.TypeParameter,
}
SYMBOL_KIND = {
    "model": types.SymbolKind.Class,
    "trait": types.SymbolKind.Interface,
    "const": types.SymbolKind.Constant,
    "global": types.SymbolKind.Constant,
    "attribute": types.SymbolKind.Field,
    "method": types.SymbolKind.Method,
    "operator": types.SymbolKind.Operator,
    "block": types.SymbolKind.Object,
    "import": types.SymbolKind.Module,
}


def _guard(method: str, fn):
    """Log a request's failure with its traceback; the request gets an error, the server lives on.

    `PLX_LSP_FAULT=<method>` makes that request fail on purpose (for the robustness tests)."""
    import functools

    @functools.wraps(fn)
    def wrapper(ls, params):
        if os.environ.get("PLX_LSP_FAULT") == method:
            raise RuntimeError(f"injected fault in {method} (PLX_LSP_FAULT)")
        try:
            return fn(ls, params)
        except JsonRpcException:
            raise
        except Exception:
            log.exception("%s failed", method)
            raise
    return wrapper


def create_server() -> PlxServer:  # noqa: C901 - one registration per feature
    server = PlxServer()

    def server_feature(method: str, options=None):
        def register(fn):
            if asyncio.iscoroutinefunction(fn):
                return server.feature(method, options)(fn)
            return server.feature(method, options)(_guard(method, fn))
        return register

    # -------------------------------------------------------------- lifecycle

    @server_feature(types.INITIALIZE)
    def initialize(ls: PlxServer, params: types.InitializeParams) -> None:
        ls.init_options = _section(params.initialization_options) or {}
        root = None
        if params.root_uri:
            root = ls.path_of(params.root_uri)
        elif params.workspace_folders:
            root = ls.path_of(params.workspace_folders[0].uri)
        elif params.root_path:
            root = params.root_path
        ls.host.root = root
        ls.apply_settings(None)
        if ls.loop is not None:  # until `initialized` has loaded the bundles, requests do not wait
            ls.warming = ls.loop.create_future()
        # pull diagnostics when the client can pull them (as ruff's server does), push otherwise;
        # never both, or editors show every diagnostic twice
        ls.pull_diagnostics = ls.cap("text_document.diagnostic") is not None and ls.diagnostic_mode != "push"
        if not ls.pull_diagnostics:
            ls.protocol.fm.features.pop(types.TEXT_DOCUMENT_DIAGNOSTIC, None)

    @server_feature(types.INITIALIZED)
    async def initialized(ls: PlxServer, params: types.InitializedParams) -> None:
        if ls.cap("workspace.configuration"):
            await _pull_configuration(ls)
        if ls.cap("workspace.did_change_watched_files.dynamic_registration"):
            await _watch_files(ls)
        # load the bundles now, not on the first keystroke, and in a thread: a request that arrives
        # meanwhile (Helix asks for completion right after opening a file) is answered at once
        loop = asyncio.get_running_loop()
        if ls.warming is None:
            ls.warming = loop.create_future()
        try:
            await loop.run_in_executor(None, lambda: ls.host.workspace)
        except asyncio.CancelledError:
            return  # the editor quit while the bundles were loading
        finally:
            done, ls.warming = ls.warming, None
            if not done.done():
                done.set_result(None)
        freeze_loaded()
        ls.notify_messages()
        ls._wake()

    async def _watch_files(ls: PlxServer) -> None:
        """Ask the editor to report model and config files changed on disk (a changed config may
        choose another bundle set)."""
        globs = ["**/*.openplx", *(f"**/{name}" for name in CONFIG_FILES if not name.endswith(".openplx"))]
        try:
            await ls.client_register_capability_async(types.RegistrationParams(registrations=[types.Registration(
                id="plx-watched-files", method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=types.DidChangeWatchedFilesRegistrationOptions(
                    watchers=[types.FileSystemWatcher(glob_pattern=g) for g in globs]))]))
        except Exception as exc:  # noqa: BLE001 - without watchers the editor's own events still arrive
            log.info("could not register file watchers: %s", exc)

    async def _pull_configuration(ls: PlxServer) -> None:
        try:
            got = await ls.workspace_configuration_async(types.ConfigurationParams(
                items=[types.ConfigurationItem(section=CONFIG_SECTION)]))
        except Exception as exc:  # noqa: BLE001 - a client that cannot answer keeps the defaults
            log.info("workspace/configuration failed: %s", exc)
            return
        if got:
            ls.apply_settings(_section(got[0]) if isinstance(got[0], dict) else None)

    @server_feature(types.WORKSPACE_DID_CHANGE_CONFIGURATION)
    async def did_change_configuration(ls: PlxServer, params: types.DidChangeConfigurationParams) -> None:
        if ls.warming is not None and ls.warming.get_loop().is_running():
            await asyncio.shield(ls.warming)  # new settings after the bundles' loader, never during it
        if ls.cap("workspace.configuration"):
            await _pull_configuration(ls)
        else:
            ls.apply_settings(_section(params.settings) if isinstance(params.settings, dict) else None)
        ls.recheck_all()

    # -------------------------------------------------------------- documents

    @server_feature(types.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: PlxServer, params: types.DidOpenTextDocumentParams) -> None:
        uri = params.text_document.uri
        path = ls.path_of(uri)
        ls.uris[path] = uri
        ls._published.pop(uri, None)
        ls.cancel_background(uri)
        if ls.warming is not None:  # the host takes the buffer once the bundles are loaded
            ls.schedule(uri, cascade=False)
            return
        doc = ls.documents.get(uri)
        if doc is not None and ls.too_big(doc):
            ls.schedule(uri, cascade=False)  # the size message, nothing parsed
            return
        before = ls.host.text_of(path)  # what the model knew: the file on disk, if any
        ls.host.open_document(path, params.text_document.text, params.text_document.version)
        ls.schedule(uri, cascade=before is not None and before != params.text_document.text)

    @server_feature(types.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: PlxServer, params: types.DidChangeTextDocumentParams) -> None:
        uri = params.text_document.uri
        ls.cancel_background(uri)  # a newer version: the check of the older one is dropped at once
        if ls.sync(uri) is None:
            if ls.documents.get(uri) is not None:
                ls.schedule(uri, cascade=False)  # over the size limit: the message for this version
            return
        ls.schedule(uri)

    @server_feature(types.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: PlxServer, params: types.DidCloseTextDocumentParams) -> None:
        uri = params.text_document.uri
        path = ls.path_of(uri)
        ls._dirty.pop(uri, None)
        ls._positions.pop(path, None)
        ls.cancel_background(uri)
        ls._shown.discard(f"size:{uri}")
        deps = ls.host.dependents(path)
        ls.host.close_document(path)
        ls.uris.pop(path, None)
        if ls._published.pop(uri, None) is not None:
            ls.text_document_publish_diagnostics(types.PublishDiagnosticsParams(uri=uri, diagnostics=[]))
        ls.schedule_dependents(path, deps)

    @server_feature(types.TEXT_DOCUMENT_DIAGNOSTIC,
                    types.DiagnosticOptions(inter_file_dependencies=True, workspace_diagnostics=False,
                                            identifier="plx"))
    async def document_diagnostic(ls: PlxServer, params: types.DocumentDiagnosticParams):
        """Pull diagnostics: the current version's, computed now (or unchanged since `previous_result_id`).
        A large document's are computed in another process; a newer version cancels the request
        with ServerCancelled and `retriggerRequest` (LSP 3.17), so the editor asks again."""
        uri = params.text_document.uri
        if ls.warming is not None:
            await asyncio.shield(ls.warming)  # the bundles are loading: these are the first diagnostics
        ls._dirty.pop(uri, None)
        if os.environ.get("PLX_LSP_FAULT") == types.TEXT_DOCUMENT_DIAGNOSTIC:
            raise RuntimeError(f"injected fault in {types.TEXT_DOCUMENT_DIAGNOSTIC} (PLX_LSP_FAULT)")
        got = ls.diagnostics_of(uri, background=True)
        if isinstance(got, BackgroundCheck):
            got = await got.wait()
            if got is None:
                raise ServerCancelled(message="a newer version of the document arrived", data={"retriggerRequest": True})
        if got is None:
            return types.RelatedFullDocumentDiagnosticReport(items=[])
        version, diags = got
        result_id = f"{version}:{hash(tuple((d.range.start.line, d.range.start.character, d.code, d.message) for d in diags)) & 0xffffffff:x}"
        ls.notify_messages()
        if params.previous_result_id == result_id:
            return types.RelatedUnchangedDocumentDiagnosticReport(result_id=result_id)
        return types.RelatedFullDocumentDiagnosticReport(items=diags, result_id=result_id)

    @server_feature(types.TEXT_DOCUMENT_DID_SAVE)
    def did_save(ls: PlxServer, params: types.DidSaveTextDocumentParams) -> None:
        pass  # buffers are checked as they change; saving changes nothing the server sees

    @server_feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)
    def did_change_watched(ls: PlxServer, params: types.DidChangeWatchedFilesParams) -> None:
        changed, new_set = watching.on_watched_files(ls, params, CONFIG_FILES)  # config, bundles, imports
        if new_set:  # a new bundle set: the old model is garbage now
            gc.unfreeze()
            _ = ls.host.workspace
            freeze_loaded()
            ls.notify_messages()
        if changed:
            ls.recheck_all()

    # -------------------------------------------------------------- hover and navigation

    @server_feature(types.TEXT_DOCUMENT_HOVER)
    def hover(ls: PlxServer, params: types.HoverParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        res = ide.hover(st, pos.offset(params.position))
        if res is None:
            return None
        return types.Hover(contents=ls.markup(res.markdown), range=pos.range(res.span))

    def _locations(ls: PlxServer, targets, link_support: str | None, origin=None):
        if not targets:
            return None
        if link_support and ls.cap(link_support) and origin is not None:
            out = []
            for t in targets:
                tp = ls.positions(t.path)
                out.append(types.LocationLink(target_uri=ls.uri_of(t.path), target_range=tp.range(t.full),
                                              target_selection_range=tp.range(t.focus), origin_selection_range=origin))
            return out
        return [types.Location(uri=ls.uri_of(t.path), range=ls.positions(t.path).range(t.focus)) for t in targets]

    def _nav(fn, link_cap):
        def handler(ls: PlxServer, params):
            st = ls.state(params.text_document.uri)
            if st is None:
                return None
            pos = ls.positions(st.path, st)
            offset = pos.offset(params.position)
            targets = fn(st, offset)
            origin = None
            from plxtools.ide.context import resolve_at

            r = resolve_at(st, offset) if targets else None
            if r is not None:
                origin = pos.range(r.span)
            return _locations(ls, targets, link_cap, origin)
        return handler

    server_feature(types.TEXT_DOCUMENT_DEFINITION)(_nav(ide.definition, "text_document.definition.link_support"))
    server_feature(types.TEXT_DOCUMENT_DECLARATION)(_nav(ide.declaration, "text_document.declaration.link_support"))
    server_feature(types.TEXT_DOCUMENT_TYPE_DEFINITION)(
        _nav(ide.type_definition, "text_document.type_definition.link_support"))

    @server_feature(types.TEXT_DOCUMENT_REFERENCES)
    def references(ls: PlxServer, params: types.ReferenceParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        refs = ide.references(ls.host, st.path, pos.offset(params.position),
                              include_declaration=params.context.include_declaration)
        return [types.Location(uri=ls.uri_of(r.path), range=ls.positions(r.path).range(r.span)) for r in refs]

    @server_feature(types.TEXT_DOCUMENT_PREPARE_RENAME)
    def prepare_rename(ls: PlxServer, params: types.PrepareRenameParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        try:
            span, name = ide.prepare_rename(ls.host, st.path, pos.offset(params.position))
        except ide.RenameError as exc:
            raise RequestFailed(str(exc)) from None
        return types.PrepareRenamePlaceholder(range=pos.range(span), placeholder=name)

    @server_feature(types.TEXT_DOCUMENT_RENAME)
    def rename(ls: PlxServer, params: types.RenameParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        try:
            edits = ide.rename(ls.host, st.path, pos.offset(params.position), params.new_name)
        except ide.RenameError as exc:
            raise RequestFailed(str(exc)) from None
        changes = {}
        for path, file_edits in edits.items():
            fp = ls.positions(path)
            changes[ls.uri_of(path)] = [types.TextEdit(range=fp.offsets_range(e.start, e.end), new_text=e.text)
                                        for e in file_edits]
        return types.WorkspaceEdit(changes=changes)

    # -------------------------------------------------------------- completion and signatures

    @server_feature(types.TEXT_DOCUMENT_COMPLETION,
                    types.CompletionOptions(trigger_characters=[".", " "], resolve_provider=True))
    def completion(ls: PlxServer, params: types.CompletionParams):
        if ls.warming is not None:  # the bundles are loading: nothing to offer yet, ask again
            return types.CompletionList(is_incomplete=True, items=[])
        t0, c0 = time.perf_counter(), time.process_time()
        ctx = params.context
        trigger = ctx.trigger_character if ctx is not None and ctx.trigger_kind == \
            types.CompletionTriggerKind.TriggerCharacter else None
        view = ls.line_view(params.text_document.uri, params.position.line)
        if view is not None:
            # typing on one line since the last analysis: answer from it and the line's text, at once
            st = view.state
            lp = Positions(view.text, ls.encoding)
            col = lp.offset_at(0, params.position.character)
            res = ide.complete_line(st, view.line, view.text, col, view.start, trigger, view.own_line,
                                    min(view.start + col, view.old_end))

            def at(offset: int) -> types.Position:
                return types.Position(line=view.line, character=lp.offset_position(offset - view.start).character)
            rng = types.Range(start=at(res.replace_start), end=at(view.start + col))
        else:
            with no_gc():
                st = ls.state(params.text_document.uri, quick=True)
            if st is None:
                return None
            pos = ls.positions(st.path, st)
            offset = pos.offset(params.position)
            res = ide.complete(st, offset, trigger)
            rng = pos.offsets_range(res.replace_start, offset)
        lazy_doc = "documentation" in (ls.cap("text_document.completion.completion_item.resolve_support.properties")
                                       or [])
        label_details = ls.cap("text_document.completion.completion_item.label_details_support")
        tag_support = ls.cap("text_document.completion.completion_item.tag_support")
        ls._completion_keys = []
        items = []
        for i, it in enumerate(res.items):
            item = types.CompletionItem(label=it.label, kind=KIND.get(it.kind), detail=it.detail or None,
                                        sort_text=it.sort_text, filter_text=it.filter_text,
                                        text_edit=types.TextEdit(range=rng, new_text=it.insert_text or it.label))
            if label_details and (it.label_detail or it.label_description):
                item.label_details = types.CompletionItemLabelDetails(detail=it.label_detail,
                                                                      description=it.label_description)
            if it.deprecated and tag_support:
                item.tags = [types.CompletionItemTag.Deprecated]
            if it.key is not None:
                ls._completion_keys.append(it.key)
                item.data = {"k": len(ls._completion_keys) - 1}
                if not lazy_doc:
                    doc = ide.completion_documentation(st.program, it.key)
                    if doc:
                        item.documentation = ls.doc_markup(doc)
            items.append(item)
            del i
        ls._record("completion" if st.checked and view is None else "completion-while-typing", t0, c0)
        return types.CompletionList(is_incomplete=res.is_incomplete, items=items)

    @server_feature(types.COMPLETION_ITEM_RESOLVE)
    def completion_resolve(ls: PlxServer, item: types.CompletionItem):
        data = item.data if isinstance(item.data, dict) else {}
        k = data.get("k")
        if isinstance(k, int) and 0 <= k < len(ls._completion_keys) and ls.host.program is not None:
            doc = ide.completion_documentation(ls.host.program, ls._completion_keys[k])
            if doc:
                item.documentation = ls.doc_markup(doc)
        return item

    @server_feature(types.TEXT_DOCUMENT_SIGNATURE_HELP,
                    types.SignatureHelpOptions(trigger_characters=["(", ","], retrigger_characters=[","]))
    def signature_help(ls: PlxServer, params: types.SignatureHelpParams):
        st = ls.state(params.text_document.uri, quick=True)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        res = ide.signature_help(st, pos.offset(params.position))
        if res is None:
            return None
        offsets = ls.cap("text_document.signature_help.signature_information.parameter_information."
                         "label_offset_support")
        from plxtools.ide.signature import param_label_offsets

        sigs = []
        for s in res.signatures:
            labels = param_label_offsets(s) if offsets else [p.label for p in s.parameters]
            params_ = [types.ParameterInformation(label=lab) for lab in labels]
            # the active parameter inside each signature too: LSP 3.18 reads a null there as "none"
            active = min(res.active_parameter or 0, max(len(params_) - 1, 0))
            sigs.append(types.SignatureInformation(label=s.label, parameters=params_,
                                                   documentation=ls.doc_markup(s.documentation)
                                                   if s.documentation else None,
                                                   active_parameter=active))
        return types.SignatureHelp(signatures=sigs, active_signature=res.active_signature,
                                   active_parameter=res.active_parameter)

    # -------------------------------------------------------------- symbols

    @server_feature(types.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def document_symbol(ls: PlxServer, params: types.DocumentSymbolParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        syms = ide.document_symbols(st.tree)
        if ls.cap("text_document.document_symbol.hierarchical_document_symbol_support"):
            def conv(s):
                return types.DocumentSymbol(name=s.name, kind=SYMBOL_KIND[s.kind], range=pos.range(s.span),
                                            selection_range=pos.range(s.selection), detail=s.detail or None,
                                            children=[conv(c) for c in s.children] or None)
            return [conv(s) for s in syms]
        flat = []
        uri = params.text_document.uri

        def walk(s, container):
            flat.append(types.SymbolInformation(name=s.name, kind=SYMBOL_KIND[s.kind],
                                                location=types.Location(uri=uri, range=pos.range(s.span)),
                                                container_name=container))
            for c in s.children:
                walk(c, s.name)
        for s in syms:
            walk(s, None)
        return flat

    @server_feature(types.WORKSPACE_SYMBOL)
    def workspace_symbol(ls: PlxServer, params: types.WorkspaceSymbolParams):
        out = []
        for w in ide.workspace_symbols(ls.host, params.query):
            out.append(types.WorkspaceSymbol(name=w.name, kind=SYMBOL_KIND.get(w.kind, types.SymbolKind.Class),
                                             location=types.Location(uri=ls.uri_of(w.path),
                                                                     range=ls.positions(w.path).range(w.span)),
                                             container_name=w.container or None))
        return out

    # -------------------------------------------------------------- formatting

    @server_feature(types.TEXT_DOCUMENT_FORMATTING)
    def formatting(ls: PlxServer, params: types.DocumentFormattingParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        try:
            edits = ide.format_document(st.text, st.path if os.path.isabs(st.path) else "")
        except ide.FormattingRefused as exc:
            if exc.syntax:
                ls.window_log_message(types.LogMessageParams(type=types.MessageType.Info, message=f"plx: {exc}"))
                return []
            raise RequestFailed(str(exc)) from None
        pos = ls.positions(st.path, st)
        return [types.TextEdit(range=pos.offsets_range(e.start, e.end), new_text=e.text) for e in edits]

    @server_feature(types.TEXT_DOCUMENT_RANGE_FORMATTING)
    def range_formatting(ls: PlxServer, params: types.DocumentRangeFormattingParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        r = params.range
        end_line = r.end.line - 1 if r.end.character == 0 and r.end.line > r.start.line else r.end.line
        try:
            edits = ide.format_lines(st.text, r.start.line, end_line)
        except ide.FormattingRefused as exc:
            raise RequestFailed(str(exc)) from None
        pos = ls.positions(st.path, st)
        return [types.TextEdit(range=pos.offsets_range(e.start, e.end), new_text=e.text) for e in edits]

    # -------------------------------------------------------------- code actions

    @server_feature(types.TEXT_DOCUMENT_CODE_ACTION,
                    types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix,
                                                               types.CodeActionKind.SourceFixAll,
                                                               "source.migrate.plx"]))
    def code_action(ls: PlxServer, params: types.CodeActionParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        start, end = pos.offset(params.range.start), pos.offset(params.range.end)
        only = [str(k.value if hasattr(k, "value") else k) for k in params.context.only] \
            if params.context.only else None
        actions = ide.code_actions(st, start, end, only)
        sent = list(params.context.diagnostics or [])
        out = []
        for a in actions:
            changes = {}
            for path, edits in a.edits.items():
                fp = ls.positions(path, st if path == st.path else None)
                changes[ls.uri_of(path)] = [types.TextEdit(range=fp.offsets_range(e.start, e.end), new_text=e.text)
                                            for e in edits]
            diags = []
            for d in a.diagnostics[:20]:
                rng = pos.range(d.span)
                match = next((x for x in sent if x.code == d.code and x.range == rng), None)
                diags.append(match or ls.lsp_diagnostic(d, pos))
            out.append(types.CodeAction(title=a.title, kind=a.kind, diagnostics=diags or None,
                                        is_preferred=a.preferred or None, edit=types.WorkspaceEdit(changes=changes)))
        # where the version diagnostic is (VS Code's Ctrl+. shows quick fixes, not source actions),
        # "migrate this file" is also a quick fix of it; elsewhere it is a source action only
        version_diags = [x for x in sent if x.code in ("U001", "U002")]
        as_quickfix = bool(version_diags) and (only is None or any(k in ("quickfix", "") for k in only))
        migrate = ls.migrate_action(st, None if as_quickfix else only)
        if migrate is not None and as_quickfix and migrate.edit is not None:
            migrate = types.CodeAction(title=migrate.title, kind=types.CodeActionKind.QuickFix,
                                       diagnostics=version_diags, edit=migrate.edit)
        if migrate is not None:
            out.append(migrate)
        return out

    @server.feature("plx/stats")
    def stats(ls: PlxServer, params) -> dict:
        """Recent server-side timings (wall and CPU ms) of checks and completions, for bench/lsp_bench.py."""
        out: dict = {kind: [list(x) for x in vals] for kind, vals in ls.timings.items()}
        out["counters"] = dict(ls.counters)
        return out

    @server.feature("plx/memory")
    def memory(ls: PlxServer, params) -> dict:
        """What the server holds (for tests and bench/lsp_large_doc.py): the syntax trees alive
        (path and length of their text, found by the collector, frozen objects included), resident
        memory, and Python's own allocations when tracemalloc traces."""
        return memory_report()

    @server.feature("plx/documentText")
    def document_text(ls: PlxServer, params) -> dict | None:
        """The text and version the server holds for an open document (for sync checks and bug reports)."""
        uri = getattr(params, "uri", None) if not isinstance(params, dict) else params.get("uri")
        doc = ls.documents.get(uri) if isinstance(uri, str) else None
        if doc is None:
            return None
        return {"version": doc.version, "text": doc.text}

    # -------------------------------------------------------------- presentation

    @server_feature(types.TEXT_DOCUMENT_SEMANTIC_TOKENS_FULL,
                    types.SemanticTokensLegend(token_types=ide.TOKEN_TYPES, token_modifiers=ide.TOKEN_MODIFIERS))
    def semantic_tokens(ls: PlxServer, params: types.SemanticTokensParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        from plxtools.ide.tokens import encode

        return types.SemanticTokens(data=encode(ide.semantic_tokens(st), pos.length))

    @server_feature(types.TEXT_DOCUMENT_FOLDING_RANGE)
    def folding_range(ls: PlxServer, params: types.FoldingRangeParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        kinds = {"comment": types.FoldingRangeKind.Comment, "region": types.FoldingRangeKind.Region}
        return [types.FoldingRange(start_line=f.start_line, end_line=f.end_line, kind=kinds.get(f.kind))
                for f in ide.folding_ranges(st.tree)]

    @server_feature(types.TEXT_DOCUMENT_DOCUMENT_LINK)
    def document_link(ls: PlxServer, params: types.DocumentLinkParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        tooltips = ls.cap("text_document.document_link.tooltip_support")
        return [types.DocumentLink(range=pos.range(link.span), target=from_fs_path(link.target),
                                   tooltip=link.tooltip if tooltips else None)
                for link in ide.document_links(st.tree, st.path)]

    @server_feature(types.TEXT_DOCUMENT_INLAY_HINT)
    def inlay_hint(ls: PlxServer, params: types.InlayHintParams):
        st = ls.state(params.text_document.uri)
        if st is None:
            return None
        pos = ls.positions(st.path, st)
        start, end = pos.offset(params.range.start), pos.offset(params.range.end)
        kinds = {"type": types.InlayHintKind.Type, "parameter": types.InlayHintKind.Parameter}
        return [types.InlayHint(position=pos.position(h.line, h.column), label=h.label, kind=kinds[h.kind],
                                padding_left=h.padding_left or None, padding_right=h.padding_right or None)
                for h in ide.inlay_hints(st, start, end)]

    return server


def _configure_logging(log_file: str | None) -> None:
    handler: logging.Handler
    if log_file:
        handler = logging.FileHandler(log_file, encoding="utf-8")
        level = logging.INFO
    else:
        handler = logging.StreamHandler(sys.stderr)
        level = logging.WARNING
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(level)
    logging.getLogger("pygls").setLevel(logging.WARNING if not log_file else logging.INFO)


def run_server(args, first: bytes | None = None, replay=None) -> int:
    """Entry point of `plx lsp`: serve over stdin/stdout until the client says exit. `first` and
    `replay` come from quickstart.py (the first message, already read; its cached answer)."""
    _configure_logging(getattr(args, "log_file", None))
    server = create_server()
    server.protocol.init_replay = replay
    log.info("plx lsp %s starting (python %s)", __version__, sys.version.split()[0])
    from plxtools.lsp.transport import serve

    code = serve(server, sys.stdin.buffer, sys.stdout.buffer, first=first)
    # stdout is closed when the client says exit; later flushes must not fail on it
    for name in ("stdout", "stderr"):
        stream = getattr(sys, name)
        if stream is None or stream.closed:
            setattr(sys, name, open(os.devnull, "w"))
    return code
