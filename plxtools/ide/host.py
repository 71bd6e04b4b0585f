"""The analysis host: open documents, the semantic model, and one cached analysis per file version.

Everything here speaks paths, text and offsets (code points); nothing knows about LSP. The host
keeps the semantic model's units in step with the editor's buffers: a buffer that differs from
the disk replaces that file's symbols, and closing it puts the disk version back.

A file's analysis stays valid while its text is the same and no bundle file changed since
(`generation`). Loose files (outside any bundle) are invisible to every other file, so editing
one never invalidates anything else.
"""

from __future__ import annotations

import bisect
import os
import threading
from dataclasses import dataclass, field
from pathlib import Path

from plxtools.config import Config, ConfigError, config_for
from plxtools.diagnostics import EMPTY_SPAN, Diagnostic, Severity
from plxtools.syntax.incremental import IncrementalParser
from plxtools.rules.analysis import analyse_file
from plxtools.syntax import ast, parse_text
from plxtools.rules import registry
from plxtools.config import _config_for_dir
from plxtools.model.imports import resolve_file
from plxtools.model.versions import BundleSetError
from plxtools.rules.analysis import final_diagnostics


def is_file_path(path: str) -> bool:
    """True for real files; False for editor buffers named by a URI such as `untitled:Untitled-1`."""
    return os.path.isabs(path)


@dataclass(slots=True)
class Document:
    path: str
    text: str
    version: int | None = None


@dataclass(slots=True, eq=False)
class FileState:
    """One analysed version of one file."""

    path: str
    text: str
    version: int | None
    tree: ast.File
    analysis: object | None  # model.workspace.FileAnalysis (None when the bundles are unavailable)
    diagnostics: list[Diagnostic]  # exactly `plx lint`'s, after config and suppressions
    generation: int
    program: object = None  # model.program.Program
    unit: object = None  # model.symbols.FileUnit
    known_annotations: frozenset = frozenset()
    _occ: list | None = None
    _by_start: dict | None = None
    _starts: list[int] | None = None

    @property
    def checked(self) -> bool:
        """False for a quick state (symbols only, no checker run: no occurrences, no diagnostics)."""
        return self.analysis is not None

    @property
    def occurrences(self) -> list:
        return self.analysis.occurrences if self.analysis is not None else []

    def occurrences_at(self, offset: int) -> list:
        """Every recorded name whose span holds the offset, innermost first, definitions first."""
        if self._occ is None:
            occ = sorted(self.occurrences, key=lambda o: (o.span.start.offset, -o.span.end.offset))
            self._occ = occ
            self._starts = [o.span.start.offset for o in occ]
        i = bisect.bisect_right(self._starts, offset)
        hits = []
        j = i - 1
        # spans do not nest deeply; a short look back finds every span that holds the offset
        while j >= 0 and i - j < 64:
            o = self._occ[j]
            if o.span.start.offset <= offset <= o.span.end.offset:
                hits.append(o)
            j -= 1
        hits.sort(key=lambda o: (o.span.end.offset - o.span.start.offset, o.kind != "definition"))
        return hits


@dataclass(slots=True)
class LineView:
    """A line of the current buffer and the (older) analysis it is read against (host.line_view)."""

    state: FileState
    line: int
    text: str  # the line's current text, without its line break
    start: int  # its offset in the current text (the same in the analysed text)
    own_line: int  # the analysed tree's line it replaces; -1 when it is a new line
    old_end: int  # the end of that line in the analysed text (a place in its tree)


def changed_lines(old: str, new: str) -> tuple[int, int, int] | None:
    """(start, old_end, new_end): the whole lines that differ between two texts, as offsets (the
    start is the same in both; the ends are where the common rest begins). None if equal."""
    if old == new:
        return None
    n = min(len(old), len(new))
    lo, hi = 0, n  # the longest common prefix, by halving (slice compares run in C)
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if old[lo:mid] == new[lo:mid]:
            lo = mid
        else:
            hi = mid - 1
    first = new.rfind("\n", 0, lo) + 1
    room = min(len(old), len(new)) - first
    lo, hi = 0, room  # the longest common suffix after `first`
    lo_o, lo_n = len(old), len(new)
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if old[lo_o - mid:lo_o - lo] == new[lo_n - mid:lo_n - lo]:
            lo = mid
        else:
            hi = mid - 1
    po, pn = len(old) - lo, len(new) - lo
    at_start_o = po == first or old[po - 1] == "\n"
    at_start_n = pn == first or new[pn - 1] == "\n"
    if not (at_start_o and at_start_n):
        k = new.find("\n", pn)
        if k == -1:
            po, pn = len(old), len(new)
        else:
            po, pn = po + (k + 1 - pn), k + 1
    return first, po, pn


@dataclass(slots=True)
class Settings:
    bundle_paths: list[str] = field(default_factory=list)
    openplx_version: str | None = None
    select: list[str] | None = None
    ignore: list[str] = field(default_factory=list)


class AnalysisHost:
    def __init__(self, settings: Settings | None = None, use_cache: bool = True, root: str | None = None):
        self.settings = settings or Settings()
        self.use_cache = use_cache
        self.root = root
        self.docs: dict[str, Document] = {}
        self._states: dict[str, FileState] = {}
        self._parsers: dict[str, IncrementalParser] = {}
        self._trees: dict[str, ast.File] = {}  # the last parse of each open buffer
        self._analyses: dict = {}  # the last analysis of each open buffer, re-used by the next (model/reuse.py)
        self._imports_seen: dict = {}  # path -> (tree, the files its imports name): see imports_of
        self._ws = None
        self._ws_lock = threading.Lock()
        self._ws_before: tuple | None = None  # (bundle-set key, workspace) while choosing the set again
        self._set_key: tuple | None = None
        self._loaded_once = False
        self.workspace_error: str | None = None
        self.generation = 0
        self.messages: list[str] = []  # problems the editor should show once (bad config, bundle path)

    # ------------------------------------------------------------------ the semantic model

    @property
    def workspace(self):
        """The semantic model of the workspace folder: the bundle set chosen as the CLI chooses it
        (settings' bundle paths, then plx.toml / pyproject.toml, OPENPLX_BUNDLE_PATH, an
        openplx-version pin, user bundles found nearby, else the installed official bundles)."""
        if self._ws is None and self.workspace_error is None:
            with self._ws_lock:  # the language server loads it in a thread: one load, others wait
                if self._ws is None and self.workspace_error is None:
                    self._load_workspace()
        return self._ws

    def _load_workspace(self) -> None:
        from plxtools.model.workspace import Workspace, WorkspaceError, bundle_set_for_folder

        good = []
        for p in (Path(p) for p in self.settings.bundle_paths):
            if p.exists():
                good.append(p)
            else:
                self.messages.append(f"bundle path {p} does not exist")
        root = Path(self.root) if self.root and is_file_path(self.root) else None
        self._loaded_once = True
        try:
            bs = bundle_set_for_folder(root, [str(p) for p in good], self.settings.openplx_version)
            if self._ws_before is not None and self._ws_before[0] == bs.key():
                self._ws = self._ws_before[1]  # the same set: keep the loaded model and its buffers
            else:
                self._ws = Workspace(use_cache=self.use_cache, bundle_set=bs)
            self._set_key = bs.key()
        except (BundleSetError, ConfigError, WorkspaceError, OSError) as exc:
            self.messages.append(str(exc))
            try:  # the official bundles still work without the user's setup
                self._ws = Workspace([], use_cache=self.use_cache)
            except (WorkspaceError, OSError) as exc2:
                self.workspace_error = str(exc2)
                self.messages.append(str(exc2))

    def config_changed(self) -> bool:
        """A plx.toml, pyproject.toml or config.openplx changed: choose the bundle set again.
        Returns True when the set is a different one (everything must be checked again)."""

        _config_for_dir.cache_clear()
        if self._ws is None:
            return False
        before = self._ws
        self._ws_before = (self._set_key, before)
        self._ws = None
        self.workspace_error = None
        try:
            after = self.workspace
        finally:
            self._ws_before = None
        if after is before:
            return False
        self._parsers.clear()
        self._trees.clear()
        self._states.clear()
        self.generation += 1
        return True

    @property
    def program(self):
        ws = self.workspace
        return ws.program if ws is not None else None

    def configure(self, settings: Settings) -> bool:
        """New settings; a different bundle path rebuilds the semantic model (returns True then)."""
        rebuild = ([str(p) for p in settings.bundle_paths] != [str(p) for p in self.settings.bundle_paths]
                   or settings.openplx_version != self.settings.openplx_version)
        self.settings = settings
        if rebuild:
            self._ws = None
            self.workspace_error = None
            self._parsers.clear()
            self._trees.clear()
            self._analyses.clear()
        self._states.clear()
        self.generation += 1
        return rebuild and self._loaded_once

    # ------------------------------------------------------------------ documents

    def open_document(self, path: str, text: str, version: int | None = None) -> None:
        self.docs[path] = Document(path, text, version)
        self._load_config_bundles(path)

    def update_document(self, path: str, text: str, version: int | None = None) -> None:
        doc = self.docs.get(path)
        if doc is None:
            self.docs[path] = Document(path, text, version)
        else:
            doc.text = text
            doc.version = version

    def close_document(self, path: str) -> None:
        """Forget a buffer; a bundle file goes back to its text on disk."""
        doc = self.docs.pop(path, None)
        self._states.pop(path, None)
        self._parsers.pop(path, None)
        self._trees.pop(path, None)
        self._analyses.pop(path, None)
        self._imports_seen.pop(path, None)
        ws = self._ws
        if doc is None or ws is None:
            return
        unit = ws.program.units.get(path)
        if unit is None:
            return
        if unit.bundle is None:
            ws.program.remove_unit(path)  # a loose file: the model resets nothing for it
            return
        if is_file_path(path) and os.path.isfile(path):
            try:
                disk = Path(path).read_text(encoding="utf-8")
            except (OSError, UnicodeDecodeError):
                return
            if disk != unit.tree.text:
                ws.unit_for(parse_text(disk, path))
                self.generation += 1

    def file_changed_on_disk(self, path: str) -> bool:
        """A watched file changed: reload it unless the editor holds it open. True if anything changed."""
        if path in self.docs or self._ws is None:
            return False
        unit = self._ws.program.units.get(path)
        if unit is None:
            if path.endswith(".openplx") and os.path.isfile(path):
                b = self._ws.bundle_of(Path(path))
                if b is not None and not b.official:
                    self._ws.unit_for(parse_text(Path(path).read_text(encoding="utf-8", errors="replace"), path))
                    self.generation += 1
                    return True
            return False
        try:
            disk = Path(path).read_text(encoding="utf-8", errors="replace")
        except OSError:
            if unit.bundle is not None and not unit.official:
                self._ws.program.remove_unit(path)
                self.generation += 1
                return True
            return False
        if disk == unit.tree.text:
            return False
        self._ws.unit_for(parse_text(disk, path))
        self._states.pop(path, None)
        if unit.bundle is not None:
            self.generation += 1
        return True

    def _load_config_bundles(self, path: str) -> None:
        if not is_file_path(path):
            return
        ws = self.workspace
        if ws is None:
            return
        try:
            cfg = config_for(path)
        except ConfigError as exc:
            self.messages.append(str(exc))
            return
        for p in cfg.bundle_paths:
            if not any(Path(b.root).resolve() == p or Path(b.root).resolve().parent == p for b in ws.bundles.values()):
                try:
                    ws.add_bundle_folder(p)
                    self.generation += 1
                except Exception as exc:  # noqa: BLE001 - a bad folder is reported, never fatal
                    self.messages.append(str(exc))

    def config(self, path: str) -> Config:
        cfg = Config()
        if is_file_path(path):
            try:
                cfg = config_for(path)
            except ConfigError as exc:
                self.messages.append(str(exc))
                cfg = Config()
        s = self.settings
        if s.select is not None or s.ignore:
            from dataclasses import replace

            cfg = replace(cfg, select=list(s.select) if s.select is not None else cfg.select,
                          ignore=list(cfg.ignore) + list(s.ignore))
        return cfg

    def text_of(self, path: str) -> str | None:
        doc = self.docs.get(path)
        if doc is not None:
            return doc.text
        ws = self._ws
        if ws is not None:
            unit = ws.program.units.get(path)
            if unit is not None:
                return unit.tree.text
        if is_file_path(path) and os.path.isfile(path):
            try:
                return Path(path).read_text(encoding="utf-8", errors="replace")
            except OSError:
                return None
        return None

    def tree_of(self, path: str) -> ast.File | None:
        """The syntax tree of any file: an analysed buffer, a bundle file, or a file on disk."""
        st = self._states.get(path)
        text = self.text_of(path)
        if st is not None and st.text == text:
            return st.tree
        ws = self._ws
        if ws is not None:
            unit = ws.program.units.get(path)
            if unit is not None and unit.tree.text == text:
                return unit.tree
        if text is None:
            return None
        return parse_text(text, path)

    # ------------------------------------------------------------------ analysis

    def _parse(self, path: str, text: str) -> ast.File:
        last = self._trees.get(path)
        if last is not None and last.text == text:
            return last
        if path in self.docs:
            parser = self._parsers.get(path)
            if parser is None:
                parser = self._parsers[path] = IncrementalParser()
            tree = parser.parse(text, path)
            self._trees[path] = tree
            return tree
        return parse_text(text, path)

    def _sync_buffers(self, skip: str) -> None:
        """Register every edited bundle buffer with the model before anything is checked against it."""
        ws = self._ws
        if ws is None:
            return
        for path, doc in self.docs.items():
            if path == skip:
                continue
            unit = ws.program.units.get(path)
            if unit is None or unit.bundle is None or unit.official or unit.tree.text == doc.text:
                continue  # an official bundle file is read-only: its edits never reach the model
            ws.unit_for(self._parse(path, doc.text))
            self.generation += 1

    def _current(self, path: str, text: str) -> FileState | None:
        st = self._states.get(path)
        if st is not None and st.text == text and st.generation == self.generation:
            doc = self.docs.get(path)
            if doc is not None:
                st.version = doc.version
            return st
        return None

    def state(self, path: str) -> FileState | None:
        """The current analysis of a file (an open buffer, or a file on disk); cached per version."""
        doc = self.docs.get(path)
        text = doc.text if doc is not None else self.text_of(path)
        if text is None:
            return None
        ws = self.workspace
        self._sync_buffers(path)
        st = self._current(path, text)
        if st is not None and st.checked:
            return st
        tree = None
        if ws is not None and doc is None:
            unit = ws.program.units.get(path)
            if unit is not None and unit.tree.text == text:
                tree = unit.tree
        if tree is None:
            tree = self._parse(path, text)
        analysis = None
        disk = ws.program.units.get(path) if ws is not None else None
        if disk is not None and disk.official and disk.tree.text != text:
            pass  # an edited official bundle file: syntax only, the model keeps the installed text
        elif ws is not None:
            before = disk
            last = self._analyses.get(path)
            analysis = analyse_file(ws, tree, previous=last if last is not None and last.snapshot is not None else None,
                                    keep=doc is not None)
            if doc is not None:
                self._analyses[path] = analysis
            if before is not None and analysis.unit is not before and analysis.unit.bundle is not None:
                self.generation += 1  # a bundle file's symbols changed: everything may see them
        diags = self._lint(tree, analysis)
        st = FileState(path, text, doc.version if doc is not None else None, tree, analysis, diags, self.generation,
                       ws.program if ws is not None else None, analysis.unit if analysis is not None else None,
                       frozenset(ws.known_annotations) if ws is not None else frozenset())
        self._states[path] = st
        return st

    def reusable(self, path: str, text: str | None = None) -> bool:
        """Whether an open buffer has an analysis the next check can re-use (model/reuse.py): one
        whose text differs from `text` in at most a tenth of it (a check that re-uses little is
        better done in a forked process, which keeps the server answering)."""
        last = self._analyses.get(path)
        if last is None or last.snapshot is None:
            return False
        if text is None:
            return True
        got = changed_lines(last.unit.tree.text, text)
        return got is None or got[2] - got[0] <= len(text) // 10

    def analysed(self, path: str) -> bool:
        """Whether an open buffer was analysed in this process since it was opened."""
        return path in self._analyses

    def parse_ahead(self, path: str) -> bool:
        """The first half of a check of an open buffer: parse its current text now, so the server
        can answer the requests that arrived meanwhile before the second half (the analysis,
        `state`) runs. True when there was something to parse."""
        doc = self.docs.get(path)
        if doc is None:
            return False
        last = self._trees.get(path)
        if last is not None and last.text == doc.text:
            return False
        st = self._states.get(path)
        if st is not None and st.text == doc.text:
            return False
        self._parse(path, doc.text)
        return True

    def quick_state(self, path: str) -> FileState | None:
        """The current text's symbols without checking it (for completion while typing).

        When the full analysis is current it is returned; otherwise the buffer is parsed
        (incrementally) and its symbols registered, which is what completion needs, and the checker
        waits for the diagnostics debounce. Such a state has no occurrences and no diagnostics.
        """
        doc = self.docs.get(path)
        text = doc.text if doc is not None else self.text_of(path)
        if text is None:
            return None
        ws = self.workspace
        if ws is None:
            return self.state(path)
        self._sync_buffers(path)
        st = self._current(path, text)
        if st is not None:
            return st
        tree = self._parse(path, text)
        before = ws.program.units.get(path)
        unit = ws.unit_for(tree)
        if before is not None and unit is not before and unit.bundle is not None:
            self.generation += 1
        st = FileState(path, text, doc.version if doc is not None else None, tree, None, [], self.generation,
                       ws.program, unit, frozenset(ws.known_annotations))
        self._states[path] = st
        return st

    def line_view(self, path: str, line: int) -> "LineView | None":
        """The buffer's line `line` seen through the file's last analysis, when that analysis is of
        an older text that differs from the buffer on this one line only (a line being typed, or
        inserted): completion answers from it at once, without parsing or registering the new
        text. None when the analysis is current (use it) or the edit is not that local."""
        doc = self.docs.get(path)
        st = self._states.get(path)
        if doc is None or st is None or st.text is doc.text or st.text == doc.text or st.unit is None \
                or st.program is None or st.generation != self.generation or st.program.units.get(path) is not st.unit:
            return None  # (a replaced unit's symbols are taken apart: only the registered one is usable)
        old, new = st.text, doc.text
        if "\r" in old or "\r" in new:
            return None
        got = changed_lines(old, new)
        if got is None:
            return None
        first, old_end, new_end = got  # offsets: the changed lines start at `first`, end at old_end / new_end
        new_region = new[first:new_end]
        old_region = old[first:old_end]
        if new_region.count("\n") + (not new_region.endswith("\n")) != 1 or \
                old_region.count("\n") + (bool(old_region) and not old_region.endswith("\n")) > 1:
            return None
        if new.count("\n", 0, first) != line:
            return None
        text = new_region[:-1] if new_region.endswith("\n") else new_region
        own = line if old_region else -1
        return LineView(st, line, text, first, own, first + (len(old_region.rstrip("\n")) if old_region else 0))

    def _lint(self, tree: ast.File, analysis) -> list[Diagnostic]:
        cfg = self.config(tree.path)
        ws = self._ws
        if ws is None:
            diags = list(tree.diagnostics)
            diags.append(Diagnostic(registry.BUNDLES_UNAVAILABLE, f"OpenPLX bundles unavailable: {self.workspace_error}", EMPTY_SPAN,
                                    Severity.WARNING, file=tree.path))
            return diags
        return final_diagnostics(tree, cfg, analysis)

    def config_reread(self) -> None:
        """A config file changed but chose the same bundle set: its other keys (select, ignore,
        per-file ignores) may differ, so every file's diagnostics are computed again."""
        self._states.clear()
        self.generation += 1

    def user_bundle_roots(self) -> list[str]:
        """The folders of the user bundles loaded now (they may lie outside the workspace)."""
        ws = self._ws
        if ws is None:
            return []
        return sorted(str(b.root) for b in ws.bundles.values() if not b.official)

    def imports_of(self, path: str) -> set[str]:
        """The files an open document imports (by the paths their import statements name now;
        a missing file too: creating it changes the diagnostics)."""

        st = self._states.get(path)
        if st is None or st.tree is None:
            return set()
        known = self._imports_seen.get(path)
        if known is not None and known[0] is st.tree:  # asked after every check: once per tree
            return known[1]
        out = set()
        for stmt in st.tree.statements:
            if isinstance(stmt, ast.Import):
                full, _unset = resolve_file(stmt, path)
                if full is not None and not full.endswith(".openplx"):
                    out.add(full)
        self._imports_seen[path] = (st.tree, out)
        return out

    def import_changed(self, path: str) -> list[str]:
        """A file imported by open documents was created, changed or deleted: those documents are
        analysed afresh (not re-used: an import's check reads the file system). Returns them."""
        hit = [doc for doc in self.docs if path in self.imports_of(doc)]
        for doc in hit:
            self._states.pop(doc, None)
            self._analyses.pop(doc, None)
        return hit

    def dependents(self, path: str) -> list[str]:
        """Open documents whose diagnostics may change when `path` changes."""
        ws = self._ws
        if ws is None:
            return []
        unit = ws.program.units.get(path)
        if unit is None or unit.bundle is None:
            return []
        out = []
        for other in self.docs:
            if other == path:
                continue
            ou = ws.program.units.get(other)
            if ou is None or ou.bundle is None:
                out.append(other)  # loose files see every bundle
            elif unit.bundle in (ws.program.visibility.get(ou.bundle) or {ou.bundle}):
                out.append(other)
        return out

    # ------------------------------------------------------------------ helpers for the features

    def bundle_files(self, bundle: str) -> list[str]:
        ws = self._ws
        if ws is None:
            return []
        return [p for p, u in ws.program.units.items() if u.bundle == bundle]

    def is_official(self, path: str) -> bool:
        ws = self._ws
        if ws is None:
            return False
        unit = ws.program.units.get(path)
        if unit is not None:
            return bool(unit.official)
        try:
            Path(path).resolve().relative_to(ws.official_root)
            return True
        except (ValueError, OSError):
            return False
