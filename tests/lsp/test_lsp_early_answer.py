"""Issue 40.1: on a warm start (the `initialize` reply in plx's cache) a completion asked for right
after opening is answered before pygls and lsprotocol have loaded (lsp/early.py), and that answer is
the one the server gives to the same request once it runs; typing before the request is seen, and
the early items resolve their documentation through the server."""

from __future__ import annotations

from pathlib import Path

from tests.lsp.rawclient import RawServer

TEXT = """\
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 12
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.3
        height: 0.2

Cart is Physics3D.System:
    left is Wheel
    
"""
CAPS = {"workspace": {"configuration": True},
        "textDocument": {"completion": {"completionItem": {
            "documentationFormat": ["markdown"], "resolveSupport": {"properties": ["documentation"]},
            "labelDetailsSupport": True}},
            "publishDiagnostics": {"relatedInformation": True, "tagSupport": {"valueSet": [1, 2]},
                                   "codeDescriptionSupport": True, "versionSupport": True}}}


def _start(tmp_path: Path, log: Path, caps: dict = CAPS, mode: str = "push") -> RawServer:
    srv = RawServer("--log-file", str(log), env={"PLX_CACHE_DIR": str(tmp_path / "cache")})
    srv.send({"jsonrpc": "2.0", "id": 1, "method": "initialize",
              "params": {"processId": None, "rootUri": tmp_path.as_uri(), "capabilities": caps,
                         "initializationOptions": {"diagnosticMode": mode,
                                                   "ruleDocsUrl": "https://example.org/rules/{code}"}}})
    assert "capabilities" in srv.response(1, timeout=120)["result"]
    srv.notify("initialized", {})
    return srv


def _warm(tmp_path: Path, caps: dict = CAPS, mode: str = "push") -> None:
    """A first start fills the cache (the initialize reply and the bundles' program)."""
    srv = _start(tmp_path, tmp_path / "first.log", caps, mode)
    try:
        uri = (tmp_path / "warm.openplx").as_uri()
        srv.open(uri, TEXT)
        _server_runs(srv, uri)
    finally:
        srv.close()


def _completion(srv: RawServer, uri: str, line: int, character: int, msg_id: int) -> dict:
    srv.send({"jsonrpc": "2.0", "id": msg_id, "method": "textDocument/completion",
              "params": {"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}})
    return srv.response(msg_id, timeout=120)


def _early_count(log: Path, what: str = "answered") -> int:
    """Requests answered (`answered`) or diagnostics pushed (`pushed`) before the server loaded."""
    for line in log.read_text(encoding="utf-8").splitlines():
        if "request(s) and pushed diagnostics" in line:
            return int(line.split(what + " ")[1].split()[0] if what == "answered"
                       else line.split("pushed diagnostics ")[1].split()[0])
    raise AssertionError("the server did not log its early phase")


def _server_runs(srv: RawServer, uri: str) -> None:
    """Returns once the server itself answers (a request the early phase never answers)."""
    srv.request("textDocument/documentSymbol", {"textDocument": {"uri": uri}}, timeout=120)


def test_completion_right_after_opening_is_answered_early_and_as_the_server_would(tmp_path):
    _warm(tmp_path)
    log = tmp_path / "second.log"
    srv = _start(tmp_path, log)
    try:
        uri = (tmp_path / "cart.openplx").as_uri()
        srv.open(uri, TEXT)
        line = TEXT.split("\n").index("    ")
        early = _completion(srv, uri, line, 4, 2)
        _server_runs(srv, uri)
        late = _completion(srv, uri, line, 4, 3)
        labels = [it["label"] for it in early["result"]["items"]]
        assert "reference_body" in labels and "inertia" not in labels[:1], labels  # Wheel's own attributes
        assert early["result"] == late["result"]
        # the early items' documentation is resolved by the server, which took over their keys
        item = next(it for it in early["result"]["items"] if it["label"] == "reference_body")
        srv.send({"jsonrpc": "2.0", "id": 4, "method": "completionItem/resolve", "params": item})
        resolved = srv.response(4, timeout=60)["result"]
        assert resolved.get("documentation", {}).get("value"), resolved
    finally:
        srv.close()
    assert _early_count(log) == 1


def test_typing_before_the_request_is_seen_by_the_early_answer(tmp_path):
    _warm(tmp_path)
    log = tmp_path / "second.log"
    srv = _start(tmp_path, log)
    try:
        uri = (tmp_path / "cart.openplx").as_uri()
        srv.open(uri, TEXT)
        line = TEXT.split("\n").index("    ")
        typed = "hub is Physics3D.Geometries."
        srv.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [
            {"range": {"start": {"line": line, "character": 4}, "end": {"line": line, "character": 4}},
             "text": typed}]})
        early = _completion(srv, uri, line, 4 + len(typed), 2)
        _server_runs(srv, uri)
        late = _completion(srv, uri, line, 4 + len(typed), 3)
        labels = [it["label"] for it in early["result"]["items"]]
        assert "Box" in labels and "Cylinder" in labels, labels
        assert early["result"] == late["result"]
    finally:
        srv.close()
    assert _early_count(log) == 1


BROKEN = """\
Wheel is Physics3D.Bodies.RigidBody:
    inertia.mass: 12
    geometry is Physics3D.Geometries.Sphere:
        raduis: 0.3
    spare is Physics3D.Geometries.Box
"""


def test_first_diagnostics_are_pushed_early_and_equal_the_servers(tmp_path):
    _warm(tmp_path)
    log = tmp_path / "second.log"
    srv = _start(tmp_path, log)
    try:
        uri = (tmp_path / "wheel.openplx").as_uri()
        srv.open(uri, BROKEN)
        first = srv.notification("textDocument/publishDiagnostics", timeout=120, where=lambda p: p["uri"] == uri)
        assert any("raduis" in d["message"] for d in first["diagnostics"]), first
        assert all(d["codeDescription"]["href"].endswith(d["code"]) for d in first["diagnostics"])
        assert any("fix" in d.get("data", {}) for d in first["diagnostics"]), first  # the quick fix travels
        _server_runs(srv, uri)
        second = srv.notification("textDocument/publishDiagnostics", timeout=120, where=lambda p: p["uri"] == uri)
        assert first == second  # the server's own check, pushed again: the same, field for field
    finally:
        srv.close()
    assert _early_count(log, "pushed") == 1


def test_pulled_first_diagnostics_are_answered_early_and_equal_the_servers(tmp_path):
    caps = {**CAPS, "textDocument": {**CAPS["textDocument"], "diagnostic": {"dynamicRegistration": False}}}
    _warm(tmp_path, caps, "auto")
    log = tmp_path / "second.log"
    srv = _start(tmp_path, log, caps, "auto")
    try:
        uri = (tmp_path / "wheel.openplx").as_uri()
        srv.open(uri, BROKEN)
        early = srv.request("textDocument/diagnostic", {"textDocument": {"uri": uri}}, timeout=120)["result"]
        _server_runs(srv, uri)
        late = srv.request("textDocument/diagnostic", {"textDocument": {"uri": uri}}, timeout=120)["result"]
        assert early["kind"] == late["kind"] == "full"
        assert any("raduis" in d["message"] for d in early["items"]), early
        assert early["items"] == late["items"]
        assert not [m for m in srv.pending if m.get("method") == "textDocument/publishDiagnostics"]  # pulled only
    finally:
        srv.close()
    assert _early_count(log) == 1 and _early_count(log, "pushed") == 0


def test_a_request_the_early_phase_cannot_read_goes_to_the_server_which_answers_it(tmp_path):
    _warm(tmp_path)
    log = tmp_path / "second.log"
    srv = _start(tmp_path, log)
    try:
        uri = (tmp_path / "cart.openplx").as_uri()
        srv.open(uri, TEXT)
        srv.send({"jsonrpc": "2.0", "id": 2, "method": "textDocument/completion",
                  "params": {"textDocument": {"uri": uri}}})  # no position
        bad = srv.response(2, timeout=120)
        assert bad["error"]["code"] == -32602, bad  # the server's InvalidParams, not a crash or silence
        line = TEXT.split("\n").index("    ")
        assert _completion(srv, uri, line, 4, 3)["result"]["items"]
    finally:
        assert srv.close() == 0
    assert _early_count(log) == 0


class _Busy(RawServer):
    """An editor that never answers client/registerCapability (Emacs in the middle of a go-to-definition
    answered it late or not at all)."""

    def _answer(self, m: dict) -> None:
        if m["method"] == "client/registerCapability":
            self.server_requests.append(m)
            return
        super()._answer(m)


def test_completion_does_not_wait_for_the_editor_to_answer_the_file_watchers_registration(tmp_path):
    srv = _Busy(env={"PLX_CACHE_DIR": str(tmp_path / "cache")})
    try:
        caps = {**CAPS, "workspace": {"configuration": True, "didChangeWatchedFiles": {"dynamicRegistration": True}}}
        srv.initialize(caps, {"diagnosticMode": "push"})
        uri = (tmp_path / "cart.openplx").as_uri()
        srv.open(uri, TEXT)
        line = TEXT.split("\n").index("    ")
        assert _completion(srv, uri, line, 4, 2)["result"]["items"]
        srv.notification("textDocument/publishDiagnostics", timeout=60, where=lambda p: p["uri"] == uri)
        assert srv.notification_request("client/registerCapability", timeout=5)  # asked, never answered
    finally:
        srv.proc.kill()
