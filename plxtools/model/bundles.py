"""Finding bundles and reading their `config.openplx` (name, version, dependencies).

A bundle is a folder with a `config.openplx` at its root; its subfolders are namespaces. Official
bundles come from the `openplx-bundles` package, `OPENPLX_BUNDLE_PATH` or configured folders.
"""

from __future__ import annotations

import os
import re
import stat as _stat
from dataclasses import dataclass, field
from pathlib import Path

from plxtools.cache import reads
from plxtools.diagnostics import EMPTY_SPAN, Span
from plxtools.model import facts
from plxtools.syntax import ast

# the dependency forms OpenPLX accepts: a bare name, `Name==1.2.3` (every official bundle's own
# config, 0.15.0 to 0.19.0) and `Name@1.2.3` (openplx.org's bundle documentation)
DEP_RE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:(==|@)(\d+(?:\.\d+)*))?$")
# a name followed by something else (`Physics>=0.19`, `Physics3D 0.17.26`): read as the bare name, with a warning
DEP_OTHER_RE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*([^A-Za-z0-9_\s].*|\s+.*)$")


@dataclass(slots=True)
class Bundle:
    name: str
    root: Path
    official: bool
    version: str | None = None
    dependencies: list[str] = field(default_factory=list)
    config_tree: ast.File | None = None
    diagnostics: list = field(default_factory=list)  # facts about its config.openplx (model/facts.py)
    dep_spans: dict[str, Span] = field(default_factory=dict)
    origin: str = ""  # why this bundle is loaded (shown by --show-settings)

    def files(self) -> list[Path]:
        return [Path(p) for p in self.file_names()]

    def file_names(self) -> list[str]:
        """`files()` as strings (the bundle loader builds no Path per file: 465 of them on a cold run)."""
        out: list[str] = []
        root = str(self.root)
        _walk(root, root, out)
        return out

    def namespace_of_name(self, path: str) -> tuple[str, ...]:
        """`namespace_of` for a path listed by `file_names()` (below the root as written)."""
        folder = os.path.dirname(path)
        root = str(self.root)
        if folder == root:
            return (self.name,)
        if not folder.startswith(root + os.sep):
            return self.namespace_of(Path(path))
        return (self.name, *[p for p in folder[len(root) + 1:].split(os.sep) if p not in ("", ".")])

    def namespace_of(self, path: Path) -> tuple[str, ...]:
        try:
            rel = path.parent.relative_to(self.root)  # files listed from the root: no resolve needed
        except ValueError:
            rel = path.resolve().parent.relative_to(self.root.resolve())
        return (self.name, *[p for p in rel.parts if p not in ("", ".")])


def _walk(root: str, folder: str, out: list[str]) -> None:
    """os.walk's order (files, then sub-folders, sorted; links to folders not entered), with each
    listing noted (`plxtools.cache.reads`): a file added to a bundle changes a cached answer."""
    try:
        entries = reads.scan(folder)
    except OSError:
        return
    subs = []
    for n, is_dir in entries:
        if is_dir:
            if not n.startswith(".") and n != "__pycache__":
                subs.append(os.path.join(folder, n))
        elif n.endswith(".openplx") and not (folder == root and n == "config.openplx"):
            p = os.path.join(folder, n)
            try:  # regular files only: a link to a folder named *.openplx, a FIFO or a device is not read
                regular = _stat.S_ISREG(os.stat(p).st_mode)
            except (OSError, ValueError):
                regular = False
            if regular:
                out.append(p)
    for p in subs:
        _walk(root, p, out)


def read_config(bundle: Bundle, tree: ast.File) -> None:
    """Fill name/version/dependencies from a parsed config.openplx, recording its problems as facts
    (model/facts.py, reported when the config file is analysed)."""
    bundle.config_tree = tree
    cfg = next((s for s in tree.statements if isinstance(s, ast.Declaration) and s.path.text == "config"), None)
    diag = bundle.diagnostics.append

    if cfg is None or cfg.body is None:
        diag(facts.ConfigWithoutName(tree.statements[0].header if tree.statements else EMPTY_SPAN, False))
        return
    name_set = False
    for s in cfg.body:
        if not isinstance(s, ast.Assignment) or s.value is None:
            continue
        key = s.path.text
        if key == "name" and isinstance(s.value, ast.String):
            bundle.name = s.value.value
            name_set = True
        elif key == "version" and isinstance(s.value, ast.String):
            bundle.version = s.value.value
        elif key == "dependencies":
            if not isinstance(s.value, ast.Array):
                diag(facts.BadDependency(s.value.span, "not-array"))
                continue
            for item in s.value.items:
                if not isinstance(item, ast.String):
                    diag(facts.BadDependency(item.span, "not-string"))
                    continue
                m = DEP_RE.match(item.value)
                other = None if m else DEP_OTHER_RE.match(item.value)
                if other:
                    diag(facts.UnreadDependencyForm(item.span, item.value, other.group(1)))
                    bundle.dependencies.append(other.group(1))
                    bundle.dep_spans[other.group(1)] = item.span
                    continue
                if not m:
                    diag(facts.BadDependency(item.span, "malformed", item.value))
                    continue
                bundle.dependencies.append(m.group(1))
                bundle.dep_spans[m.group(1)] = item.span
    if not name_set:
        diag(facts.ConfigWithoutName(cfg.header, True))


def find_user_bundle_root(path: Path, stop_at: set[Path]) -> Path | None:
    """The nearest folder at or above `path` holding a config.openplx, if any."""
    folder = Path(reads.realpath(path)).parent
    for d in (folder, *folder.parents):
        if d in stop_at:
            return None
        if reads.is_file(d / "config.openplx"):
            return d
    return None


def dependency_closure(bundles: dict[str, Bundle], name: str) -> tuple[set[str], list[str] | None]:
    """Transitive dependencies of a bundle (itself included), and a cycle if there is one."""
    seen: set[str] = set()
    cycle: list[str] | None = None
    stack: list[tuple[str, list[str]]] = [(name, [name])]
    while stack:
        cur, trail = stack.pop()
        if cur in seen:
            continue
        seen.add(cur)
        b = bundles.get(cur)
        if b is None:
            continue
        for dep in b.dependencies:
            if dep in trail and cycle is None:
                cycle = trail[trail.index(dep):] + [dep]
            if dep not in seen:
                stack.append((dep, trail + [dep]))
    return seen, cycle
