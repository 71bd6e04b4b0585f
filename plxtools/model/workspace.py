"""The workspace: official bundles, user bundles and loose files loaded into one Program.

This is the semantic model's front door for lint, the language server and check. The official
bundles' program is kept in plx's cache (`plxtools.cache`), with the record of every file and
folder listing its load read, by content, and plxtools' own code stamp: a one-file lint does not
re-parse 465 bundle files, and never uses a program built from other files or by other code.
"""

from __future__ import annotations

import functools
import os
import pickle
from dataclasses import replace
from pathlib import Path

from plxtools.diagnostics import EMPTY_SPAN, Diagnostic
from plxtools.model.bundles import Bundle, dependency_closure, find_user_bundle_root, read_config
from plxtools.model.checker import Checker, Occurrence
from plxtools.model import facts
from plxtools.model.facts import Fact
from plxtools.model.imports import is_editor_buffer
from plxtools.model.program import Program
from plxtools.model.symbols import FileUnit, Namespace
from plxtools.model.versions import BundleSet, BundleSetError, bundle_roots_in, explicit_bundle_set
from plxtools.runmode import is_one_shot
from plxtools.syntax import ast, parse_bytes





class _Reuse:
    """model/reuse.py, imported on first use: only the language server re-uses analyses, so a
    `plx lint` run does not import it."""

    def __getattr__(self, name: str):
        from plxtools.model import reuse as module

        return getattr(module, name)


reuse = _Reuse()


class WorkspaceError(BundleSetError):
    """A bundle setup that cannot be used (missing bundle folder, folder without config)."""


class FileAnalysis:
    """What the model says about one file: its unit, diagnostics, facts (model/facts.py: the
    findings the rules layer reports) and occurrences (names and what they refer to).
    `occurrences` may be given as a reuse.Occurrences, built when first read."""

    __slots__ = ("unit", "diagnostics", "_occurrences", "snapshot", "plan", "facts")

    def __init__(self, unit: FileUnit, diagnostics: list[Diagnostic], occurrences,
                 snapshot: "reuse.Snapshot | None" = None, plan: "reuse.Plan | None" = None, facts: list = ()):
        self.unit = unit
        self.diagnostics = diagnostics
        self.facts = facts
        self._occurrences = occurrences
        self.snapshot = snapshot  # for re-using this analysis in the next version's
        self.plan = plan  # how this analysis re-used the previous one (None: it did not)

    @property
    def lazy_occurrences(self):
        """The occurrences as they are: a list, or a reuse.Occurrences not built yet."""
        return self._occurrences

    @property
    def occurrences(self) -> list[Occurrence]:
        got = self._occurrences
        if not isinstance(got, list):  # a reuse.Occurrences (checking `list` keeps reuse unimported)
            got = self._occurrences = got.all()
        return got


def _load_cached(kind: str, key: str):
    """An authenticated pickle of plx's cache (`plxtools.cache.store`), or None. The payload is
    unpickled only after its tag proved this user's plx wrote it."""
    from plxtools.cache import store

    data = store.get(kind, key)
    if data is None:
        return None
    import gc

    enabled = gc.isenabled()
    gc.disable()  # ~50k acyclic nodes: collection passes during the load are pure cost
    try:
        value = pickle.loads(data)
        gc.freeze()  # long-lived: keep the collector from rescanning them on every later pass
        return value
    except Exception:  # an entry of another shape is rebuilt, never trusted
        return None
    finally:
        if enabled:
            gc.enable()


def _store_cached(writes: list) -> None:
    """Write cache entries [(kind, key, value, as_data)]. In a one-shot CLI process
    (`runmode.is_one_shot()`: only the console entry says so) a forked child writes them: pickling the bundle
    program is about a third of a cold run, and the child does it on a snapshot of the program as
    it is now (copy-on-write, so the file is what the parent would have written) while the parent
    checks and reports. The child holds none of the parent's standard streams (a caller waiting
    for their end is not kept waiting), runs in its own session (a Ctrl-C of the command does not
    cut it off) and at a lower priority, and leaves with os._exit. Entries are replaced
    atomically, in order (the program before the record that names it)."""
    from plxtools.cache import folder

    if folder.root() is None or folder.secret() is None:
        return
    pid = -1
    if is_one_shot() and hasattr(os, "fork"):
        try:
            pid = os.fork()
        except OSError:
            pid = -1
    if pid > 0:
        return  # the parent goes on
    if pid < 0:
        _write_cached(writes)
        return
    try:  # the child
        try:
            null = os.open(os.devnull, os.O_RDWR)
            for fd in (0, 1, 2):
                os.dup2(null, fd)
            os.setsid()
            os.nice(5)
        except OSError:
            pass
        _write_cached(writes)
    finally:
        os._exit(0)


def _write_cached(writes: list) -> None:
    from plxtools.cache import store
    from plxtools.diagnostics import Pos, Span
    from plxtools.pickling import tuple_reducers

    for kind, key, value, as_data in writes:
        if as_data:
            if not store.put_data(kind, key, value):
                return
            continue
        import io
        import sys

        limit = sys.getrecursionlimit()
        sys.setrecursionlimit(max(limit, 20000))  # the namespace tree links parents and children
        try:
            buf = io.BytesIO()
            pickler = pickle.Pickler(buf, protocol=pickle.HIGHEST_PROTOCOL)
            # about 45k positions and spans: rebuilt by tuple.__new__, not their Python __new__
            pickler.dispatch_table = tuple_reducers(Pos, Span)
            pickler.dump(value)
        except (pickle.PicklingError, RecursionError, TypeError, AttributeError):
            return
        finally:
            sys.setrecursionlimit(limit)
        if not store.put(kind, key, buf.getvalue()):
            return


def bundle_set_digest(bs: BundleSet) -> str | None:
    """The digest of everything loading this bundle set read last time, if each of those reads
    still gives the same (`plxtools.cache.records`), else None: the set must be loaded to know."""
    from plxtools.cache import records

    return records.recorded_digest(_set_key(bs))


def _set_key(bs: BundleSet) -> str:
    from plxtools.cache import records
    from plxtools.cache.stamp import code_stamp

    return records.set_key(code_stamp(), bs.key()[:2], bs.official_version)  # (the program does not depend on `pinned`)


def _parse_path(path) -> ast.File:
    """parse_file(path), its bytes noted as read (`plxtools.cache.reads`)."""
    from plxtools.cache import reads

    return parse_bytes(reads.read_bytes(path), str(path))


class Workspace:
    """One bundle set loaded into one Program. Several can live side by side (one per version)."""

    def __init__(self, bundle_paths: list[Path] | None = None, use_cache: bool = True,
                 bundle_set: BundleSet | None = None):
        self.program = Program()
        self.bundles: dict[str, Bundle] = {}
        self.use_cache = use_cache
        self.errors: list[str] = []
        self.known_annotations: set[str] = set()
        self._loose_ns: dict[str, Namespace] = {}
        self._nearby: dict[Path, dict[str, Path]] = {}
        self._plain_folders: set[str] = set()  # folders in no user bundle (one-shot commands: bundle_of)
        if bundle_set is None:
            try:
                bundle_set = explicit_bundle_set([Path(p) for p in bundle_paths or []])
            except BundleSetError as exc:  # callers of the library API catch WorkspaceError
                raise WorkspaceError(str(exc)) from None
        self.bundle_set = bundle_set
        from plxtools.cache import reads

        with reads.recording() as deps:
            self._load(bundle_set)
        self.read_deps = reads.dedupe(deps)  # what loading the set read (`bundle_set_digest`)
        from plxtools.cache.stamp import code_stamp

        self.read_digest = f"{code_stamp()}-{reads.content_digest(self.read_deps)}"
        if use_cache:  # small: written here, not by a forked child
            from plxtools.cache import store

            store.put_data("bundle-sets", _set_key(bundle_set), {"deps": self.read_deps, "digest": self.read_digest})

    def _load(self, bundle_set: BundleSet) -> None:
        official, user = self._plan(bundle_set)
        root = bundle_set.official_root or (official[0][0].parent if official else None)
        if root is None:
            raise WorkspaceError("cannot find the OpenPLX bundles: install openplx-bundles, set "
                                 "OPENPLX_BUNDLE_PATH, or pass --bundle-path")
        self.official_root = root.resolve()
        self._load_official(official)
        for folder, why in user:
            b = self._load_user_bundle(folder)
            b.origin = b.origin or why
        self._compute_visibility()

    # ------------------------------------------------------------------ loading

    def _plan(self, bs: BundleSet) -> tuple[list[tuple[Path, str, str | None]], list[tuple[Path, str]]]:
        """Official bundles (root, why, version) after replacements by name, and the user bundle folders."""
        from plxtools.model.versions import _config_name

        official: dict[str, tuple[Path, str, str | None]] = {}
        if bs.official_root is not None:
            for d in bundle_roots_in(bs.official_root):
                official[_config_name(d)] = (d.resolve(), bs.official_why, bs.official_version)
        base_names = set(official) or {"Math", "Physics", "Physics1D", "Physics3D", "DriveTrain", "Robotics",
                                       "Simulation", "Terrain", "Urdf", "Vehicles", "Visuals"}
        replaced: set[str] = set()
        user: list[tuple[Path, str]] = []
        for src in bs.sources:
            for d in bundle_roots_in(src.path):
                name = _config_name(d)
                if name in base_names:
                    if name in replaced:
                        continue  # an earlier source already replaced it: first wins, as in the order
                    replaced.add(name)
                    official[name] = (d.resolve(), f"replaces the official bundle: {src.why}", None)
                else:
                    user.append((d, src.why))
        if {"Math", "Physics"} <= replaced:
            # a whole official set (an AGX installation, a copy of a release): drop the base's other
            # bundles too, they belong to another version
            official = {n: v for n, v in official.items() if n in replaced}
        return sorted(official.values(), key=lambda t: str(t[0])), user

    def _load_official(self, plan: list[tuple[Path, str, str | None]]) -> None:
        """Parse the official bundles and build their symbols, or load both from the disk cache.

        The pickle is named by the set of bundle folders, so switching between versions or sets keeps
        each one's cache warm, and by every file's size and mtime, so an edited bundle invalidates it.
        """
        from plxtools.cache import reads, store
        from plxtools.cache.stamp import code_stamp

        bundles = [Bundle(root.name, root, official=True, origin=why) for root, why, _v in plan]
        set_key = store.new_hash(repr((code_stamp(), [str(b.root) for b in bundles])).encode()).hexdigest()
        if self.use_cache:  # the record of the last load: what it read, and the program it built
            record = store.get_data("bundle-sets", set_key)
            state = None
            if isinstance(record, dict) and reads.all_hold(record.get("deps")):
                state = _load_cached("programs", str(record.get("program")))
            if isinstance(state, dict) and state.get("files") == record.get("files"):
                reads.note_all(record["deps"])
                self.program = state["program"]
                self.bundles = state["bundles"]
                self.known_annotations = state["annotations"]
                why = {root: w for root, w, _v in plan}
                for b in self.bundles.values():  # the reason is this run's, not the cached run's
                    b.origin = why.get(b.root, b.origin)
                return
        with reads.recording() as deps:
            files: list[str] = []  # strings, not Paths: a cold run lists, reads and registers 465 of them
            per_bundle: list[list[str]] = []
            for b in bundles:
                files.append(os.path.join(str(b.root), "config.openplx"))
                per_bundle.append(b.file_names())
                files.extend(per_bundle[-1])
            trees = {p: _parse_path(p) for p in files}
        for b, listed in zip(bundles, per_bundle):
            read_config(b, trees[os.path.join(str(b.root), "config.openplx")])
            self.bundles[b.name] = b
            self.program.official_bundles.add(b.name)
            for f in listed:
                unit = FileUnit(f, trees[f], self.program.namespace(b.namespace_of_name(f), b.name), b.name,
                                official=True)
                self.program.add_unit(unit)
        for tree in trees.values():
            for s in ast.walk_statements(tree.statements):
                if isinstance(s, ast.Annotation):
                    self.known_annotations.add(s.name.name)
        if self.use_cache:
            deps = reads.dedupe(deps)
            program = f"{code_stamp()}-{reads.content_digest(deps)}"
            # now, before user bundles join the program: the child pickles this moment's snapshot
            _store_cached([("programs", program, {"files": len(files), "program": self.program,
                                                  "bundles": self.bundles, "annotations": self.known_annotations},
                            False),
                           ("bundle-sets", set_key, {"deps": deps, "program": program, "files": len(files)}, True)])

    def add_bundle_folder(self, folder: Path) -> None:
        """A configured bundle folder: a bundle itself, or a folder of bundles."""
        if not folder.is_dir():
            raise WorkspaceError(f"bundle path {folder} is not a folder")
        if (folder / "config.openplx").is_file():
            self._load_user_bundle(folder)
            return
        subs = [d for d in sorted(folder.iterdir()) if (d / "config.openplx").is_file()]
        if not subs:
            raise WorkspaceError(f"bundle path {folder} has no config.openplx (a bundle needs one at its root)")
        for d in subs:
            self._load_user_bundle(d)

    def _load_user_bundle(self, root: Path) -> Bundle:
        root = root.resolve()  # bundle roots are kept resolved, so containment is a parents check
        for b in self.bundles.values():
            if b.root.resolve() == root:
                return b
        b = Bundle(root.name, root, official=False)
        read_config(b, _parse_path(root / "config.openplx"))
        if b.name in self.bundles and self.bundles[b.name].root.resolve() != root:
            b.diagnostics.append(facts.UnknownDependency(EMPTY_SPAN, b.name, str(self.bundles[b.name].root)))
            return b
        self.bundles[b.name] = b
        for f in b.files():
            self._add_bundle_file(b, f, _parse_path(f))
        self._compute_visibility()
        return b

    def _add_bundle_file(self, b: Bundle, path: Path, tree: ast.File) -> FileUnit:
        ns = self.program.namespace(b.namespace_of(path), b.name)
        unit = FileUnit(str(path), tree, ns, b.name, official=b.official)
        self.program.add_unit(unit)
        return unit

    def _compute_visibility(self) -> None:
        for name in self.bundles:
            closure, _cycle = dependency_closure(self.bundles, name)
            self.program.visibility[name] = closure

    # ------------------------------------------------------------------ files

    def bundle_of(self, path: Path) -> Bundle | None:
        rp = str(path.resolve())
        for b in self.bundles.values():
            root = str(b.root)  # below the root: the root's path and a separator start the file's
            if rp.startswith(root) and len(rp) > len(root) and (rp[len(root)] == os.sep or root.endswith(os.sep)):
                return b
        # a one-shot command's files do not move into a bundle while it runs: a folder found to be in
        # none is not walked up again for each of its files (the language server always asks)
        one_shot = is_one_shot()
        folder = os.path.dirname(rp)
        if one_shot and folder in self._plain_folders:
            return None
        user_root = find_user_bundle_root(path, {self.official_root})
        if user_root is not None:
            return self._load_user_bundle(user_root)
        if one_shot:
            self._plain_folders.add(folder)
        return None

    def unit_for(self, tree: ast.File) -> FileUnit:
        """Register (or replace) a file's symbols and return its unit."""
        path = tree.path or "<stdin>"
        existing = self.program.units.get(path)
        if existing is not None and existing.tree is tree:
            return existing
        if existing is None and tree.path:
            existing = self.program.units.get(str(Path(path).resolve()))
        if existing is not None and existing.tree.text == tree.text:
            return existing
        # an editor buffer named by a URI (`untitled:Untitled-1`) is no file: it belongs to no bundle
        bundle = self.bundle_of(Path(path)) if tree.path and not is_editor_buffer(path) else None
        if existing is None and bundle is not None:
            # finding the bundle may just have loaded it, this file included
            existing = self.program.units.get(str(Path(path).resolve())) or self.program.units.get(path)
            if existing is not None and existing.tree.text == tree.text:
                return existing
        if existing is not None:
            self.program.remove_unit(existing.path)
        if bundle is not None and Path(path).name == "config.openplx" and Path(path).resolve().parent == bundle.root.resolve():
            unit = FileUnit(existing.path if existing else path, tree, self.program.namespace((bundle.name,), bundle.name),
                            bundle.name, official=bundle.official)
            self.program.units[unit.path] = unit
            return unit
        if bundle is not None:
            ns = self.program.namespace(bundle.namespace_of(Path(path)), bundle.name)
            unit = FileUnit(existing.path if existing else path, tree, ns, bundle.name, official=bundle.official)
        else:
            ns = self._loose_ns.setdefault(path, Namespace("", ()))
            unit = FileUnit(path, tree, ns, None)
        self.program.add_unit(unit)
        if existing is not None and bundle is not None:
            self.program.invalidate(unit.path)  # a bundle file changed: any model may see its symbols
        return unit

    def forget_loose(self, path: str) -> None:
        """Drop a loose file's unit once a one-shot command is done with it (no other file can
        name a loose file's symbols), so a run over many files keeps only the file at hand."""
        unit = self.program.units.get(path)
        if unit is not None and unit.bundle is None:
            self.program.remove_unit(path)
            self._loose_ns.pop(path, None)

    def analyse(self, tree: ast.File, previous: "reuse.Snapshot | None" = None, keep: bool = False) -> FileAnalysis:
        """What the model itself says about a file: names, types, bundle config. The rules that
        judge a resolved file (completeness, conventions) run on top of this in plxtools.rules.

        `keep`: make a snapshot for the next version (the language server); `previous`: the
        snapshot of this file's last analysis, whose findings are re-used for the statements whose
        key did not change (model/reuse.py)."""
        path = tree.path or "<stdin>"
        others = self.program.epoch_without(path)
        unit = self.unit_for(tree)
        plan = reuse.plan(previous, self.program, unit, others, self.known_annotations) if keep or previous else None
        checker = Checker(self.program, unit, self.known_annotations)
        checker.run(plan.dirty if plan is not None else None)
        if plan is None:
            diags, occurrences, snap = checker.diags, checker.occurrences, None
        else:
            diags, occurrences, snap = reuse.assemble(checker, plan, unit, self.program, self.known_annotations,
                                                      Occurrence)
        diags += self._bundle_config_diagnostics(tree)
        found = [d for d in diags if isinstance(d, Fact)]
        if found:
            diags = [d for d in diags if not isinstance(d, Fact)]
        for d in diags:
            d.file = tree.path
        self._help_for_unloaded_bundles(tree, found)
        self._help_for_other_versions(tree, found, occurrences)
        return FileAnalysis(unit, diags, occurrences, snap, plan, found)

    def _help_for_unloaded_bundles(self, tree: ast.File, found: list) -> None:
        """`Name.X` unknown, without a better hint, and a bundle called Name sits nearby but is not
        loaded (or is a dependency, or is AGX's own): the fact says which bundle and where."""
        unknown = [i for i, f in enumerate(found) if _without_hint(f)]
        if not unknown or not tree.path or is_editor_buffer(tree.path):
            return
        nearby = self.nearby_bundles(Path(tree.path).resolve().parent)
        home = self.bundle_of(Path(tree.path))
        wanted = set(home.dependencies) if home is not None else set()
        for i in unknown:
            f = found[i]
            # the first name of what was written where the fact points (`Name` of `Name.X`)
            name = tree.text[f.span.start.offset:f.span.end.offset].split(".", 1)[0].strip().strip("`")
            if not name.isidentifier() or name in self.bundles:
                continue
            if name in nearby:
                found[i] = replace(f, bundle=("nearby", name, str(nearby[name])))
            elif name in wanted:
                found[i] = replace(f, bundle=("dependency", name, str(home.root / "config.openplx")))
            elif name == "AGX":
                agx = getattr(getattr(self, "bundle_set", None), "agx", None)
                if agx is not None and agx.agx_bundle is not None:
                    found[i] = replace(f, bundle=("agx", agx.describe(), str(agx.agx_bundle)))
                else:
                    found[i] = replace(f, bundle=("agx", None, None))

    def _help_for_other_versions(self, tree: ast.File, found: list, occurrences=None) -> None:
        """An unknown type that another official OpenPLX version has. When the API index says it
        moved or was renamed one to one by the version in use, it is U001 with a safe fix to the new
        name; otherwise the help says which versions have it, so the user migrates (or chooses that
        version) instead of hunting for a typo. Help lines that say to migrate print a `plx migrate`
        command that works as printed for this file (model/written_for.py)."""
        bs = getattr(self, "bundle_set", None)
        using = getattr(bs, "official_version", None)
        attrs = [i for i, f in enumerate(found) if isinstance(f, facts.UnknownAttribute)]
        unknown = [i for i, f in enumerate(found) if isinstance(f, facts.UnknownType)]
        if not using or not (attrs or unknown):
            return
        from plxtools.model.written_for import MigrateHint

        path = tree.path if tree.path and not is_editor_buffer(tree.path) else None
        hint = MigrateHint(path, tree.text, found, occurrences, using, getattr(bs, "pinned", True))
        self._renamed_attributes(tree, found, attrs, using, hint)
        for i in unknown:
            found[i] = self._older_type(tree, found[i], using, hint)

    def _older_type(self, tree: ast.File, d: facts.UnknownType, using: str, hint) -> facts.Fact:
        """One unknown type: U001 when a release before `using` had it and it was renamed one to one,
        else a note of the versions that have it (or of newer bundles that might)."""
        from plxtools.model.apiindex import UnknownVersion, spans, version_key, where_defined

        bs = getattr(self, "bundle_set", None)
        written = tree.text[d.span.start.offset:d.span.end.offset]
        if "." not in written or not written.replace(".", "").replace("_", "").isalnum():
            return d
        found = [v for v in where_defined(written) if v != using]
        if not found:
            if not where_defined(written) and written.split(".", 1)[0] in self.bundles:
                from plxtools.model.agx import newer_bundles
                from plxtools.model.apiindex import versions

                newer = newer_bundles(written, bs, versions()[-1], typo=d.suggestion is not None)
                if newer:
                    return replace(d, newer=newer)
            return d
        older = [v for v in found if version_key(v) < version_key(using)]
        try:
            moved = _moved_to(written, older[-1], using) if older else None
        except UnknownVersion:
            moved = None
        new = moved.new if moved is not None else None
        if new is not None and self._resolves(new, tree):
            return facts.OlderName(d.span, written, new, older[-1], using, moved.handling == "declared",
                                   hint.command(older[-1]))
        return replace(d, versions=(written, spans(found), found[-1], using))

    def _renamed_attributes(self, tree: ast.File, found: list, unknown: list[int], using: str, hint) -> None:
        """An unknown attribute that official versions before `using` renamed (`charges` ->
        `connectors`): U002 with the new name. The fix is unsafe: the index knows which models
        renamed it, and the user confirms that this is one of them."""
        if not unknown:
            return
        renamed = _renamed_attributes_before(using, self.use_cache)
        converted = []
        for i in unknown:
            d = found[i]
            written = tree.text[d.span.start.offset:d.span.end.offset]
            targets = [t for t in renamed.get(written, ()) if self._may_own(tree, d, t[3] if len(t) > 3 else None)]
            if not targets or len({t[0] for t in targets}) != 1:
                continue
            new, model, since = targets[0][:3]
            owners = ", ".join(sorted({t[1] for t in targets})[:3])
            found[i] = facts.RenamedAttribute(d.span, written, new, since, owners, _version_before(since))
            converted.append(i)
        for i in converted:  # (after all: the command may infer the version from every U002)
            found[i] = replace(found[i], command=hint.command(found[i].older_version))

    def _may_own(self, tree: ast.File, d: facts.UnknownAttribute, model: str | None) -> bool:
        """Whether the object the unknown attribute is set on (the fact's owner) may be one of the
        models that renamed it (`model`, by its name in the version in use): itself or a subtype,
        so that `body:` on an unrelated model keeps its did-you-mean. Unsure (no name, a value of a
        type that is no model, a kind of the owner that has it): yes."""
        from plxtools.model.symbols import ModelSym

        if model is None or d.on_value or d.kind_of is not None:
            return True
        unit = self.program.units.get(tree.path) if tree.path else None
        try:
            sym = (self.program.lookup(d.owner.split("."), unit) if unit is not None else None) \
                or self.program.lookup_outside_visibility(d.owner.split("."))
            want = self.program.lookup_outside_visibility(model.split("."))
        except Exception:  # noqa: BLE001 - a lookup for a hint must never break the analysis
            return True
        if not isinstance(sym, ModelSym) or not isinstance(want, ModelSym):
            return not isinstance(want, ModelSym) or sym is None
        return any(a is want for a in self.program.ancestors(sym))

    def _resolves(self, qname: str, tree: ast.File) -> bool:
        from plxtools.model.symbols import ModelSym

        unit = self.program.units.get(tree.path) if tree.path else None
        try:
            return isinstance(self.program.lookup(qname.split("."), unit), ModelSym)
        except Exception:  # noqa: BLE001 - a lookup for a hint must never break the analysis
            return False

    def nearby_bundles(self, folder: Path, levels: int = 3) -> dict[str, Path]:
        """Bundles (by config name) in `folder`, its parents up to `levels` up, and their subfolders."""
        if folder in self._nearby:
            return self._nearby[folder]
        from plxtools.model.versions import _config_name

        out: dict[str, Path] = {}
        for d in [folder, *list(folder.parents)[:levels]]:
            for r in bundle_roots_in(d):
                out.setdefault(_config_name(r), r)
        self._nearby[folder] = out
        return out

    def _bundle_config_diagnostics(self, tree: ast.File) -> list:
        """The facts about a bundle's config.openplx (model/facts.py), when `tree` is one."""
        if not tree.path or Path(tree.path).name != "config.openplx":
            return []
        folder = Path(tree.path).resolve().parent
        b = next((b for b in self.bundles.values() if b.root.resolve() == folder), None)
        if b is None:
            return []
        out = list(b.diagnostics)
        for dep in b.dependencies:
            if dep not in self.bundles:
                out.append(facts.UnknownDependency(b.dep_spans.get(dep, EMPTY_SPAN), dep))
        _closure, cycle = dependency_closure(self.bundles, b.name)
        if cycle:
            out.append(facts.DependencyCycle(b.dep_spans.get(cycle[1], EMPTY_SPAN) if len(cycle) > 1 else EMPTY_SPAN,
                                             tuple(cycle)))
        return out


def _without_hint(f) -> bool:
    """An unknown type or name for which the model has no better hint than a bundle to load."""
    if isinstance(f, facts.UnknownType):
        return f.suggestion is None and f.listing is None
    return isinstance(f, facts.UnknownName) and f.suggestion is None and f.broken_line is None


_CLI_WORKSPACES: dict[tuple, Workspace] = {}


def workspace_for_cli(bundle_paths: list[str], files: list[Path], use_cache: bool = True,
                      openplx_version: str | None = None) -> Workspace:
    """The workspace for a CLI run over `files`: their bundle set (see model/versions.py), loaded once."""
    from plxtools.model.versions import resolve_bundle_set

    bs = resolve_bundle_set(list(files), bundle_paths, openplx_version)
    return workspace_for_set(bs, use_cache)


def forget_cli_workspaces() -> None:
    """Drop the workspaces kept for this process's runs: the next run loads the user bundles again
    (a long-running command whose user bundle files changed on disk, ``plx view``)."""
    _CLI_WORKSPACES.clear()


def workspace_for_set(bs: BundleSet, use_cache: bool = True) -> Workspace:
    """One Workspace per bundle set and process: several sets (versions) can be loaded side by side."""
    key = (bs.key(), use_cache)
    if key not in _CLI_WORKSPACES:
        _CLI_WORKSPACES[key] = Workspace(use_cache=use_cache, bundle_set=bs)
    return _CLI_WORKSPACES[key]


def workspace_for_folder(folder: Path | None, bundle_paths: list[str] = (), openplx_version: str | None = None,
                         use_cache: bool = True) -> Workspace:
    """The language server's entry: the workspace of an editor workspace folder (same order as the CLI).

    Raises BundleSetError (a ValueError) with a one-line message when the setup cannot be used. Call
    again after a config file (plx.toml, pyproject.toml, config.openplx) changes: an unchanged set
    returns the same Workspace, a changed one a new Workspace.
    """
    return workspace_for_set(bundle_set_for_folder(folder, bundle_paths, openplx_version), use_cache)


def bundle_set_for_folder(folder: Path | None, bundle_paths: list[str] = (), openplx_version: str | None = None):
    """The bundle set of an editor workspace folder, in the CLI's order (raises BundleSetError).

    A server that edits its model (open buffers, added bundle folders) builds its own Workspace
    from this set, so two servers or hosts in one process never share mutable state."""
    from plxtools.model.versions import resolve_bundle_set

    root = Path(folder) if folder is not None else None
    return resolve_bundle_set([], list(bundle_paths), openplx_version, workspace_root=root)


def describe_bundle_set(ws: Workspace) -> list[dict]:
    """The bundles in use, for --show-settings and the server: name, version, folder, why."""
    out = []
    for b in sorted(ws.bundles.values(), key=lambda b: (not b.official, b.name)):
        out.append({"name": b.name, "version": b.version or "", "folder": str(b.root),
                    "official": b.official, "why": b.origin})
    return out


def _moved_to(qname: str, old_v: str, new_v: str):
    """The change that moved or renamed a model one to one between two versions (apichanges.renamed_model)."""
    from plxtools.model.apichanges import renamed_model

    return renamed_model(qname, old_v, new_v)


@functools.lru_cache(maxsize=8)
def _version_before(version: str) -> str | None:
    """The official version indexed just before ``version`` (None for the first)."""
    from plxtools.model.apiindex import versions

    known = list(versions())
    i = known.index(version) if version in known else 0
    return known[i - 1] if i > 0 else None


@functools.lru_cache(maxsize=8)
def _renamed_attributes_before(using: str, use_cache: bool = True) -> dict[str, list[tuple]]:
    """old attribute name -> [(new name, model, first version, the model's name in `using`)] for
    renames from the oldest indexed version up to `using`, one to one (from the index, the reviewed
    table or OpenPLX's declared list).

    Composing the changes diffs every pair of consecutive indexed versions (about 1.5 s of CPU), so
    the answer is kept per process and in plx's cache folder, keyed by the index's files and the
    code that diffs them (shared: callers only read it)."""
    from plxtools.model.apichanges import MECHANICAL, changes
    from plxtools.model.apiindex import versions

    out: dict[str, list[tuple[str, str, str]]] = {}
    first = versions()[0]
    if first == using:
        return out
    name = None
    if use_cache:  # the index and the code that diffs it are plxtools' own files: the code stamp
        from plxtools.cache import store
        from plxtools.cache.stamp import code_stamp

        name = store.new_hash(f"renames\0{code_stamp()}\0{using}".encode()).hexdigest()
        got = store.get_json("renames", name)
        if isinstance(got, dict):
            return {k: [tuple(t) for t in v] for k, v in got.items()}
    cs = changes(first, using)
    moved = {c.old: c.new for c in cs if c.kind in ("model-moved", "model-renamed") and c.handling in MECHANICAL}
    for c in cs:
        if c.kind == "attr-renamed" and c.handling in MECHANICAL and c.old and c.new:
            out.setdefault(c.old, []).append((c.new, c.model, c.since, moved.get(c.model, c.model)))
    if name is not None:
        store.put_json("renames", name, out)
    return out
