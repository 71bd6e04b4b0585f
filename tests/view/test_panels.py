"""The window's panels share the room the viewport gives (no window needed: the layout is arithmetic
over MuJoCo's measured font, checked on screen by test_window_xvfb.py)."""

from __future__ import annotations

from types import SimpleNamespace

from plxtools.view.window import CHAR_PX, HELP_PX, LINE_PX, _fit, _panel_room


def _handle(width: int, height: int):
    return SimpleNamespace(viewport=SimpleNamespace(width=width, height=height))


def test_lines_stay_right_of_the_help_and_panels_share_the_height():
    for width, height in ((733, 466), (1280, 800), (500, 300)):
        cols, rows = _panel_room(_handle(width, height))
        assert cols * CHAR_PX <= max(width - HELP_PX, 24 * CHAR_PX), (width, cols)
        assert rows * LINE_PX <= height, (height, rows)
    cols, rows = _panel_room(_handle(733, 466))
    assert (cols, rows) == (53, 19)


def test_fit_keeps_at_most_the_lines_given_and_counts_the_rest():
    lines = [f"out a.b{i} = {i}" for i in range(20)]
    out = _fit(lines, 5)
    assert out == lines[:4] + ["... 16 more"]
    assert _fit(lines[:5], 5) == lines[:5]  # all fit: no "more" line
    assert _fit(lines[:3], 5) == lines[:3]


def test_a_long_error_keeps_the_clock_line_and_leaves_room_for_signals():
    from plxtools.view.window import _panel_texts

    class Session:  # the two methods the panels read, as ViewSession answers them
        def status(self, width):
            return ["LOAD FAILED at a.openplx:3:7:"] + [f"  reason part {i}" for i in range(30)] + ["Scene  t=1.00s  running"]

        def signals(self, width):
            return [f"out x{i} = {i}" for i in range(30)]

    status, signals = _panel_texts(_handle(733, 466), Session())
    cols, rows = _panel_room(_handle(733, 466))
    assert status[0].startswith("LOAD FAILED") and status[-1].startswith("Scene  t=1.00s")
    assert len(status) + len(signals) < rows and signals[-1].endswith("more")
    assert all(len(line) <= cols for line in status + signals)
