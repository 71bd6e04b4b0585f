"""The editor's settings (`initializationOptions`, then `workspace/configuration` or
`didChangeConfiguration`), read into the analysis host's `Settings` and the server's own options.

One small reader per setting (`READERS`): each takes the merged settings and fills its part of an
`EditorSettings`; a value of the wrong kind falls back to the default, with a message for the user
where the setting would otherwise be silently ignored.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from plxtools.ide.host import Settings

MAX_DOCUMENT_SIZE = 1_000_000  # characters: above it a document is not analysed (maxDocumentSize)
DIAGNOSTIC_MODES = ("auto", "push", "pull")


@dataclass
class EditorSettings:
    analysis: Settings = field(default_factory=Settings)
    diagnostic_mode: str = "auto"
    max_document_size: int = MAX_DOCUMENT_SIZE  # characters; 0: no limit
    rule_docs_url: str | None = None
    messages: list[str] = field(default_factory=list)  # for the user: a setting that was not understood


CONFIG_SECTION = "openplx"  # the editor settings' section plx asks for


def section(obj) -> dict | None:
    """plx's part of a settings object (`openplx` or `plx`, else the object itself)."""
    if not isinstance(obj, dict):
        return None
    for key in ("openplx", "plx"):
        if isinstance(obj.get(key), dict):
            return obj[key]
    return obj


def merge(init_options: dict, raw: dict | None) -> dict:
    """The editor's settings over the initialization options."""
    merged = dict(init_options)
    for k, v in (raw or {}).items():
        if v is None or v == "":
            continue  # an unset editor setting does not override initializationOptions
        if k == "bundlePath" and init_options.get("bundlePath"):
            continue  # the client resolved this one already (VS Code expands ${workspaceFolder})
        merged[k] = v
    return merged


def read(merged: dict, root: str | None) -> EditorSettings:
    """`root`: the workspace folder relative setting paths are resolved against (else the current one)."""
    out = EditorSettings()
    for reader in READERS:
        reader(merged, out, root)
    return out


def _codes(value) -> list[str]:
    if isinstance(value, str):
        value = [c.strip() for c in value.split(",") if c.strip()]
    return [c.upper() for c in value]


def resolve_setting_path(p: str, root: str | None) -> str:
    root = root if root and os.path.isabs(root) else os.getcwd()
    p = os.path.expanduser(p.strip().replace("${workspaceFolder}", root))
    return p if os.path.isabs(p) else os.path.normpath(os.path.join(root, p))


def _bundle_path(m: dict, out: EditorSettings, root) -> None:
    bp = m.get("bundlePath") or m.get("bundle_path") or []
    if isinstance(bp, str):
        bp = [p for p in bp.split(os.pathsep) if p.strip()]
    out.analysis.bundle_paths = [resolve_setting_path(str(p), root) for p in bp if isinstance(p, str)]


def _openplx_version(m: dict, out: EditorSettings, root) -> None:
    version = m.get("openplxVersion") or m.get("openplx_version")
    out.analysis.openplx_version = version.strip() if isinstance(version, str) and version.strip() else None


def _select(m: dict, out: EditorSettings, root) -> None:
    sel = m.get("select")
    out.analysis.select = (_codes(sel) or None) if sel else None  # " , " selects nothing: all rules


def _ignore(m: dict, out: EditorSettings, root) -> None:
    out.analysis.ignore = _codes(m.get("ignore") or [])


def _diagnostic_mode(m: dict, out: EditorSettings, root) -> None:
    mode = m.get("diagnosticMode")
    out.diagnostic_mode = mode if mode in DIAGNOSTIC_MODES else "auto"


def _max_document_size(m: dict, out: EditorSettings, root) -> None:
    size = m.get("maxDocumentSize")
    if isinstance(size, (int, float)) and not isinstance(size, bool) and size >= 0:
        out.max_document_size = int(size)
    elif size is not None:
        out.messages.append(f"maxDocumentSize must be a number of characters (0: no limit), not {size!r}")


def _rule_docs_url(m: dict, out: EditorSettings, root) -> None:
    url = m.get("ruleDocsUrl")
    out.rule_docs_url = url if isinstance(url, str) and url else None


READERS = (_bundle_path, _openplx_version, _select, _ignore, _diagnostic_mode, _max_document_size, _rule_docs_url)
