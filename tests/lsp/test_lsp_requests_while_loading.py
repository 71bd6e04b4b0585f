"""Issue 32.12: the first check of a new file must not hold back completion. The bundles load in a
thread after `initialized` (seconds with an empty cache); a completion sent right after opening a
file (as Helix does) waits for them, not for the file's check, and is answered with real items
before that file's first diagnostics (issue 40.1: Neovim does not ask again after an empty answer);
the diagnostics still come, for the text the editor has by then."""

from __future__ import annotations

import time

from tests.conftest import REPO
from tests.lsp.rawclient import RawServer

TEXT = (REPO / "examples" / "tutorial" / "step07-boxtruck" / "boxtruck.openplx").read_text(encoding="utf-8")
URI = "file:///tmp/plx-first-hour/boxtruck.openplx"


def test_requests_are_answered_while_the_bundles_load(tmp_path):
    srv = RawServer(env={"PLX_CACHE_DIR": str(tmp_path / "cold-cache")})  # nothing cached: a slow first load
    try:
        srv.initialize()
        srv.open(URI, TEXT)
        t0 = time.monotonic()
        line = TEXT.splitlines().index("    front_left_wheel is Wheel")
        got = srv.request("textDocument/completion",
                          {"textDocument": {"uri": URI}, "position": {"line": line, "character": 4}})
        answered = time.monotonic() - t0
        assert "error" not in got, got
        labels = {i["label"] for i in got["result"]["items"]}
        assert "kinematically_controlled" in labels, labels  # an attribute of the System the line is in
        # nothing published yet: the answers did not wait for the check
        assert not any(m.get("method") == "textDocument/publishDiagnostics" for m in srv.pending), (answered, srv.pending)
        diags = srv.notification("textDocument/publishDiagnostics", timeout=120,
                                 where=lambda p: p["uri"] == URI)
        # checked with the real bundles: only the naming note the tutorial's folder turns off
        assert [d["code"] for d in diags["diagnostics"]] == ["C001"]
        # and once loaded, the same requests are answered from the model
        got = srv.request("textDocument/hover",
                          {"textDocument": {"uri": URI}, "position": {"line": line, "character": 6}})
        assert got["result"] is not None and "Wheel" in str(got["result"])
    finally:
        srv.close()
