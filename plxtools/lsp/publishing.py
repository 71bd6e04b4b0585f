"""From checks to the editor: LSP diagnostics, pushed once per version (or pulled), the size limit's
message, the forked check of a large document wired to the protocol, and the re-check of documents
that depend on a changed one.

`Publishing` is a part of `PlxServer` (server.py); when a check runs is decided by
`ide.runtime.scheduler.CheckQueue`, a check apart by `ide.runtime.background`.
"""

from __future__ import annotations

import logging
import time

from lsprotocol import types

from plxtools.diagnostics import Diagnostic, Severity
from plxtools.ide.runtime.background import BackgroundCheck, checked_apart
from plxtools.ide.runtime.collector import no_gc
from plxtools.lsp import diagnostic_fields as fields
from plxtools.lsp import watching
from plxtools.lsp.convert import Positions

log = logging.getLogger("plxtools.lsp")

SEVERITY = {Severity.ERROR: types.DiagnosticSeverity.Error, Severity.WARNING: types.DiagnosticSeverity.Warning,
            Severity.INFO: types.DiagnosticSeverity.Information}


class Publishing:
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
        """A large loose document is checked in a forked process (ide.runtime.background)."""
        return checked_apart(self.host, self.path_of(uri), doc.text, self.background_size, self.loop)

    def start_background(self, uri: str, doc) -> BackgroundCheck:
        def check() -> dict:  # in the child
            got = self.diagnostics_of(uri, background=False)
            diags = got[1] if got is not None else []
            return {"diagnostics": self.protocol._converter.unstructure(diags),
                    "timing": self.stats.timings.get("check", [[0, 0]])[-1]}

        return self.background.start(uri, doc.version, doc.text, self.loop, check)

    def cancel_background(self, uri: str) -> None:
        self.background.cancel(uri)

    def _decode_diagnostics(self, raw) -> list[types.Diagnostic]:
        return self.protocol._converter.structure(raw, list[types.Diagnostic])

    def _background_failed(self, bg: BackgroundCheck) -> None:
        doc = self.documents.get(bg.uri)
        if doc is not None and doc.text is bg.text:
            bg.fallback = True
            self._check_one(bg.uri, False, background=False)

    def _background_done(self, bg: BackgroundCheck, diags: list[types.Diagnostic]) -> None:
        doc = self.documents.get(bg.uri)
        if doc is None or doc.text is not bg.text:
            bg.settle(None)
            return  # superseded (normally cancelled before it got here)
        bg.settle((bg.version, diags))
        if not self.pull_diagnostics:
            self._push(bg.uri, bg.version, diags)
        self.notify_messages()
        if not self.host.analysed(self.path_of(bg.uri)):
            # the server's own analysis, made once after the first answer: the next edits re-use it
            self.loop.call_soon(self._check_one, bg.uri, False, False)

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
        out = types.Diagnostic(range=pos.range(d.span), message=fields.message(d), severity=SEVERITY[d.severity],
                               code=d.code, source="plx")
        href = fields.docs_href(d, self.rule_docs_url)
        if href and self.cap("text_document.publish_diagnostics.code_description_support"):
            out.code_description = types.CodeDescription(href=href)
        tags = [types.DiagnosticTag(t) for t in fields.tags(d)]
        if tags and self.cap("text_document.publish_diagnostics.tag_support"):
            out.tags = tags
        if d.related and self.cap("text_document.publish_diagnostics.related_information"):
            rel = []
            for file, span, msg in d.related:
                p = file or ""
                rel.append(types.DiagnosticRelatedInformation(
                    location=types.Location(uri=self.uri_of(p), range=self.positions(p).range(span)), message=msg))
            out.related_information = rel
        out.data = fields.fix_data(d)
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
            bg = self.background.get(uri)
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
            self.stats.record("check", t0, c0)
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
            return  # a large document: its check runs in another process (_background_done)
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

    # -------------------------------------------------------------- what to check

    def schedule(self, uri: str, delay: float | None = None, cascade: bool = True) -> None:
        """Queue a document for checking (ide.runtime.scheduler: no fixed delay, messages first)."""
        if self.documents.get(uri) is None:
            return
        self.checks.add(uri, cascade)

    def _parse_ahead(self, uri: str) -> bool:
        """The first half of a check (the scheduler handles waiting messages before the analysis)."""
        doc = self.documents.get(uri)
        if doc is None or self.too_big(doc) or self.in_background(uri, doc):
            return False
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            with no_gc():
                done = self.host.parse_ahead(self.sync(uri) or self.path_of(uri))
            if done:
                self.stats.record("parse", t0, c0)
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
            if dep_uri not in self.checks:
                self.schedule(dep_uri, cascade=False)

    def recheck_all(self) -> None:
        if self.pull_diagnostics:
            if self.cap("workspace.diagnostics.refresh_support"):
                self.workspace_diagnostic_refresh(None)
            return
        for uri in list(self.documents):
            self.schedule(uri, cascade=False)
