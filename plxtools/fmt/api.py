"""Formatting a text: the entry point shared by the CLI and the language server.

`format_text` never raises on input: a file with syntax errors comes back refused with its
error diagnostics, and a formatter bug comes back as `internal_error` with nothing changed.
"""

from __future__ import annotations

import gc
from dataclasses import dataclass, field

from plxtools.diagnostics import Diagnostic, Severity
from plxtools.fmt.brackets import LayoutError
from plxtools.fmt.document import Layout, layout
from plxtools.fmt.safety import same_lint_results, same_meaning
from plxtools.syntax import ast, parse_bytes, parse_text
from plxtools.syntax.lexer import Lexer

BOM = "\ufeff"


@dataclass(slots=True)
class FormatResult:
    """`text` is the formatted text (with the input's BOM and line endings), or None if refused."""

    text: str | None
    changed: bool = False
    diagnostics: list[Diagnostic] = field(default_factory=list)  # the errors that refused the file
    internal_error: str | None = None
    had_bom: bool = False

    @property
    def ok(self) -> bool:
        return self.text is not None


class FormatError(Exception):
    """The formatter produced output it could not verify; nothing must be written."""


def syntax_errors(tree: ast.File) -> list[Diagnostic]:
    return [d for d in tree.diagnostics if d.severity is Severity.ERROR]


def layout_tree(tree: ast.File) -> Layout:
    """Lay out an error-free tree (raises LayoutError on a shape the printer cannot handle)."""
    return layout(tree.text, tree, Lexer(tree.text), tree.newline)  # (tokens not kept: see document.py)


def format_tree(tree: ast.File) -> str:
    """The canonical text of an error-free tree, verified; raises FormatError if it cannot be."""
    try:
        out = layout_tree(tree).text
    except LayoutError as exc:
        raise FormatError(f"the formatter could not lay out this file ({exc})") from None
    if out == tree.text:
        return out  # a fixed point: nothing to verify
    try:
        again = parse_text(out, tree.path)
        reason = same_meaning(tree, again)
        if reason is None and not again.has_errors:
            second = layout_tree(again).text
            if second != out:
                reason = "formatting the output again changes it (unstable)"
        if reason is None:
            reason = same_lint_results(tree, again)
    except LayoutError as exc:
        reason = f"the output could not be laid out again ({exc})"
    except RecursionError:
        reason = "the file is nested too deeply to verify"
    if reason is not None:
        raise FormatError(reason)
    return out


def _result(tree: ast.File) -> FormatResult:
    errors = syntax_errors(tree)
    if errors:
        return FormatResult(None, diagnostics=errors, had_bom=tree.had_bom)
    # layout builds many small acyclic objects (pieces, lines, a second tree): the cyclic
    # collector would only rescan them as they grow (superlinear on big files), as in the parser
    enabled = gc.isenabled()
    gc.disable()
    try:
        out = format_tree(tree)
    except FormatError as exc:
        return FormatResult(None, internal_error=str(exc), had_bom=tree.had_bom)
    finally:
        if enabled:
            gc.enable()
    return FormatResult(out, out != tree.text, had_bom=tree.had_bom)


def format_text(text: str, path: str = "") -> FormatResult:
    """Format editor or stdin text. A leading BOM is kept in the returned text."""
    result = _result(parse_text(text, path))
    if result.text is not None and result.had_bom:
        result.text = BOM + result.text
    return result


def format_bytes(data: bytes, path: str = "") -> FormatResult:
    """Format file contents. The returned text has no BOM; `had_bom` says whether to write one."""
    return _result(parse_bytes(data, path))
