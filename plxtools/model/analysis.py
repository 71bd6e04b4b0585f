"""The lint hook: semantic diagnostics for one parsed file."""

from __future__ import annotations

from plxtools.diagnostics import Diagnostic
from plxtools.syntax import ast


def semantic_diagnostics(tree: ast.File, cfg, workspace=None) -> list[Diagnostic]:
    if workspace is None:
        from plxtools.model.workspace import workspace_for_cli

        workspace = workspace_for_cli([], [], use_cache=True)
    return workspace.analyse(tree).diagnostics
