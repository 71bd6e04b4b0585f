"""Notes (diagnostics) produced by the MuJoCo backend, and the MuJoCo name <-> OpenPLX path map."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from plxtools.check.scene import Source
from plxtools.rules import registry

ERROR = "error"
WARNING = "warning"
INFO = "info"


@dataclass(slots=True)
class BackendNote:
    """Something unsupported, approximated, wrong or found by simulation.

    ``severity`` is "error" | "warning" | "info" (same words as ``plxtools.diagnostics.Severity``);
    ``code`` is a stable kebab-case identifier; ``path`` the OpenPLX dotted path concerned."""

    severity: str
    code: str
    message: str
    source: Source | None = None
    path: str | None = None

    def to_dict(self) -> dict[str, Any]:
        src = None
        if self.source is not None:
            s = self.source
            src = {
                "file": s.file,
                "line": s.line,
                "column": s.column,
                "end_line": s.end_line,
                "end_column": s.end_column,
            }
        return {
            "severity": self.severity,
            "code": self.code,
            "message": self.message,
            "path": self.path,
            "source": src,
        }


_BAD = re.compile(r"[^A-Za-z0-9_.:\-/\[\]]")


@dataclass(slots=True)
class NameMap:
    """Unique, sanitised MuJoCo names per object kind, mapped back to OpenPLX paths and sources."""

    to_path: dict[tuple[str, str], str] = field(default_factory=dict)  # (kind, mj name) -> path
    to_name: dict[tuple[str, str], str] = field(default_factory=dict)  # (kind, path) -> mj name
    sources: dict[str, Source | None] = field(default_factory=dict)  # path -> source

    def add(self, kind: str, path: str, source: Source | None = None, suffix: str = "") -> str:
        key = path + suffix
        if (kind, key) in self.to_name:
            return self.to_name[(kind, key)]
        base = _BAD.sub("_", key) or "unnamed"
        if base == "world":
            base = "world_"
        name, i = base, 2
        while (kind, name) in self.to_path:
            name = f"{base}~{i}"
            i += 1
        self.to_path[(kind, name)] = path
        self.to_name[(kind, key)] = name
        if path not in self.sources or self.sources[path] is None:
            self.sources[path] = source
        return name

    def name(self, kind: str, path: str, suffix: str = "") -> str | None:
        return self.to_name.get((kind, path + suffix))

    def path(self, kind: str, name: str) -> str | None:
        return self.to_path.get((kind, name))

    def path_any(self, name: str) -> str | None:
        for (_, n), p in self.to_path.items():
            if n == name:
                return p
        return None


_ELEMENT = re.compile(r"Element name '([^']*)', id (\d+)")
_KIND = re.compile(r"\bin (body|geom|joint|actuator|equality|mesh|pair|exclude|tendon|site)\b")
_QUOTED = re.compile(r"'([^']+)'")


def note_from_compile_error(err: Exception, names: NameMap) -> BackendNote:
    """Map a MuJoCo compile ``ValueError`` to a note at the OpenPLX element involved."""
    msg = str(err).strip()
    path: str | None = None
    m = _ELEMENT.search(msg)
    kind_m = _KIND.search(msg)
    candidates: list[str] = []
    if m and m.group(1):
        candidates.append(m.group(1))
    candidates += _QUOTED.findall(msg)
    for cand in candidates:
        if kind_m is not None:
            path = names.path(kind_m.group(1), cand)
        if path is None:
            path = names.path_any(cand)
        if path is not None:
            break
    src = names.sources.get(path) if path else None
    where = f" (OpenPLX element {path})" if path else ""
    text = msg.replace("\n", " ")
    return BackendNote(ERROR, registry.MUJOCO_COMPILE_ERROR, f"MuJoCo rejected the model{where}: {text}", src, path)
