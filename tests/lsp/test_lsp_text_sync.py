"""The server's copy of a document follows LSP's rules for any edit (issue 14 item 4): only `\\n`,
`\\r\\n` and `\\r` end a line, and a position past a line's end is that line's end. Checked
against a client-side model written independently here, and over stdio for the reproductions."""

from __future__ import annotations

from types import SimpleNamespace

from hypothesis import given, settings
from hypothesis import strategies as st

from plxtools.lsp.convert import apply_change
from tests.conftest import campaign_size
from tests.lsp.rawclient import RawServer

# characters that are line breaks to Python's str.splitlines but not to LSP, and non-BMP text
ALPHABET = ["a", "b", " ", "\n", "\r\n", "\r", "\u2028", "\u2029", "\x0c", "\x0b", "\x85", "\x1c", "\x1d",
            "\x1e", "é", "\U0001F600"]


def _client_lines(text: str) -> list[tuple[int, int]]:
    """(start, end) offsets of each LSP line, end before its line break."""
    lines, start, i = [], 0, 0
    while i < len(text):
        ch = text[i]
        if ch == "\r" or ch == "\n":
            lines.append((start, i))
            i += 2 if text.startswith("\r\n", i) else 1
            start = i
        else:
            i += 1
    lines.append((start, len(text)))
    return lines


def _client_offset(text: str, line: int, character: int) -> int:
    lines = _client_lines(text)
    if line >= len(lines):
        return len(text)
    start, end = lines[line]
    units = 0
    for i in range(start, end):
        if units >= character:
            return i
        units += 2 if ord(text[i]) > 0xFFFF else 1  # UTF-16 code units
    return end


def _client_apply(text: str, sl: int, sc: int, el: int, ec: int, new: str) -> str:
    a, b = _client_offset(text, sl, sc), _client_offset(text, el, ec)
    a, b = min(a, b), max(a, b)
    return text[:a] + new + text[b:]


def _change(sl, sc, el, ec, new):
    pos = SimpleNamespace
    return SimpleNamespace(range=SimpleNamespace(start=pos(line=sl, character=sc), end=pos(line=el, character=ec)),
                           text=new)


texts = st.lists(st.sampled_from(ALPHABET), max_size=30).map("".join)


@settings(max_examples=campaign_size(300), deadline=None)
@given(text=texts, edits=st.lists(st.tuples(st.integers(0, 8), st.integers(0, 12), st.integers(0, 8),
                                            st.integers(0, 12), texts), min_size=1, max_size=6))
def test_random_edits_match_a_client_model(text, edits):
    server_text = client_text = text
    for sl, sc, el, ec, new in edits:
        server_text = apply_change(server_text, _change(sl, sc, el, ec, new))
        client_text = _client_apply(client_text, sl, sc, el, ec, new)
        assert server_text == client_text


def _diagnostics_after(text: str, change: dict) -> list[tuple]:
    s = RawServer()
    try:
        s.initialize(options={"diagnosticMode": "push"})
        uri = "file:///sync/doc.openplx"
        s.open(uri, text)
        s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri)
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2}, "contentChanges": [change]})
        got = s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri and p["version"] == 2)
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    return [(d["code"], d["range"]["start"]["line"], d["range"]["start"]["character"]) for d in got["diagnostics"]]


def test_a_line_separator_in_a_comment_does_not_move_later_edits():
    text = "# note\u2028more\nScene is Physics3D.System:\n    x is Real: 1\n    y is Real: 2\n"
    change = {"range": {"start": {"line": 3, "character": 15}, "end": {"line": 3, "character": 16}}, "text": "zzz"}
    assert _diagnostics_after(text, change) == [("N003", 3, 15)]


def test_an_edit_past_the_end_of_a_line_stays_on_that_line():
    text = "Scene is Physics3D.System:\n    x is Real: 1\n    y is Real: 2\n"
    change = {"range": {"start": {"line": 1, "character": 17}, "end": {"line": 1, "character": 17}}, "text": " + zzz"}
    assert _diagnostics_after(text, change) == [("N003", 1, 19)]


# Helix 25.01 and 25.07 write the didChange notifications of fast typing to the pipe out of order
# (seen in a real Helix under tmux: versions 7, 8, 6). The server must end with the text the user typed.

def _typing(text: str, line: int, col: int, word: str, first_version: int, step: int = 1) -> list[tuple[int, list]]:
    """One didChange per character typed at (line, col), versions first_version, +step, ..."""
    return [(first_version + i * step, [_change(line, col + i, line, col + i, ch)]) for i, ch in enumerate(word)]


@settings(max_examples=campaign_size(200), deadline=None)
@given(data=st.data(), step=st.integers(1, 3))
def test_edits_that_arrive_out_of_order_give_the_text_typed(data, step):
    from plxtools.lsp.documents import Documents

    text = "Ball is X:\n    r: 1\n"
    edits = _typing(text, 1, 4, "radius_", 2, step) + [(2 + 7 * step, [_change(0, 0, 0, 4, "Wheel")])]
    in_order = text
    for _, changes in edits:
        in_order = apply_change(in_order, changes[0])
    # each edit arrives at most a few places away from where it belongs, as in Helix
    order = data.draw(st.permutations(range(len(edits))).filter(
        lambda p: all(abs(p[i] - i) <= 3 for i in range(len(p)))))
    docs = Documents()
    docs.open("file:///t.openplx", text, 1)
    for i in order:
        version, changes = edits[i]
        docs.change("file:///t.openplx", version, changes, "utf-16")
    doc = docs.get("file:///t.openplx")
    assert (doc.text, doc.version) == (in_order, edits[-1][0])


def _send_edit(s, uri: str, edit) -> None:
    """One keystroke of `_typing` as a didChange notification."""
    version, changes = edit
    c = changes[0]
    s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version}, "contentChanges": [
        {"range": {"start": vars(c.range.start), "end": vars(c.range.end)}, "text": c.text}]})


def test_a_shuffled_burst_over_stdio_is_checked_as_typed():
    s = RawServer()
    try:
        s.initialize(options={"diagnosticMode": "push"})
        uri = "file:///sync/shuffled.openplx"
        s.open(uri, "Ball is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n    \n")
        s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri)
        edits = _typing("", 2, 4, "is_dynamic: false", 2)
        for k in (0, 1, 3, 4, 2, 5, 7, 6, 8, 9, 10, 12, 11, 13, 14, 16, 15):  # the order Helix wrote them in
            _send_edit(s, uri, edits[k])
        # a check may run between two arrivals (the server cannot know an edit is still on its way,
        # versions may skip numbers), so an early publish for the newest version may show the text
        # without the late edit; the late edit must then be checked and published for that version
        got = s.notification("textDocument/publishDiagnostics",
                             where=lambda p: p["uri"] == uri and p["version"] == edits[-1][0] and not p["diagnostics"])
        assert got["diagnostics"] == []
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
    # the client broke LSP's ordering: said once as a warning, not once per edit
    log = b"".join(s.stderr).decode()
    assert len([ln for ln in log.splitlines() if "WARNING" in ln and "edits out of order" in ln]) == 1, log


def test_an_edit_that_arrives_after_its_successor_was_checked_is_checked_again():
    """The late edit of a shuffled burst arrives after the server has already checked and published
    the newer version without it: the document is re-applied in version order and published again."""
    s = RawServer()
    try:
        s.initialize(options={"diagnosticMode": "push"})
        uri = "file:///sync/late.openplx"
        s.open(uri, "Ball is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n    \n")
        s.notification("textDocument/publishDiagnostics", where=lambda p: p["uri"] == uri)
        edits = _typing("", 2, 4, "is_dynamic: false", 2)
        for k in [*range(15), 16]:  # every keystroke but the 's'
            _send_edit(s, uri, edits[k])
        early = s.notification("textDocument/publishDiagnostics",
                               where=lambda p: p["uri"] == uri and p["version"] == edits[-1][0])
        assert [d["code"] for d in early["diagnostics"]] == ["N003"], early  # `fale` without its 's'
        _send_edit(s, uri, edits[15])
        got = s.notification("textDocument/publishDiagnostics",
                             where=lambda p: p["uri"] == uri and p["version"] == edits[-1][0])
        assert got["diagnostics"] == []
        assert s.close() == 0
    finally:
        if s.proc.poll() is None:
            s.proc.kill()
