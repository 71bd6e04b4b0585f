"""The wire side of the server that pygls leaves open: the server's own text model (`Documents`)
fed before the handlers run, quiet writes, the cached first `initialize` reply (quickstart.py),
and cancellation of requests that were running when the client cancelled them; plus LSP's two
request errors the handlers raise."""

from __future__ import annotations

import logging

from lsprotocol import types
from pygls.exceptions import JsonRpcException
from pygls.protocol import LanguageServerProtocol
from pygls.protocol.language_server import lsp_method

log = logging.getLogger("plxtools.lsp")


class RequestFailed(JsonRpcException):
    """LSP's RequestFailed (-32803): the request was valid but cannot be answered."""

    CODE = -32803


class ServerCancelled(JsonRpcException):
    """LSP's ServerCancelled (-32802): the server dropped the request (a newer version arrived)."""

    CODE = -32802


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
