"""The `initialize` reply is kept in plx's cache: a second start with the same params answers it
before the server's libraries are loaded, with the same reply and only one reply."""

from __future__ import annotations

import queue

from tests.lsp.rawclient import RawServer

PARAMS = {"processId": None, "rootUri": None, "capabilities": {"textDocument": {"hover": {}}},
          "initializationOptions": {"openplx": {"diagnosticMode": "push"}}}


def _session(cache: str, msg_id) -> tuple[dict, list[dict]]:
    srv = RawServer(env={"PLX_CACHE_DIR": cache})
    try:
        srv.send({"jsonrpc": "2.0", "id": msg_id, "method": "initialize", "params": PARAMS})
        reply = srv.response(msg_id)
        srv.notify("initialized", {})
        down = srv.request("shutdown")
        assert down.get("result", "missing") is None
        srv.notify("exit", None)
        srv.proc.wait(timeout=30)
        extra = []
        while True:
            try:
                m = srv.out.get(timeout=0.2)
            except queue.Empty:
                break
            extra.append(m)
        extra += srv.pending
        return reply, [m for m in extra if m.get("id") == msg_id and "method" not in m]
    finally:
        if srv.proc.poll() is None:
            srv.proc.kill()


def test_second_start_answers_initialize_from_the_cache(tmp_path):
    first, dup1 = _session(str(tmp_path), 1)
    assert "capabilities" in first["result"] and not dup1
    assert list((tmp_path / "plxtools" / "lsp").glob("*"))
    second, dup2 = _session(str(tmp_path), "init-2")  # another id: the cached reply carries this one
    assert second["id"] == "init-2"
    assert second["result"] == first["result"]
    assert not dup2  # the real server's own reply to the replayed request is not sent again


def test_other_params_are_not_answered_from_the_cache(tmp_path):
    _session(str(tmp_path), 1)
    PARAMS_NO_HOVER = dict(PARAMS, capabilities={})
    srv = RawServer(env={"PLX_CACHE_DIR": str(tmp_path)})
    try:
        srv.send({"jsonrpc": "2.0", "id": 5, "method": "initialize", "params": PARAMS_NO_HOVER})
        assert "capabilities" in srv.response(5)["result"]
    finally:
        srv.proc.kill()
    assert len(list((tmp_path / "plxtools" / "lsp").glob("*"))) == 2


def test_the_reply_does_not_depend_on_the_folder_which_is_left_out_of_the_key(tmp_path):
    """The key leaves out rootUri, rootPath and workspaceFolders (an editor's first start in a new
    project is then answered from the cache): that holds only if fresh servers started on two
    folders, one with a plx.toml choosing settings, give the same reply."""
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir()
    b.mkdir()
    (b / "plx.toml").write_text('openplx-version = "0.19.0"\n[lint]\nignore = ["S001"]\n', encoding="utf-8")
    replies = []
    for folder in (a, b):
        params = dict(PARAMS, rootUri=folder.as_uri(), rootPath=str(folder),
                      workspaceFolders=[{"uri": folder.as_uri(), "name": folder.name}])
        srv = RawServer(env={"PLX_CACHE_DIR": str(tmp_path / f"cache-{folder.name}")})  # no cached reply
        try:
            srv.send({"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": params})
            replies.append(srv.response(1, timeout=120)["result"])
        finally:
            srv.proc.kill()
    assert replies[0] == replies[1]
