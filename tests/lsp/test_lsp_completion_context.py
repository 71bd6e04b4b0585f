"""Issue 40.4 over stdio: in a slot that wants a model type (a joint's `connectors: [`), completion
lists what fits first and leaves out what cannot lead to it: no signal, no Vec3, no body attribute
that holds no connector; after `a.` only the connectors on `a`."""

from __future__ import annotations

from tests.lsp.rawclient import RawServer

MODEL = """\
Body is Physics3D.Bodies.RigidBody:
    hub is Physics3D.Interactions.MateConnector
    offset is Math.Vec3: {0, 0, 1}
    push is Physics.Signals.LinearVelocity1DInput
Joint is Physics3D.System:
    a is Body
    b is Body
    v is Math.Vec3: {0, 0, 1}
    sig is Physics.Signals.LinearVelocity1DInput
    h is Physics3D.Interactions.Hinge:
"""


def _labels(srv: RawServer, uri: str, text: str) -> list[str]:
    lines = text.split("\n")
    line = len(lines) - 2
    got = srv.request("textDocument/completion", {"textDocument": {"uri": uri},
                                                   "position": {"line": line, "character": len(lines[line])}},
                      timeout=120)["result"]
    items = got["items"] if isinstance(got, dict) else got
    return [it["label"] for it in sorted(items, key=lambda it: (it.get("sortText") or "", it["label"]))]


def test_a_joint_connectors_list_offers_connectors_first_and_no_signal_or_vector(tmp_path):
    srv = RawServer(env={"PLX_CACHE_DIR": str(tmp_path / "cache")})
    try:
        srv.initialize({}, {"diagnosticMode": "push"})
        cases = {}
        for i, tail in enumerate(["        connectors: [", "        connectors: [a.hub, ", "        connectors: [a.",
                                  "        connectors: "]):
            uri = (tmp_path / f"joint{i}.openplx").as_uri()
            text = MODEL + tail + "\n"
            srv.open(uri, text)
            cases[tail.strip()] = _labels(srv, uri, text)
        for key in ("connectors: [", "connectors: [a.hub,"):
            got = cases[key]
            assert got[:2] == ["a.hub", "b.hub"], (key, got[:8])
            assert not {"v", "sig", "a.offset", "a.push", "b.push"} & set(got), (key, got)
        assert [x for x in cases["connectors: [a."] if x in ("hub", "offset", "push", "inertia")] == ["hub"]
        before_bracket = cases["connectors:"]
        assert "a" in before_bracket and "b" in before_bracket and "sig" not in before_bracket, before_bracket
    finally:
        srv.close()
