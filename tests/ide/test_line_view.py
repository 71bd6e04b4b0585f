"""Completion while typing gives what a full analysis gives.

The host answers completion on a line typed since the last analysis from that analysis
(host.line_view); it is compared here with a fresh host that analyses the new text from scratch."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from plxtools.ide import AnalysisHost, complete, complete_line

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "bench"))
from lsp_bench import openplx_text  # noqa: E402

@pytest.mark.parametrize("typed", ["    inertia.", "    inertia.m", "    geometry.", "    ", "    mass: ",
                                   "    connector is Physics3D.", "    inertia.mass: 10 # "])
def test_completion_on_a_typed_line_matches_a_fresh_analysis(tmp_path, typed):
    text = openplx_text(120)
    path = str(tmp_path / "typing.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    host.state(path)
    lines = text.split("\n")
    n = next(k for k, ln in enumerate(lines) if "inertia.mass: 10" in ln)
    for new_lines, line in ((lines[:n + 1] + [typed] + lines[n + 1:], n + 1),  # a new line
                            (lines[:n] + [typed] + lines[n + 1:], n)):  # a line typed over
        new = "\n".join(new_lines)
        host.update_document(path, new, 2)
        view = host.line_view(path, line)
        assert view is not None and view.text == typed
        got = complete_line(view.state, line, view.text, len(typed), view.start, None, view.own_line,
                            min(view.start + len(typed), view.old_end))
        fresh = AnalysisHost(root=str(tmp_path))
        fresh.open_document(path, new, 2)
        offset = view.start + len(typed)
        want = complete(fresh.state(path), offset)
        assert [(i.label, i.kind, i.detail, i.insert_text) for i in got.items] == \
            [(i.label, i.kind, i.detail, i.insert_text) for i in want.items]
        assert (got.replace_start, got.replace_end) == (want.replace_start, want.replace_end)


def test_line_view_only_for_one_changed_line(tmp_path):
    text = openplx_text(60)
    path = str(tmp_path / "view.openplx")
    host = AnalysisHost(root=str(tmp_path))
    host.open_document(path, text, 1)
    host.state(path)
    assert host.line_view(path, 3) is None  # the analysis is current
    lines = text.split("\n")
    host.update_document(path, "\n".join(lines[:5] + ["    a:", "    b"] + lines[5:]), 2)
    assert host.line_view(path, 5) is None and host.line_view(path, 6) is None  # two new lines
