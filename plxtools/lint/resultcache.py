"""Per-file lint results kept between runs, as ruff does: an unchanged file is not re-checked.

A result is stored (`plxtools.cache`) under a key made of:

- the file's path, where it leads, and the very bytes that were linted (read once: the key is
  made from the bytes handed to the checker, so a save during the run cannot file one content's
  result under another's key);
- its configuration (every field of the Config in effect, --select/--ignore included);
- the bundle set and the digest of everything loading it read (`workspace.bundle_set_digest`:
  every bundle file by content, every folder listing), which includes plxtools' own code stamp.

With the result go the reads its check made (`cache.reads`): the files its imports name (there
or not) and the environment variables a `$"..."` path read, recorded by the checker itself, and
checked again before the result is believed.

Only loose files are cached: a file inside a bundle is named by its neighbours (and loads them),
so it is always checked. A result with an unknown name (N001/N003) is not stored either: its help
may name a bundle folder found near the file. `--fix`, `--diff` and stdin runs neither read nor
write the cache; `--no-cache` turns it off.

Results are stored as JSON, never as pickles: an entry cannot run code when it is read.
"""

from __future__ import annotations

from pathlib import Path

from plxtools.cache import reads, store
from plxtools.diagnostics import Diagnostic, Edit, Fix, Pos, Severity, Span
from plxtools.rules import registry


def _span(s: Span) -> list:
    return [*s.start, *s.end]


def _unspan(v) -> Span:
    return Span(Pos(v[0], v[1], v[2]), Pos(v[3], v[4], v[5]))


def to_json(d: Diagnostic) -> list:
    fix = None if d.fix is None else [d.fix.message, [[e.start, e.end, e.text] for e in d.fix.edits], d.fix.safe]
    return [d.code, d.message, _span(d.span), d.severity.value, d.file, d.help, fix,
            [[a, _span(s), b] for a, s, b in d.related], d.older_version]


def from_json(v) -> Diagnostic:
    code, message, span, sev, file, help_, fix, related, older = v
    return Diagnostic(code, message, _unspan(span), Severity(sev), file, help_,
                      None if fix is None else Fix(fix[0], tuple(Edit(*e) for e in fix[1]), fix[2]),
                      [(a, _unspan(s), b) for a, s, b in related], older)


def _folder_in_bundle(folder: Path, stop_at: set) -> bool:
    """model.bundles.find_user_bundle_root(...) is not None, without importing the model (and lark)."""
    for d in (folder, *folder.parents):
        if d in stop_at:
            return False
        if reads.is_file(d / "config.openplx"):
            return True
    return False


class ResultCache:
    def __init__(self, bundle_set, stamp: str) -> None:
        """`stamp`: the bundle set's digest (`workspace.bundle_set_digest`, or the loaded
        workspace's `read_digest`)."""
        self.bundle_set = bundle_set
        self.official_root = bundle_set.official_root.resolve() if bundle_set.official_root else None
        self.stamp = f"{stamp}\0{bundle_set.key()!r}\0{bundle_set.official_version}"
        self._bundle_folders: dict[Path, bool] = {}  # folder -> inside a bundle (asked once per run)

    def key(self, path: Path, data: bytes, cfg) -> str | None:
        """The key of this file's result for these bytes, or None when it is not cached (a
        bundle file)."""
        if path.name == "config.openplx":
            return None
        folder = Path(reads.realpath(path)).parent
        inside = self._bundle_folders.get(folder)
        if inside is None:
            stop = {self.official_root} if self.official_root is not None else set()
            inside = self._bundle_folders[folder] = _folder_in_bundle(folder, stop)
        if inside:
            return None
        h = store.new_hash(f"{self.stamp}\0{path}\0{folder}\0{cfg!r}\0".encode())
        h.update(data)
        return h.hexdigest()

    def get(self, key: str | None) -> list | None:
        """The stored diagnostics when every read their check made still holds (those reads are
        then noted as this run's)."""
        entry = store.get_data("results", key) if key is not None else None
        if not isinstance(entry, dict) or not reads.all_hold(entry.get("deps")):
            return None
        try:
            diags = [from_json(v) for v in entry["diags"]]
        except (TypeError, ValueError, KeyError, IndexError):
            return None
        reads.note_all(entry["deps"])
        return diags

    @staticmethod
    def stores(diagnostics: list) -> bool:
        """Whether a result with these diagnostics is kept (see the module's notes)."""
        if not diagnostics:
            return True
        # (imported here: a replay must not load the model; a result to store was just computed with it)

        return not any(d.code in (registry.UNRESOLVED_TYPE, registry.UNRESOLVED_NAME) for d in diagnostics)

    def put(self, key: str | None, deps: list, diagnostics: list) -> None:
        if key is None or not self.stores(diagnostics):
            return
        store.put_data("results", key, {"deps": reads.dedupe(deps), "diags": [to_json(d) for d in diagnostics]})
