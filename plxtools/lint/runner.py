"""`plx lint`: find files, analyse each, filter by config and suppressions, apply fixes."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from plxtools.cache import reads
from plxtools.config import Config, config_for
from plxtools.diagnostics import Diagnostic, Edit, Severity, apply_edits  # noqa: F401 - lint's name for it
from plxtools.discovery import UsageError, discover  # noqa: F401 - the lint command's names for them
from plxtools.fileio import unified_diff  # noqa: F401
from plxtools.rules.analysis import analyse_tree
from plxtools.syntax import ast, parse_bytes
from plxtools.syntax.lexer import forget_last
from plxtools.syntax.source import unreadable


@dataclass(slots=True)
class FileResult:
    path: Path
    tree: ast.File | None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    data: bytes | None = None  # the bytes read: `--fix` writes only if the file still holds them


def lint_file(path: Path, cfg: Config | None = None, workspace=None, data: bytes | None = None) -> FileResult:
    """Lint one file: `data`, when given, are its bytes as the caller read them (read once: a cached
    result is keyed by the same bytes)."""
    cfg = cfg or config_for(path)
    try:
        if data is None:
            data = reads.read_bytes(path, cfg.max_file_bytes)
    except OSError as exc:
        return FileResult(path, None, [unreadable(str(path), exc)])
    tree = None
    if workspace is not None:  # a bundle file the workspace already parsed: reuse its tree
        unit = workspace.program.units.get(str(path))
        if unit is not None and not data.startswith(b"\xef\xbb\xbf"):
            try:
                if unit.tree.text == data.decode("utf-8"):
                    tree = unit.tree
            except UnicodeDecodeError:
                pass
    if tree is None:
        tree = parse_bytes(data, str(path))
        forget_last()  # lint does not format: the tokens need not outlive the parse
    return FileResult(path, tree, analyse_tree(tree, cfg, workspace), data)


def fixed_text(tree: ast.File, diags: list[Diagnostic], unsafe: bool) -> tuple[str, int]:
    edits: list[Edit] = []
    n = 0
    for d in diags:
        if d.fix is not None and (d.fix.safe or unsafe):
            edits.extend(d.fix.edits)
            n += 1
    if not edits:
        return tree.text, 0
    return apply_edits(tree.text, edits), n
