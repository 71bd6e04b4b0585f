"""The "migrate this file" source action (`source.migrate.plx`) over stdio (issue 13)."""

from __future__ import annotations

from tests.bundles.conftest import fetched  # noqa: F401 - provides the 0.17 bundles, as plx migrate's tests
from tests.lsp.rawclient import RawServer
from tests.migrate.test_migrate_files import NEW, OLD

END = {"line": OLD.count("\n"), "character": 0}


def apply(text: str, edit: dict) -> str:
    lines = text.split("\n")
    r = edit["range"]
    start = sum(len(x) + 1 for x in lines[:r["start"]["line"]]) + r["start"]["character"]
    end = sum(len(x) + 1 for x in lines[:r["end"]["line"]]) + r["end"]["character"]
    return text[:start] + edit["newText"] + text[end:]


def actions(s: RawServer, uri: str, only=None) -> list[dict]:
    ctx = {"diagnostics": []}
    if only is not None:
        ctx["only"] = only
    got = s.request("textDocument/codeAction", {"textDocument": {"uri": uri}, "context": ctx, "range": {
        "start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 0}}}, timeout=120)
    return got["result"] or []


def test_a_file_written_for_0_17_is_migrated_by_the_source_action(tmp_path, fetched):  # noqa: F811
    fetched("0.17.26")
    f = tmp_path / "pendulum.openplx"
    f.write_text(OLD, encoding="utf-8")
    (tmp_path / "plx.toml").write_text('openplx-version = "0.19.0"\n', encoding="utf-8")
    uri = f.as_uri()
    s = RawServer()
    try:
        caps = {"textDocument": {"codeAction": {"disabledSupport": True}}}
        init = s.initialize(caps, {"diagnosticMode": "push"})
        kinds = init["result"]["capabilities"]["codeActionProvider"]["codeActionKinds"]
        assert "source.migrate.plx" in kinds
        s.open(uri, OLD)
        diags = s.notification("textDocument/publishDiagnostics", timeout=120, where=lambda p: p["uri"] == uri)
        assert {"U001", "U002"} <= {d.get("code") for d in diags["diagnostics"]}
        # offered without asking (U001/U002 are there) and when asked for source actions
        for only in (None, ["source"], ["source.migrate.plx"]):
            got = [a for a in actions(s, uri, only) if a.get("kind") == "source.migrate.plx"]
            assert len(got) == 1, (only, got)
        action = got[0]
        assert action["title"].startswith("Migrate this file from OpenPLX 0.1") and "to 0.19.0" in action["title"]
        assert "(4 changes)" in action["title"]
        (edit,) = action["edit"]["changes"][uri]
        assert apply(OLD, edit) == NEW
        # not offered for quick fixes only
        assert not [a for a in actions(s, uri, ["quickfix"]) if a.get("kind") == "source.migrate.plx"]
        # on the version diagnostic (Ctrl+. in VS Code) it is a quick fix of it, once (issue 32.13)
        version = [d for d in diags["diagnostics"] if d.get("code") in ("U001", "U002")][:1]
        for only in (None, ["quickfix"]):
            ctx = {"diagnostics": version, **({"only": only} if only else {})}
            got = s.request("textDocument/codeAction", {"textDocument": {"uri": uri}, "context": ctx,
                                                        "range": version[0]["range"]}, timeout=120)["result"]
            migrations = [a for a in got if a["title"].startswith("Migrate this file")]
            assert [a["kind"] for a in migrations] == ["quickfix"], (only, migrations)
            assert migrations[0]["diagnostics"] == version
            assert apply(OLD, migrations[0]["edit"]["changes"][uri][0]) == NEW
        # after the migration there is nothing to migrate
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                            "contentChanges": [{"text": NEW}]})
        s.notification("textDocument/publishDiagnostics", timeout=120,
                       where=lambda p: p["uri"] == uri and p.get("version") == 2)
        assert not [a for a in actions(s, uri, ["source"]) if a.get("kind") == "source.migrate.plx"]
    finally:
        s.close()


def test_a_refused_migration_is_a_disabled_action_with_the_reason(tmp_path, fetched):  # noqa: F811
    fetched("0.17.26")
    f = tmp_path / "broken.openplx"
    text = OLD + "Broken is Physics3D.Charges.Box:\n    size: {1, 1,\n"  # a syntax error: refused
    f.write_text(text, encoding="utf-8")
    (tmp_path / "plx.toml").write_text('openplx-version = "0.19.0"\n', encoding="utf-8")
    uri = f.as_uri()
    s = RawServer()
    try:
        s.initialize({"textDocument": {"codeAction": {"disabledSupport": True}}}, {"diagnosticMode": "push"})
        s.open(uri, text)
        s.notification("textDocument/publishDiagnostics", timeout=120, where=lambda p: p["uri"] == uri)
        got = [a for a in actions(s, uri, ["source"]) if a.get("kind") == "source.migrate.plx"]
        assert len(got) == 1 and "syntax errors" in got[0]["disabled"]["reason"] and "edit" not in got[0]
        assert "syntax errors" in got[0]["title"]  # Neovim shows the title and "(disabled)" only
    finally:
        s.close()


def test_missing_bundles_are_offered_to_be_fetched_then_the_migration(tmp_path, fetched):  # noqa: F811
    """Issue 40.4: with the old version's bundles not on the machine, the action is not hidden: it
    offers to fetch them (`plx bundles install`'s fetch, run by the command it carries); after
    that the migration itself is offered. The fetch here unpacks the wheel `plx bundles install`
    left in the test cache (pip is not asked: no network in tests)."""
    import shutil

    from plxtools.model.versions import _wheel_dir

    fetched("0.18.10")  # the version OLD's U001/U002 diagnostics point at (the oldest of them)
    wheels = sorted(_wheel_dir().glob("openplx_bundles-0.18.10-*.whl"))
    assert wheels, "plx bundles install keeps the wheel it fetched"
    cache = tmp_path / "cache"
    (cache / "plxtools" / "wheels").mkdir(parents=True)
    shutil.copy(wheels[0], cache / "plxtools" / "wheels" / wheels[0].name)
    f = tmp_path / "pendulum.openplx"
    f.write_text(OLD, encoding="utf-8")
    (tmp_path / "plx.toml").write_text('openplx-version = "0.19.0"\n', encoding="utf-8")
    uri = f.as_uri()
    s = RawServer(env={"PLX_CACHE_DIR": str(cache), "PIP_INDEX_URL": "http://127.0.0.1:9/simple",
                       "PLX_PIP_TIMEOUT": "2"})
    try:
        init = s.initialize({"textDocument": {"codeAction": {"disabledSupport": True}}}, {"diagnosticMode": "push"})
        assert "plx.fetchBundles" in init["result"]["capabilities"]["executeCommandProvider"]["commands"]
        s.open(uri, OLD)
        s.notification("textDocument/publishDiagnostics", timeout=120, where=lambda p: p["uri"] == uri)
        (offer,) = [a for a in actions(s, uri, ["source"]) if a.get("kind") == "source.migrate.plx"]
        assert "disabled" not in offer and "Fetch the bundles of OpenPLX 0.18.10" in offer["title"], offer
        assert offer["command"]["command"] == "plx.fetchBundles" and offer["command"]["arguments"] == ["0.18.10"]
        got = s.request("workspace/executeCommand", offer["command"], timeout=120)
        assert "error" not in got and got["result"]["fetched"], got
        assert got["result"]["fetched"].startswith(str(cache))  # into this server's cache, as the CLI does
        (action,) = [a for a in actions(s, uri, ["source"]) if a.get("kind") == "source.migrate.plx"]
        assert action["title"].startswith("Migrate this file from OpenPLX 0.18.10 to 0.19.0"), action
        assert apply(OLD, action["edit"]["changes"][uri][0]) == NEW
    finally:
        s.close()
