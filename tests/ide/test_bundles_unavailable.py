"""Without any loadable bundles the editor still answers: syntax checks plus one B000 warning that
says why (for example openplx-bundles missing from the server's environment)."""

from __future__ import annotations

import plxtools.model.workspace as workspace
from plxtools.ide.host import AnalysisHost


def test_no_bundles_gives_one_b000_and_the_syntax_errors(monkeypatch):
    def unavailable(*args, **kwargs):
        raise workspace.WorkspaceError("openplx-bundles is not installed")

    monkeypatch.setattr(workspace, "Workspace", unavailable)
    host = AnalysisHost(use_cache=False)
    path = "/tmp/plx-no-bundles/scene.openplx"
    host.open_document(path, "Scene is Physics3D.System:\n    x is Real: = 1\n", 1)
    st = host.state(path)
    codes = [d.code for d in st.diagnostics]
    assert codes.count("B000") == 1 and any(c.startswith("S") for c in codes), codes
    b000 = next(d for d in st.diagnostics if d.code == "B000")
    assert "openplx-bundles is not installed" in b000.message
