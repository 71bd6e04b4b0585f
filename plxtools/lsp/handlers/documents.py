"""Documents and their diagnostics: open, change, close and save, pull diagnostics
(`textDocument/diagnostic`), and files changed on disk (`workspace/didChangeWatchedFiles`)."""

from __future__ import annotations

import asyncio
import os
from typing import TYPE_CHECKING

from lsprotocol import types

from plxtools.ide.runtime.background import BackgroundCheck
from plxtools.ide.runtime.collector import reload_model
from plxtools.lsp import watching
from plxtools.lsp.handlers import CONFIG_FILES
from plxtools.lsp.protocol import ServerCancelled

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer


def register(server, server_feature) -> None:
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
        ls.checks.discard(uri)
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
        ls.checks.discard(uri)
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
            reload_model(ls.host)
            ls.notify_messages()
        if changed:
            ls.recheck_all()
