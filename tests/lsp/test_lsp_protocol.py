"""Every request gets an answer, bad frames do not deafen the server, cancellation is honoured,
and routine events are not logged as errors (issue 14 items 3, 11, 12; issue 16 log noise)."""

from __future__ import annotations

import json

import pytest

from tests.lsp.rawclient import RawServer, frame

URI = "file:///proto/doc.openplx"
TEXT = "Scene is Physics3D.System:\n    x is Real: 1\n"


@pytest.fixture(scope="module")
def server():
    s = RawServer()
    pre = s.request("textDocument/hover", {"textDocument": {"uri": URI}, "position": {"line": 0, "character": 0}})
    s.pre_init = pre
    s.initialize()
    s.open(URI, TEXT)
    yield s
    assert s.close() == 0
    assert not [line for line in s.stderr if b"ERROR" in line or b"Traceback" in line], s.stderr


def hover(s: RawServer, line=1, character=4) -> dict:
    return s.request("textDocument/hover", {"textDocument": {"uri": URI},
                                            "position": {"line": line, "character": character}})


def test_request_before_initialize_is_refused_with_32002(server):
    assert server.pre_init["error"]["code"] == -32002


@pytest.mark.parametrize("params", [
    {"textDocument": {"uri": URI}, "position": {"line": -1, "character": 0}},
    {"textDocument": {"uri": URI}, "position": {"line": 2 ** 32, "character": 0}},
    {"textDocument": {"uri": URI}, "position": {"line": 0, "character": -3}},
    {},
    {"textDocument": {"uri": 5}, "position": {"line": "a", "character": 0}},
    [1, 2],
    None,
])
def test_invalid_params_get_32602_and_the_server_keeps_serving(server, params):
    got = server.request("textDocument/hover", params)
    assert got["error"]["code"] == -32602, got
    assert "textDocument/hover" in got["error"]["message"]
    ok = hover(server)
    assert "error" not in ok and "Real" in json.dumps(ok["result"])


def test_unknown_method_gets_32601(server):
    assert server.request("plx/noSuchThing", {})["error"]["code"] == -32601


def test_second_initialize_is_refused(server):
    got = server.request("initialize", {"processId": None, "capabilities": {}})
    assert got["error"]["code"] == -32600


def test_content_length_shorter_than_the_body_does_not_deafen_the_server(server):
    body = json.dumps({"jsonrpc": "2.0", "id": 77, "method": "textDocument/hover",
                       "params": {"textDocument": {"uri": URI}, "position": {"line": 1, "character": 4}}}).encode()
    server.write(b"Content-Length: %d\r\n\r\n" % (len(body) - 10) + body)
    assert "Real" in json.dumps(hover(server)["result"])
    # a Content-Length longer than what follows eats the next frame, then the server resynchronises
    server.write(b"Content-Length: 5\r\n\r\n{}")
    server.write(frame({"jsonrpc": "2.0", "method": "$/noop"}))
    assert "Real" in json.dumps(hover(server)["result"])


def test_queued_and_running_requests_are_cancelled():
    s = RawServer()
    try:
        s.initialize(options={"diagnosticMode": "push"})
        uri = "file:///proto/big.openplx"
        big = "".join(f"M{i} is Physics3D.System:\n    x is Real: {i}\n    y is Real: x * 2\n" for i in range(3000))
        s.open(uri, big)
        # one write: a slow request, its cancel, then a queue of requests each cancelled at once
        slow_id, data = s.request_bytes("textDocument/documentSymbol", {"textDocument": {"uri": uri}})
        data += frame({"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": slow_id}})
        ids = []
        for i in range(200):
            rid, req = s.request_bytes("textDocument/hover", {"textDocument": {"uri": uri},
                                                              "position": {"line": i, "character": 0}})
            ids.append(rid)
            data += req + frame({"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": rid}})
        # cancels for ids that were answered long ago or never existed: routine, not errors
        for i in range(20):
            data += frame({"jsonrpc": "2.0", "method": "$/cancelRequest", "params": {"id": 10 ** 6 + i}})
        s.write(data)
        assert s.response(slow_id, timeout=120)["error"]["code"] == -32800
        codes = [s.response(i)["error"]["code"] for i in ids]
        assert codes == [-32800] * len(ids)
        # not cancelled: answered normally
        got = s.request("textDocument/documentSymbol", {"textDocument": {"uri": uri}}, timeout=120)
        assert len(got["result"]) == 9000  # flat: each model and its two attributes
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    assert not [line for line in s.stderr if b"ERROR" in line or b"Traceback" in line], s.stderr


def test_editor_quitting_right_after_open_leaves_no_traceback():
    """The editor goes away while diagnostics are on their way: the server exits quietly.

    No reader thread here: closing a pipe another thread is blocked reading would deadlock the test."""
    import subprocess
    import sys
    import time

    proc = subprocess.Popen([sys.executable, "-m", "plxtools", "lsp"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        proc.stdin.write(frame({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                                "params": {"processId": None, "rootUri": None, "capabilities": {},
                                           "initializationOptions": {"diagnosticMode": "push"}}}))
        proc.stdin.flush()
        header = b""
        while not header.endswith(b"\r\n\r\n"):
            header += proc.stdout.read(1)
        proc.stdout.read(int(header.split(b"Content-Length:")[1].split(b"\r\n")[0]))
        proc.stdin.write(frame({"jsonrpc": "2.0", "method": "initialized", "params": {}}))
        proc.stdin.write(frame({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
            "uri": URI, "languageId": "openplx", "version": 1, "text": TEXT}}}))
        proc.stdin.flush()
        time.sleep(0.5)
        proc.stdout.close()  # the editor is gone: the diagnostics cannot be written
        proc.stdin.close()
        assert proc.wait(timeout=60) in (0, 1)
        err = proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
    assert b"Traceback" not in err and b"BrokenPipe" not in err, err


def test_malformed_messages_are_answered_or_ignored(server):
    junk = [
        b"{this is not json", b"[]", b"42", b'"x"', b"null",
        json.dumps({"id": 5, "method": "textDocument/hover"}).encode(),  # no jsonrpc
        json.dumps({"jsonrpc": "2.0", "id": 6, "method": 12}).encode(),
        json.dumps({"jsonrpc": "2.0", "id": [1], "method": "textDocument/hover"}).encode(),
        json.dumps({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {"x": 1}}).encode(),
        json.dumps({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": []}).encode(),
        json.dumps({"jsonrpc": "2.0", "id": 99999, "result": {"unexpected": True}}).encode(),
        "Content-Length: x\r\n\r\n".encode(),
        b"\xff\xfe garbage \r\n\r\n",
    ]
    for j in junk:
        server.write(frame(j))
    invalid = server.request("textDocument/completion", {"textDocument": {"uri": URI}})
    assert invalid["error"]["code"] == -32602
    assert "Real" in json.dumps(hover(server)["result"])


def test_signature_help_names_the_active_parameter_inside_the_signature(server):
    """LSP 3.18 reads `activeParameter: null` inside a signature as "no parameter active"."""
    uri = "file:///proto/sig.openplx"
    text = "S is Physics3D.System:\n    q is Math.Quat: Math.Quat.angle_axis(Math.PI / 4, \n"
    server.open(uri, text)
    res = server.request("textDocument/signatureHelp", {"textDocument": {"uri": uri},
                                                        "position": {"line": 1, "character": len(text.splitlines()[1])}})
    result = res["result"]
    assert result["activeParameter"] == 1
    assert [sig["activeParameter"] for sig in result["signatures"]][result.get("activeSignature", 0)] == 1


def test_refusing_to_rename_an_official_name_is_an_answer_not_an_error_in_the_log(server):
    """The fixture's teardown checks the whole log: no ERROR line and no traceback."""
    uri = "file:///proto/rename.openplx"
    server.open(uri, "S is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n")
    got = server.request("textDocument/rename", {"textDocument": {"uri": uri},
                                                 "position": {"line": 1, "character": 33}, "newName": "X"})
    assert got["error"]["code"] == -32803 and "official bundle" in got["error"]["message"]
    server.notify("$/cancelRequest", {"id": 424242})  # a routine cancel of a request already answered
    assert "Real" in json.dumps(hover(server)["result"])


def test_document_versions_going_backwards_are_logged_as_a_warning():
    s = RawServer()
    try:
        s.initialize(options={"diagnosticMode": "push"})
        s.open(URI, TEXT, version=5)
        edit = {"range": {"start": {"line": 1, "character": 15}, "end": {"line": 1, "character": 16}}, "text": "2"}
        s.notify("textDocument/didChange", {"textDocument": {"uri": URI, "version": 3}, "contentChanges": [edit]})
        assert "Real" in json.dumps(hover(s)["result"])  # the server goes on
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    log = b"".join(s.stderr).decode()
    assert "went from 5 to 3" in log and "WARNING" in log, log
