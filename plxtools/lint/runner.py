"""`plx lint`: find files, analyse each, filter by config and suppressions, apply fixes."""

from __future__ import annotations

import difflib
import os
from dataclasses import dataclass, field
from pathlib import Path

from plxtools.config import DEFAULT_EXCLUDE, Config, config_for
from plxtools.diagnostics import Diagnostic, Edit, Severity
from plxtools.syntax import ast, parse_bytes


class UsageError(Exception):
    """Bad command-line input (exit code 2)."""


def discover(paths: list[str], *, use_exclude: str = "lint") -> list[Path]:
    """Expand folders into their .openplx files; explicit files are always taken."""
    out: list[Path] = []
    seen: set[Path] = set()
    for raw in paths:
        p = Path(raw)
        if not p.exists():
            raise UsageError(f"{raw}: no such file or folder")
        if p.is_file():
            if p not in seen:
                seen.add(p)
                out.append(p)
            continue
        # a folder named on the command line is walked even if an exclude pattern matches it;
        # patterns still skip what they match below it
        root_excluded = config_for(p).is_excluded(p)
        for dirpath, dirnames, filenames in os.walk(p):
            dirnames[:] = sorted(d for d in dirnames if d not in DEFAULT_EXCLUDE and not d.startswith("."))
            for name in sorted(filenames):
                if not name.endswith(".openplx"):
                    continue
                f = Path(dirpath) / name
                cfg = config_for(f)
                patterns = cfg.exclude + (cfg.fmt_exclude if use_exclude == "fmt" else [])
                if not root_excluded and cfg.is_excluded(f, patterns):
                    continue
                if f not in seen:
                    seen.add(f)
                    out.append(f)
    return out


@dataclass(slots=True)
class FileResult:
    path: Path
    tree: ast.File | None
    diagnostics: list[Diagnostic] = field(default_factory=list)


def analyse_tree(tree: ast.File, cfg: Config, workspace=None) -> list[Diagnostic]:
    """All diagnostics for a parsed file: syntax, then the semantic model's, filtered by config."""
    diags = list(tree.diagnostics)
    if not tree.diagnostics or not any(d.code == "S001" for d in tree.diagnostics):
        try:
            from plxtools.model.analysis import semantic_diagnostics
        except ImportError:  # the semantic layer is optional while it is being built
            semantic_diagnostics = None
        if semantic_diagnostics is not None:
            diags.extend(semantic_diagnostics(tree, cfg, workspace))
    return finalize(tree, diags, cfg)


def finalize(tree: ast.File, diags: list[Diagnostic], cfg: Config) -> list[Diagnostic]:
    """Config selection, inline suppressions and ordering: shared by lint, check and the server."""
    from plxtools.lint.suppress import apply

    for d in diags:
        d.file = tree.path
    diags = [d for d in diags if cfg.rule_enabled(d.code, tree.path)]
    diags = apply(tree, diags, report_unused=cfg.rule_enabled("C002", tree.path))
    diags.sort(key=Diagnostic.sort_key)
    return diags


def lint_file(path: Path, cfg: Config | None = None, workspace=None) -> FileResult:
    cfg = cfg or config_for(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        from plxtools.diagnostics import EMPTY_SPAN

        d = Diagnostic("E001", f"cannot read file: {exc.strerror}", EMPTY_SPAN, Severity.ERROR, file=str(path))
        return FileResult(path, None, [d])
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
    return FileResult(path, tree, analyse_tree(tree, cfg, workspace))


def apply_edits(text: str, edits: list[Edit]) -> str:
    """Apply non-overlapping edits (later ones first); overlapping edits are skipped."""
    out = text
    last_start = len(text) + 1
    for e in sorted(edits, key=lambda e: (e.start, e.end), reverse=True):
        if e.end > last_start:
            continue
        out = out[: e.start] + e.text + out[e.end :]
        last_start = e.start
    return out


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


def unified_diff(path: str, old: str, new: str) -> str:
    return "".join(
        difflib.unified_diff(old.splitlines(True), new.splitlines(True), f"a/{path}", f"b/{path}")
    )
