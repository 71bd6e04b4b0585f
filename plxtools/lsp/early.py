"""`plx lsp` before pygls: completion answered while pygls and lsprotocol load (issue 40.1).

Importing them costs about 0.7 s of CPU (lsprotocol builds some 570 attrs classes), far more than
loading the bundles' program from plx's cache (~0.1 s) and a completion (~20 ms) together, and an
editor opens a file and may ask for completion within that time. So, once `initialize` has been
answered from the cache (quickstart.py), the frames that follow are read into a queue; the bundles
are loaded into the analysis host the server will use, then pygls is imported on a thread while
completion requests on documents opened meanwhile are answered here, through the same function as
the server's handler (`ide.complete`, `completion_items`). Every other message waits, in order, and
is handed to the server with the host; an answered request is not handed on.

The workspace's settings are asked for here as the server will ask for them (`workspace/
configuration`), and a completion waits for them: the answer must be the one the server would give.
Imports nothing of pygls but `pygls.uris` (no lsprotocol).
"""

from __future__ import annotations

import json
import logging
import os
import queue
import threading

from plxtools.lsp.transport import FrameReader, Writer

log = logging.getLogger("plxtools.lsp")

CONFIG_ID = "plx-early-configuration"
ANSWERED = ("textDocument/completion", "textDocument/diagnostic")  # the requests this phase may answer
EARLY_SIZE = 200_000  # characters: a larger document waits for the server (which checks it in a forked process)


class _Range:
    __slots__ = ("start", "end")

    def __init__(self, raw: dict):
        self.start = _Pos(raw["start"])
        self.end = _Pos(raw["end"])


class _Pos:
    __slots__ = ("line", "character")

    def __init__(self, raw: dict):
        self.line = int(raw["line"])
        self.character = int(raw["character"])


class _Change:
    """A raw `contentChanges` entry in the shape `convert.apply_change` reads."""

    __slots__ = ("range", "text")

    def __init__(self, raw: dict):
        self.text = raw["text"]
        self.range = _Range(raw["range"]) if raw.get("range") is not None else None
        if not isinstance(self.text, str):
            raise TypeError("change text")


class Early:
    """The phase between the cached `initialize` reply and the real server (see the module doc)."""

    def __init__(self, init: dict, reply: dict, stdin, stdout) -> None:
        params = init.get("params") if isinstance(init.get("params"), dict) else {}
        caps = params.get("capabilities") if isinstance(params.get("capabilities"), dict) else {}
        self.caps = caps
        self.params = params
        server_caps = reply.get("capabilities") if isinstance(reply, dict) else None
        enc = server_caps.get("positionEncoding") if isinstance(server_caps, dict) else None
        self.encoding = enc if enc in ("utf-8", "utf-16", "utf-32") else "utf-16"
        self.frames: queue.Queue = queue.Queue()
        self.writer = Writer(stdout)
        self.kept: list[bytes] = []  # bodies for the server, in arrival order
        self.completion_keys: list = []
        self.answered = 0  # requests answered here (completion, pulled diagnostics)
        self.pushed = 0  # diagnostics pushed here
        self.docs: dict[str, list] = {}  # uri -> [text, version, path]; None text: lost track (wait)
        self.host = None
        self.config_pending = False
        self.waiting: list = []  # (body, completion request, its document's text) until the settings come
        self.init_options: dict = {}
        self.max_size = 0  # the maxDocumentSize setting (0: no limit)
        self.settings = None
        self.published: dict[str, object] = {}  # uri -> the text whose diagnostics were pushed
        self.pushing = True  # False after a failure: the server pushes them
        self.ended = False
        self.imported = threading.Event()  # the server's modules are loaded (set at once if never started)
        self.import_started = False
        threading.Thread(target=self._read, args=(stdin,), name="plx-lsp-reader", daemon=True).start()

    # ------------------------------------------------------------------ frames

    def _read(self, stdin) -> None:
        reader = FrameReader(stdin)
        try:
            while True:
                body = reader.next_body()
                self.frames.put(body)
                if body is None:
                    return
        except (OSError, ValueError) as exc:
            log.info("input closed: %s", exc)
            self.frames.put(None)

    def next_body(self):
        """The server's source of frames after the hand-over (the reader thread keeps filling it)."""
        return self.frames.get()

    def _send(self, msg: dict) -> None:
        data = json.dumps(msg).encode("utf-8")
        self.writer.write(b"Content-Length: %d\r\n\r\n" % len(data) + data)

    # ------------------------------------------------------------------ the phase

    def run(self) -> None:
        """The phase; never raises: on a failure here the server starts with its own host, and
        whatever was not answered goes to it (what was is not sent twice)."""
        try:
            self._run()
        except Exception:  # noqa: BLE001 - the server must start whatever happened here
            log.exception("the early phase failed; the server answers everything")
            self.host, self.completion_keys = None, []
            if self.import_started:
                self.imported.wait()

    def _run(self) -> None:
        """Load the bundles, then answer completions until the server's modules are imported."""
        from plxtools import ide  # noqa: F401 - before the import thread starts: no waiting on its locks
        from plxtools.ide.runtime import settings as editor_settings
        from plxtools.ide.runtime import collector  # noqa: F401
        from plxtools.lsp import completion_items, convert  # noqa: F401

        host, got, self.init_options = host_for(self.params)
        self.settings = got
        self.max_size = got.max_document_size
        self.host = host
        workspace = self.caps.get("workspace")
        if isinstance(workspace, dict) and workspace.get("configuration"):
            # as the server's `initialized` will: the answer may choose other bundles
            self.config_pending = True
            self._send({"jsonrpc": "2.0", "id": CONFIG_ID, "method": "workspace/configuration",
                        "params": {"items": [{"section": editor_settings.CONFIG_SECTION}]}})
        _ = host.workspace
        loaded = self.imported

        def load_server() -> None:
            try:
                import plxtools.lsp.handlers.editing  # noqa: F401 - pygls, lsprotocol and the handlers
                import plxtools.lsp.server  # noqa: F401
            except BaseException:  # noqa: BLE001 - run_server imports them again and fails there, loudly
                pass
            finally:
                loaded.set()

        threading.Thread(target=load_server, name="plx-lsp-import", daemon=True).start()
        self.import_started = True
        while not self.ended:
            try:
                body = self.frames.get(timeout=0.01)
            except queue.Empty:
                if loaded.is_set():
                    break
                try:
                    self._push_diagnostics()
                except Exception:  # noqa: BLE001 - the server pushes them after its check
                    log.exception("early phase: diagnostics left to the server")
                    self.pushing = False
                continue
            if body is None:
                self.ended = True
                self.frames.put(None)  # the end of input, for the server to see after the rest
                break
            self._take(body)
        loaded.wait()
        for uri, (_text, _version, path) in self.docs.items():
            if path is not None:
                host.close_document(path)  # the server opens it again from the didOpen it is handed

    def _take(self, body: bytes) -> None:
        try:
            msg = json.loads(body)
        except (ValueError, UnicodeDecodeError):
            msg = None
        if not isinstance(msg, dict):
            self.kept.append(body)
            return
        method = msg.get("method")
        if method is None and msg.get("id") == CONFIG_ID:
            self._configured(msg.get("result"))
            return
        self.kept.append(body)
        try:
            if method == "textDocument/didOpen":
                doc = msg["params"]["textDocument"]
                if isinstance(doc["text"], str):
                    self.docs[doc["uri"]] = [doc["text"], doc.get("version"), None]
            elif method == "textDocument/didChange":
                self._changed(msg["params"])
            elif method == "textDocument/didClose":
                self._closed(msg["params"]["textDocument"]["uri"])
            elif method in ANSWERED and "id" in msg:
                if self.config_pending:
                    doc = self.docs.get(msg["params"]["textDocument"]["uri"])
                    if doc is not None:  # answered when the settings come, if the text is still the same
                        self.waiting.append((body, msg, doc[0]))
                elif self._answer(msg):
                    self.kept.pop()
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            log.info("early phase: %s left to the server (%s)", method, exc)
        except Exception:  # noqa: BLE001 - a failing analysis here: the server answers, and logs its own
            log.exception("early phase: %s left to the server", method)

    def _configured(self, result) -> None:
        from plxtools.ide.runtime import settings as editor_settings
        from plxtools.ide.runtime.collector import reload_model

        self.config_pending = False
        raw = editor_settings.section(result[0]) if isinstance(result, list) and result and isinstance(result[0], dict) else None
        got = editor_settings.read(editor_settings.merge(self.init_options, raw), self.host.root)
        self.settings = got
        self.max_size = got.max_document_size
        if self.host.configure(got.analysis):
            reload_model(self.host)
        waiting, self.waiting = self.waiting, []
        for body, msg, text in waiting:
            doc = self.docs.get(msg["params"]["textDocument"]["uri"])
            if doc is not None and doc[0] is text and self._answer(msg):
                self.kept[:] = [k for k in self.kept if k is not body]

    def _changed(self, params: dict) -> None:
        from plxtools.lsp.convert import apply_change

        uri = params["textDocument"]["uri"]
        doc = self.docs.get(uri)
        if doc is None or doc[0] is None:
            return
        try:
            text = doc[0]
            for raw in params["contentChanges"]:
                text = apply_change(text, _Change(raw), self.encoding)
        except (KeyError, TypeError, ValueError):
            doc[0] = None  # lost track: the server will answer for this document
            raise
        doc[0], doc[1] = text, params["textDocument"].get("version")

    def _closed(self, uri: str) -> None:
        doc = self.docs.pop(uri, None)
        if doc is not None and doc[2] is not None:
            self.host.close_document(doc[2])

    # ------------------------------------------------------------------ first diagnostics

    def _pulls(self) -> bool:
        """The server's choice in `initialize`: pull when the client can and the setting allows."""
        text_caps = self.caps.get("textDocument")
        can = isinstance(text_caps, dict) and text_caps.get("diagnostic") is not None
        return can and self.settings is not None and self.settings.diagnostic_mode != "push"

    def _ready(self, uri: str):
        """(text, version, path) of an open document this phase may analyse, else None."""
        doc = self.docs.get(uri)
        if self.config_pending or self.settings is None or doc is None or doc[0] is None:
            return None
        if len(doc[0]) > EARLY_SIZE or (self.max_size and len(doc[0]) > self.max_size):
            return None
        text, version, path = doc
        if path is None:
            path = doc[2] = _path_of(uri)
            self.host.open_document(path, text, version)
        elif self.host.docs[path].text is not text:
            self.host.update_document(path, text, version)
        return text, version, path

    def _push_diagnostics(self) -> None:
        """The first diagnostics of the documents opened meanwhile, pushed as the server will push them
        (it sends them again after its own check: the same, so the editor shows no change)."""
        if self._pulls() or not self.pushing:
            return
        for uri in list(self.docs):
            got = self._ready(uri)
            if got is None or self.published.get(uri) is got[0] or not self.frames.empty():
                continue
            text, version, path = got
            params = {"uri": uri, "diagnostics": self._diagnostics(uri, path)}
            if version is not None:
                params["version"] = version
            self._send({"jsonrpc": "2.0", "method": "textDocument/publishDiagnostics", "params": params})
            self.published[uri] = text
            self.pushed += 1

    def _pull(self, msg: dict) -> bool:
        if not self._pulls() or not isinstance(msg["id"], (int, str)) or isinstance(msg["id"], bool):
            return False
        uri = msg["params"]["textDocument"]["uri"]
        got = self._ready(uri)
        if got is None:
            return False
        items = self._diagnostics(uri, got[2])
        self._send({"jsonrpc": "2.0", "id": msg["id"], "result": {
            "kind": "full", "resultId": f"early:{got[1]}", "items": items}})
        self.answered += 1
        return True

    def _diagnostics(self, uri: str, path: str) -> list[dict]:
        """The document's check as LSP JSON, field for field what `Publishing.lsp_diagnostic` gives."""
        from plxtools.ide.runtime.collector import no_gc
        from plxtools.lsp import diagnostic_fields as fields
        from plxtools.lsp.convert import Positions

        with no_gc():
            st = self.host.state(path)
        if st is None:
            return []
        pos = Positions(st.tree.text, self.encoding, st.tree.index)
        published = self.caps.get("textDocument", {}).get("publishDiagnostics") or {}
        out = []
        for d in st.diagnostics:
            item = {"range": _span_range(pos, d.span), "message": fields.message(d),
                    "severity": fields.SEVERITY[d.severity.value], "code": d.code, "source": "plx"}
            href = fields.docs_href(d, self.settings.rule_docs_url)
            if href and published.get("codeDescriptionSupport"):
                item["codeDescription"] = {"href": href}
            tags = fields.tags(d)
            if tags and published.get("tagSupport"):
                item["tags"] = tags
            if d.related and published.get("relatedInformation"):
                item["relatedInformation"] = [
                    {"location": {"uri": self._uri_of(file or "", uri, path),
                                  "range": _span_range(self._positions_of(file or "", path, pos), span)},
                     "message": msg} for file, span, msg in d.related]
            data = fields.fix_data(d)
            if data is not None:
                item["data"] = data
            out.append(item)
        return out

    def _uri_of(self, file: str, uri: str, path: str) -> str:
        if file == path:
            return uri
        for u, (_t, _v, p) in self.docs.items():
            if p == file:
                return u
        if os.path.isabs(file):
            from pygls.uris import from_fs_path

            return from_fs_path(file) or file
        return file

    def _positions_of(self, file: str, path: str, own):
        from plxtools.lsp.convert import Positions

        if file == path:
            return own
        tree = self.host.tree_of(file)
        if tree is not None:
            return Positions(tree.text, self.encoding, tree.index)
        return Positions(self.host.text_of(file) or "", self.encoding)

    def _answer(self, msg: dict) -> bool:
        if msg["method"] == "textDocument/diagnostic":
            return self._pull(msg)
        return self._complete(msg)

    def _complete(self, msg: dict) -> bool:
        """Answer a completion request here; False: leave it to the server."""
        from plxtools import ide
        from plxtools.ide.runtime.collector import no_gc
        from plxtools.lsp import completion_items
        from plxtools.lsp.convert import Positions

        params = msg["params"]
        if not isinstance(msg["id"], (int, str)) or isinstance(msg["id"], bool):
            return False
        got = self._ready(params["textDocument"]["uri"])
        if got is None:
            return False
        path = got[2]
        position = params["position"]
        ctx = params.get("context")
        trigger = ctx.get("triggerCharacter") if isinstance(ctx, dict) and ctx.get("triggerKind") == 2 else None
        with no_gc():
            st = self.host.quick_state(path)
        if st is None:
            return False
        pos = Positions(st.tree.text, self.encoding, st.tree.index)
        offset = pos.offset_at(int(position["line"]), int(position["character"]))
        res = ide.complete(st, offset, trigger)
        completion = self.caps.get("textDocument", {}).get("completion") or {}
        keys: list = []
        answer = completion_items.completion_list(
            res, completion_items.lsp_range(pos, res.replace_start, offset),
            completion_items.options_from(completion.get("completionItem")), keys,
            lambda key: ide.completion_documentation(st.program, key))
        self.completion_keys = keys
        self._send({"jsonrpc": "2.0", "id": msg["id"], "result": answer})
        self.answered += 1
        return True


def host_for(params: dict):
    """(analysis host, editor settings, initialization options) as the server's `initialize`
    handler sets them up from the request's params (no bundles loaded yet)."""
    from plxtools.ide.host import AnalysisHost
    from plxtools.ide.runtime import settings as editor_settings

    init_options = editor_settings.section(params.get("initializationOptions")) or {}
    host = AnalysisHost()
    host.root = _root_of(params)
    got = editor_settings.read(editor_settings.merge(init_options, None), host.root)
    host.configure(got.analysis)
    return host, got, init_options


def _span_range(pos, span) -> dict:
    from plxtools.lsp.completion_items import lsp_range

    return lsp_range(pos, span.start.offset, span.end.offset)


def _root_of(params: dict) -> str | None:
    """The workspace folder as the server's `initialize` handler reads it."""
    if params.get("rootUri"):
        return _path_of(params["rootUri"])
    folders = params.get("workspaceFolders")
    if isinstance(folders, list) and folders and isinstance(folders[0], dict) and folders[0].get("uri"):
        return _path_of(folders[0]["uri"])
    return params.get("rootPath") or None


def _path_of(uri: str) -> str:
    from pygls.uris import to_fs_path

    if uri.startswith("file:"):
        fs = to_fs_path(uri)
        if fs:
            return os.path.realpath(fs)
    return uri
