"""`plx lsp`: the OpenPLX language server (pygls glue only).

Every feature is a call into `plxtools.ide` (offsets in, data out); the handlers (`handlers/`, one
module per group of features) convert positions (`convert.Positions`, the one place that knows the
client's encoding) and shape LSP objects to the client's capabilities. This module holds the
server's state: the open documents handed to the analysis host, position conversions, client
capabilities and settings; `publishing.py` turns checks into published diagnostics. When checks
run, large documents checked in another process and the garbage collector's policy are
`plxtools.ide.runtime`. The wire (framing, validation, cancellation) is `transport.py` and
`protocol.py`; the text model is `convert.py` plus `documents.py`.
"""

from __future__ import annotations

import asyncio
import logging
import os
import sys

from lsprotocol import types
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from plxtools import __version__
from plxtools.ide.host import AnalysisHost
from plxtools.ide.migrate_action import Migrations
from plxtools.ide.runtime import settings as editor_settings
from plxtools.ide.runtime.background import BACKGROUND_SIZE, BackgroundChecks
from plxtools.ide.runtime.collector import reload_model
from plxtools.ide.runtime.scheduler import CheckQueue
from plxtools.ide.runtime.stats import Stats
from plxtools.lsp.convert import Positions
from plxtools.lsp.documents import Documents
from plxtools.lsp.protocol import PlxProtocol
from plxtools.lsp.publishing import Publishing
from plxtools.lsp.transport import Dispatcher
from plxtools.lsp.transport import serve

log = logging.getLogger("plxtools.lsp")

MAX_DOCUMENT_SIZE = editor_settings.MAX_DOCUMENT_SIZE


class PlxServer(Publishing, LanguageServer):
    def __init__(self, host: AnalysisHost | None = None) -> None:
        super().__init__("plx", __version__, protocol_cls=PlxProtocol,
                         text_document_sync_kind=types.TextDocumentSyncKind.Incremental)

        self.host = host or AnalysisHost()  # early.py hands over the one it loaded the bundles into
        self.documents = Documents()
        self.dispatcher = Dispatcher(self)
        self.loop: asyncio.AbstractEventLoop | None = None
        self.writer = None
        self.rule_docs_url: str | None = None
        self.init_options: dict = {}
        self.diagnostic_mode = "auto"
        self.pull_diagnostics = False  # decided in `initialize` (client support and `diagnosticMode`)
        self.uris: dict[str, str] = {}  # path -> the client's URI for open documents
        self._published: dict[str, tuple] = {}  # uri -> (version, diagnostics) last pushed
        self._positions: dict[str, Positions] = {}
        self._completion_keys: list = []
        self._shown: set[str] = set()
        self.stats = Stats()  # recent timings (wall ms, CPU ms) per kind, background-check counters
        self.max_document_size = MAX_DOCUMENT_SIZE  # characters; 0: no limit (setting maxDocumentSize)
        self.background_size = int(os.environ.get("PLX_LSP_BACKGROUND_SIZE") or BACKGROUND_SIZE)
        # uri -> the forked check running for it
        self.background = BackgroundChecks(self.stats, self._decode_diagnostics, self._background_done,
                                           self._background_failed)
        # documents waiting for a check (uri -> cascade), oldest first
        self.checks = CheckQueue(self._check_one, self._parse_ahead,
                                 lambda: self.dispatcher.inbox > 0 or self.dispatcher.prompt > 0,
                                 lambda: self.warming is not None, lambda: self.loop)
        self.migrations = Migrations()  # "migrate this file", once per version of the text
        # set while `initialized` loads the bundles in a thread (issue 32.12): completion waits for
        # the load and is answered before the first checks (issue 40.1), checks wait for the load,
        # and a request that needs the model (hover, go-to) waits for it (the host's lock) rather
        # than loading it twice
        self.warming: asyncio.Future | None = None
        self.registering: asyncio.Future | None = None  # the file watchers' registration, not waited for

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

    # -------------------------------------------------------------- settings

    def apply_settings(self, raw: dict | None) -> None:
        """The editor's settings over the initialization options (`ide.runtime.settings`)."""
        got = editor_settings.read(editor_settings.merge(self.init_options, raw), self.host.root)
        self.diagnostic_mode = got.diagnostic_mode
        self.host.messages.extend(got.messages)
        self.max_document_size = got.max_document_size
        self.rule_docs_url = got.rule_docs_url
        if self.host.configure(got.analysis):  # a new bundle path: the old model is garbage now
            reload_model(self.host)


def _plain(markdown: str) -> str:
    return markdown.replace("```openplx\n", "").replace("```\n", "").replace("```", "")


def create_server(host: AnalysisHost | None = None) -> PlxServer:
    from plxtools.lsp.handlers import register_all

    server = PlxServer(host)
    register_all(server)
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


def run_server(args, first=None, replay=None, early=None) -> int:
    """Entry point of `plx lsp`: serve over stdin/stdout until the client says exit. `first` and
    `replay` come from quickstart.py (the first message, already read; its cached answer); `early`
    is early.py's hand-over (the loaded host, the messages it kept, its queue of frames)."""
    _configure_logging(getattr(args, "log_file", None))
    server = create_server(early.host if early is not None else None)
    server.protocol.init_replay = replay
    log.info("plx lsp %s starting (python %s)", __version__, sys.version.split()[0])

    if early is not None:
        server._completion_keys = early.completion_keys
        log.info("answered %d request(s) and pushed diagnostics %d time(s) before the server loaded",
                 early.answered, early.pushed)
        code = serve(server, sys.stdin.buffer, sys.stdout.buffer, first=[first, *early.kept],
                     next_body=early.next_body, writer=early.writer)
    else:
        code = serve(server, sys.stdin.buffer, sys.stdout.buffer, first=first)
    # stdout is closed when the client says exit; later flushes must not fail on it
    for name in ("stdout", "stderr"):
        stream = getattr(sys, name)
        if stream is None or stream.closed:
            setattr(sys, name, open(os.devnull, "w"))
    return code
