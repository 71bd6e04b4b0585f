"""Diagnostic output formats shared by `plx lint` and `plx check`: text, json, github, sarif."""

from __future__ import annotations

import os
import re
import sys
import textwrap
from collections import Counter
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Iterable, TextIO

from plxtools import DOCS_BASE_URL, __version__
from plxtools.diagnostics import Diagnostic, Severity, printable

FORMATS = ("text", "json", "github", "sarif")
DOCS_URL = DOCS_BASE_URL + "rules/{code}/"  # mkdocs serves docs/rules/CODE.md at rules/CODE/


def _use_color(stream: TextIO) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return hasattr(stream, "isatty") and stream.isatty()


def _loc(d: Diagnostic) -> str:
    return f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}"


def text_line(d: Diagnostic) -> str:
    """`path:line:col: severity CODE`, the start of a diagnostic's line in text output."""
    return f"{_loc(d)}: {d.severity.value} {d.code}"


WIDTH = 200  # the longest line text output prints; JSON, SARIF and GitHub keep the whole message
_REPEAT = re.compile(r"\b(\w+)((?:\.\1){3,})\b")
_DOTTED = re.compile(r"\b[A-Za-z_]\w*(?:\.[A-Za-z_]\w*){7,}\b")


def shorten(text: str) -> str:
    """Long object paths made readable: `a.spare.spare.spare.spare` -> `a.spare.spare(x4)`,
    a dotted path of more than 8 parts -> its first 3 and last 2 around `...`."""
    text = _REPEAT.sub(lambda m: f"{m.group(1)}(x{m.group(0).count('.') + 1})", text)
    return _DOTTED.sub(lambda m: ".".join(m.group(0).split(".")[:3] + ["..."] + m.group(0).split(".")[-2:]), text)


def fit(first: str, text: str, indent: str = "    ") -> str:
    """`first` + `text`, with a message longer than WIDTH made readable: long object paths
    shortened, then wrapped at spaces onto indented continuation lines of at most WIDTH characters
    (nothing is cut). The width is the message's: a long file path before it is the user's own."""
    if len(text) <= WIDTH:
        return first + text
    line = first + shorten(text)
    return "\n".join(textwrap.wrap(line, max(WIDTH, len(first) + 80), subsequent_indent=indent,
                                    break_long_words=False, break_on_hyphens=False))


def render_text(diags: list[Diagnostic], stream: TextIO, *, show_fix_hint: bool = True,
                summary: bool = True, files_checked: int | None = None) -> None:
    if _use_color(stream):
        _render_rich(diags, stream, summary=summary, files_checked=files_checked)
        return
    for d in diags:
        fixable = " [*]" if d.fix is not None and d.fix.safe and show_fix_hint else ""
        stream.write(fit(printable(f"{text_line(d)}{fixable} "), printable(d.message)) + "\n")
        if d.help:
            stream.write(fit("  help: ", printable(d.help)) + "\n")
    if summary:
        stream.write(_summary_line(diags, files_checked) + "\n")


def _summary_line(diags: list[Diagnostic], files_checked: int | None) -> str:
    counts = Counter(d.severity for d in diags)
    if not diags:
        where = f" in {files_checked} file{'s' if files_checked != 1 else ''}" if files_checked is not None else ""
        return f"All checks passed{where}."
    parts = []
    for sev, word in ((Severity.ERROR, "error"), (Severity.WARNING, "warning"), (Severity.INFO, "info")):
        n = counts.get(sev, 0)
        if n:
            parts.append(f"{n} {word}{'s' if n != 1 and word != 'info' else ''}")
    fixable = sum(1 for d in diags if d.fix is not None and d.fix.safe)
    line = "Found " + ", ".join(parts) + "."
    if fixable:
        line += f"\n[*] {fixable} fixable with `--fix`."
    return line


def _render_rich(diags: list[Diagnostic], stream: TextIO, *, summary: bool, files_checked: int | None) -> None:
    from rich.console import Console
    from rich.text import Text

    console = Console(file=stream, highlight=False, soft_wrap=True)
    styles = {Severity.ERROR: "bold red", Severity.WARNING: "bold yellow", Severity.INFO: "bold blue"}
    for d in diags:
        t = Text()
        t.append(printable(_loc(d)), style="bold")
        t.append(": ")
        t.append(f"{d.severity.value} {d.code}", style=styles[d.severity])
        if d.fix is not None and d.fix.safe:
            t.append(" [*]", style="cyan")
        head = len(t.plain) + 1
        t.append(" " + fit(" " * head, printable(d.message))[head:])
        console.print(t)
        if d.help:
            console.print(Text("  help: ", style="cyan") + Text(fit("  help: ", printable(d.help))[8:]))
    if summary:
        console.print(_summary_line(diags, files_checked), style="bold" if diags else "green")


def render_json(diags: list[Diagnostic], stream: TextIO) -> None:
    import json

    json.dump([d.to_json() for d in diags], stream, indent=2)
    stream.write("\n")


def _gh_escape(s: str, prop: bool = False) -> str:
    s = printable(s).replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


def _absolute(file: str) -> Path:
    p = Path(file)
    return Path(os.path.normpath(p if p.is_absolute() else Path.cwd() / p))


def repository_root(start: Path | None = None) -> Path:
    """The git work tree that holds `start` (default: the current folder), else that folder."""
    start = (start or Path.cwd()).resolve()
    for p in (start, *start.parents):
        if (p / ".git").exists():
            return p
    return start


def _relative_to(file: str, root: Path) -> str | None:
    try:
        return _absolute(file).relative_to(root).as_posix()
    except ValueError:
        try:  # the root was resolved (symlinks); compare resolved paths too
            return _absolute(file).resolve().relative_to(root).as_posix()
        except (ValueError, OSError):
            return None


def render_github(diags: list[Diagnostic], stream: TextIO) -> None:
    """GitHub workflow annotations; GitHub wants paths relative to the repository root."""
    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
    root = repository_root()
    for d in diags:
        path = _relative_to(d.file, root) or d.file
        props = (
            f"file={_gh_escape(path, True)},line={d.span.start.line + 1},col={d.span.start.column + 1},"
            f"endLine={d.span.end.line + 1},endColumn={d.span.end.column + 1},"
            f"title={_gh_escape('plx ' + d.code, True)}"
        )
        msg = d.message + (f"\nhelp: {d.help}" if d.help else "")
        stream.write(f"::{level[d.severity]} {props}::{_gh_escape(d.code + ' ' + msg)}\n")


def sarif_document(diags: list[Diagnostic], rules: Iterable = ()) -> dict:
    """SARIF 2.1.0. `rules` gives the rules (plxtools.rules.registry.Rule) of the codes that appear:
    GitHub code scanning shows an alert's rule text from fullDescription and help."""
    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
    rule_list = [sarif_rule(r) for r in rules]
    results = []
    root = Path.cwd().resolve()
    for d in diags:
        results.append(
            {
                "ruleId": d.code,
                "level": level[d.severity],
                "message": {"text": d.message + (f" (help: {d.help})" if d.help else "")},
                "locations": [
                    {
                        "physicalLocation": {
                            "artifactLocation": _artifact_location(d.file, root),
                            "region": {
                                "startLine": d.span.start.line + 1,
                                "startColumn": d.span.start.column + 1,
                                "endLine": d.span.end.line + 1,
                                "endColumn": d.span.end.column + 1,
                            },
                        }
                    }
                ],
            }
        )
    return {
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [
            {
                "tool": {
                    "driver": {
                        "name": "plxtools",
                        "version": __version__,
                        "informationUri": DOCS_BASE_URL,
                        "rules": rule_list,
                    }
                },
                "originalUriBaseIds": {"%SRCROOT%": {"uri": root.as_uri().rstrip("/") + "/"}},
                "results": results,
            }
        ],
    }


def sarif_rule(r) -> dict:
    """A SARIF reportingDescriptor: the rule's summary, why it matters, its page as help, its docs URL."""
    page = r.page()
    return {
        "id": r.code,
        "name": r.name,
        "shortDescription": {"text": r.summary},
        "fullDescription": {"text": f"{r.summary} {r.why}".strip()},
        "help": {"text": page, "markdown": page},
        "helpUri": DOCS_URL.format(code=r.code),
        "defaultConfiguration": {"level": {"error": "error", "warning": "warning"}.get(r.severity.value, "note")},
        "properties": {"tags": [r.stage]},
    }


def _artifact_location(file: str, root: Path) -> dict:
    """A percent-encoded URI relative to %SRCROOT% (the current folder), or a file:// URI for a
    file outside it: SARIF viewers resolve either, whatever the path's spaces, '#' or accents."""
    rel = _relative_to(file, root)
    if rel is not None:
        from urllib.parse import quote

        return {"uri": quote(rel, safe="/"), "uriBaseId": "%SRCROOT%"}
    return {"uri": _absolute(file).as_uri()}


def render(diags: list[Diagnostic], fmt: str, stream: TextIO | None = None, *,
           files_checked: int | None = None) -> None:
    stream = stream or sys.stdout
    if fmt == "json":
        render_json(diags, stream)
    elif fmt == "github":
        render_github(diags, stream)
    elif fmt == "sarif":
        import json

        from plxtools.rules.registry import get

        rules = [r for r in (get(c) for c in sorted({d.code for d in diags})) if r is not None]
        json.dump(sarif_document(diags, rules), stream, indent=2)
        stream.write("\n")
    else:
        render_text(diags, stream, files_checked=files_checked)
