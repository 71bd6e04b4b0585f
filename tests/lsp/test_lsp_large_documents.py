"""Large documents in `plx lsp`, over stdio: the size limit, memory released after a document
shrinks or closes, checks in another process that a newer version cancels, and requests on other
documents answered while a large one is checked."""

from __future__ import annotations

import time

import pytest

from tests.lsp.conftest import EXAMPLE_URI, example_text
from tests.lsp.rawclient import RawServer


def big_text(models: int) -> str:
    out = ["# generated for the large-document tests", ""]
    for i in range(models):
        out += [f"Wheel{i} is Physics3D.Bodies.RigidBody:",
                f"    inertia.mass: {10 + i}",
                "    geometry is Physics3D.Geometries.Cylinder:",
                "        radius: 0.26",
                "        height: 0.165",
                ""]
    return "\n".join(out) + "\n"


def diagnostics(s: RawServer, uri: str, version: int, timeout: float = 120) -> list[dict]:
    return s.notification("textDocument/publishDiagnostics", timeout=timeout,
                          where=lambda p: p["uri"] == uri and p.get("version") == version)["diagnostics"]


def counters(s: RawServer) -> dict:
    return s.request("plx/stats", {})["result"]["counters"]


def wait_counter(s: RawServer, name: str, at_least: int = 1, timeout: float = 60) -> dict:
    deadline = time.monotonic() + timeout
    while True:
        got = counters(s)
        if got.get(name, 0) >= at_least:
            return got
        assert time.monotonic() < deadline, f"{name} never reached {at_least}: {got}"
        time.sleep(0.05)


def trees(s: RawServer) -> list[dict]:
    return s.request("plx/memory", {})["result"]["trees"]


def test_a_document_over_the_size_limit_gets_a_message_not_an_analysis(tmp_path):
    uri = (tmp_path / "big.openplx").as_uri()
    text = big_text(40)
    assert len(text) > 2000
    s = RawServer()
    try:
        s.initialize({"window": {"showMessage": {}}}, {"diagnosticMode": "push", "maxDocumentSize": 2000})
        s.open(uri, text)
        got = diagnostics(s, uri, 1)
        assert len(got) == 1 and "maxDocumentSize" in got[0]["message"] and f"{len(text):,}" in got[0]["message"]
        assert got[0]["severity"] == 2 and "code" not in got[0]
        shown = s.notification("window/showMessage", where=lambda p: "big.openplx" in p["message"])
        assert "over the language server's limit of 2,000" in shown["message"]
        assert s.request("textDocument/hover", {"textDocument": {"uri": uri},
                                                "position": {"line": 2, "character": 2}})["result"] is None
        assert s.request("textDocument/documentSymbol", {"textDocument": {"uri": uri}})["result"] is None
        assert s.request("textDocument/formatting", {"textDocument": {"uri": uri},
                                                     "options": {"tabSize": 4, "insertSpaces": True}})["result"] is None
        assert not [t for t in trees(s) if t["chars"] == len(text)]  # never parsed
        # shrunk under the limit: analysed as usual
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                            "contentChanges": [{"text": "X is Real: 1\nY is Nonsense\n"}]})
        got = diagnostics(s, uri, 2)
        assert got and all("maxDocumentSize" not in d["message"] for d in got)
        assert any(d.get("code") for d in got)
    finally:
        s.close()


def test_a_bad_size_setting_is_reported_and_the_default_kept(tmp_path):
    uri = (tmp_path / "a.openplx").as_uri()
    s = RawServer()
    try:
        s.initialize({"window": {"showMessage": {}}}, {"diagnosticMode": "push", "maxDocumentSize": "big"})
        s.open(uri, "X is Real: 1\n")
        assert diagnostics(s, uri, 1) == []
        shown = s.notification("window/showMessage", where=lambda p: "maxDocumentSize" in p["message"])
        assert "number of characters" in shown["message"]
    finally:
        s.close()


def test_memory_of_a_document_is_released_after_it_shrinks_and_after_close(tmp_path):
    """Checked in the server's own process: once the text shrinks, no syntax tree of the big version
    is alive (not in caches, not in the collector's frozen generation); the same after close."""
    uri = (tmp_path / "big.openplx").as_uri()
    text = big_text(600)
    s = RawServer(env={"PLX_LSP_BACKGROUND_SIZE": str(1 << 40)})
    try:
        s.initialize({}, {"diagnosticMode": "push"})
        s.open(uri, text)
        diagnostics(s, uri, 1)
        assert s.request("textDocument/documentSymbol", {"textDocument": {"uri": uri}})["result"]
        # an edit in the middle: the incremental parser keeps the chunks of this version
        mid = text.count("\n") // 2
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [
            {"range": {"start": {"line": mid, "character": 0}, "end": {"line": mid, "character": 0}}, "text": "#"}]})
        diagnostics(s, uri, 2)
        assert [t for t in trees(s) if t["chars"] == len(text) + 1]
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 3},
                                            "contentChanges": [{"text": "X is Real: 1\n"}]})
        diagnostics(s, uri, 3)
        assert not [t for t in trees(s) if t["chars"] > 1000 and t["path"].endswith("big.openplx")]
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 4},
                                            "contentChanges": [{"text": text}]})
        diagnostics(s, uri, 4)
        s.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
        s.request("plx/stats", {})
        assert not [t for t in trees(s) if t["path"].endswith("big.openplx")]
    finally:
        s.close()


def test_a_newer_version_cancels_the_check_of_the_older_one(tmp_path):
    uri = (tmp_path / "big.openplx").as_uri()
    text = big_text(3000)
    s = RawServer(env={"PLX_LSP_BACKGROUND_SIZE": "10000"})
    try:
        s.initialize({}, {"diagnosticMode": "push", "maxDocumentSize": 0})
        s.open(uri, text)
        wait_counter(s, "background-started")
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                            "contentChanges": [{"text": "X is Real: 1\n"}]})
        assert diagnostics(s, uri, 2) == []
        got = counters(s)
        assert got.get("background-cancelled", 0) >= 1 and "background-finished" not in got
        # version 1's diagnostics were never sent
        assert not [m for m in s.pending if m.get("method") == "textDocument/publishDiagnostics"
                    and m["params"].get("version") == 1]
        # closing cancels too
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 3},
                                            "contentChanges": [{"text": text}]})
        wait_counter(s, "background-started", 2)
        s.notify("textDocument/didClose", {"textDocument": {"uri": uri}})
        assert wait_counter(s, "background-cancelled", 2).get("background-finished", 0) == 0
    finally:
        s.close()


def test_other_documents_are_answered_while_a_large_one_is_checked(tmp_path):
    uri = (tmp_path / "big.openplx").as_uri()
    text = big_text(6000)
    small = example_text()
    line = small[:small.index("inertia.mass")].count("\n")
    s = RawServer(env={"PLX_LSP_BACKGROUND_SIZE": "10000"})
    try:
        s.initialize({}, {"diagnosticMode": "push", "maxDocumentSize": 0})
        s.open(EXAMPLE_URI, small)
        diagnostics(s, EXAMPLE_URI, 1)
        s.open(uri, text)
        wait_counter(s, "background-started")
        for _ in range(3):
            got = s.request("textDocument/hover", {"textDocument": {"uri": EXAMPLE_URI},
                                                   "position": {"line": line, "character": 14}})
            assert got["result"] and "mass" in str(got["result"]).lower()
        assert "background-finished" not in counters(s)  # answered while the large one was being checked
        got = diagnostics(s, uri, 1, timeout=300)
        assert isinstance(got, list)
        assert counters(s).get("background-finished") == 1
    finally:
        s.close()


@pytest.mark.parametrize("mode", ["pull"])
def test_a_pull_for_an_older_version_is_cancelled_with_retrigger(tmp_path, mode):
    uri = (tmp_path / "big.openplx").as_uri()
    text = big_text(3000)
    s = RawServer(env={"PLX_LSP_BACKGROUND_SIZE": "10000"})
    try:
        s.initialize({"textDocument": {"diagnostic": {}}}, {"diagnosticMode": mode, "maxDocumentSize": 0})
        s.open(uri, text)
        msg_id, data = s.request_bytes("textDocument/diagnostic", {"textDocument": {"uri": uri}})
        s.write(data)
        wait_counter(s, "background-started")
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                            "contentChanges": [{"text": "X is Real: 1\n"}]})
        got = s.response(msg_id, timeout=60)
        assert got["error"]["code"] == -32802 and got["error"]["data"] == {"retriggerRequest": True}
        again = s.request("textDocument/diagnostic", {"textDocument": {"uri": uri}})
        assert again["result"]["kind"] == "full" and again["result"]["items"] == []
    finally:
        s.close()
