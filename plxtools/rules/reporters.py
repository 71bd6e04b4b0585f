"""Diagnostic output formats shared by `plx lint` and `plx check`: text, json, github, sarif."""

from __future__ import annotations

import json
import os
import sys
from collections import Counter
from typing import Iterable, TextIO

from plxtools import __version__
from plxtools.diagnostics import Diagnostic, Severity

FORMATS = ("text", "json", "github", "sarif")
DOCS_URL = "https://plxtools.invalid/docs/rules/{code}/"


def _use_color(stream: TextIO) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return hasattr(stream, "isatty") and stream.isatty()


def _loc(d: Diagnostic) -> str:
    return f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}"


def render_text(diags: list[Diagnostic], stream: TextIO, *, show_fix_hint: bool = True,
                summary: bool = True, files_checked: int | None = None) -> None:
    if _use_color(stream):
        _render_rich(diags, stream, summary=summary, files_checked=files_checked)
        return
    for d in diags:
        fixable = " [*]" if d.fix is not None and d.fix.safe and show_fix_hint else ""
        stream.write(f"{_loc(d)}: {d.code}{fixable} {d.message}\n")
        if d.help:
            stream.write(f"  help: {d.help}\n")
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
        t.append(_loc(d), style="bold")
        t.append(": ")
        t.append(d.code, style=styles[d.severity])
        if d.fix is not None and d.fix.safe:
            t.append(" [*]", style="cyan")
        t.append(" " + d.message)
        console.print(t)
        if d.help:
            console.print(Text("  help: ", style="cyan") + Text(d.help))
    if summary:
        console.print(_summary_line(diags, files_checked), style="bold" if diags else "green")


def render_json(diags: list[Diagnostic], stream: TextIO) -> None:
    json.dump([d.to_json() for d in diags], stream, indent=2)
    stream.write("\n")


def _gh_escape(s: str, prop: bool = False) -> str:
    s = s.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")
    if prop:
        s = s.replace(":", "%3A").replace(",", "%2C")
    return s


def render_github(diags: list[Diagnostic], stream: TextIO) -> None:
    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "notice"}
    for d in diags:
        props = (
            f"file={_gh_escape(d.file, True)},line={d.span.start.line + 1},col={d.span.start.column + 1},"
            f"endLine={d.span.end.line + 1},endColumn={d.span.end.column + 1},"
            f"title={_gh_escape('plx ' + d.code, True)}"
        )
        msg = d.message + (f"\nhelp: {d.help}" if d.help else "")
        stream.write(f"::{level[d.severity]} {props}::{_gh_escape(d.code + ' ' + msg)}\n")


def sarif_document(diags: list[Diagnostic], rules: Iterable[tuple[str, str, str]] = ()) -> dict:
    """SARIF 2.1.0. `rules` gives (code, name, short description) for the codes that appear."""
    level = {Severity.ERROR: "error", Severity.WARNING: "warning", Severity.INFO: "note"}
    rule_list = [
        {
            "id": code,
            "name": name,
            "shortDescription": {"text": desc},
            "helpUri": DOCS_URL.format(code=code),
        }
        for code, name, desc in rules
    ]
    results = []
    for d in diags:
        results.append(
            {
                "ruleId": d.code,
                "level": level[d.severity],
                "message": {"text": d.message + (f" (help: {d.help})" if d.help else "")},
                "locations": [
                    {
                        "physicalLocation": {
                            "artifactLocation": {"uri": d.file.replace(os.sep, "/")},
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
                        "informationUri": "https://plxtools.invalid/docs/",
                        "rules": rule_list,
                    }
                },
                "results": results,
            }
        ],
    }


def render(diags: list[Diagnostic], fmt: str, stream: TextIO | None = None, *,
           files_checked: int | None = None) -> None:
    stream = stream or sys.stdout
    if fmt == "json":
        render_json(diags, stream)
    elif fmt == "github":
        render_github(diags, stream)
    elif fmt == "sarif":
        from plxtools.rules.registry import describe_codes

        json.dump(sarif_document(diags, describe_codes({d.code for d in diags})), stream, indent=2)
        stream.write("\n")
    else:
        render_text(diags, stream, files_checked=files_checked)
