"""Which official OpenPLX version a file was written for, inferred from the names it uses.

When nothing pins a version (no flag, config or dependency), plx lints with the installed
bundles; a file written for an older release then fails with names that release had. The release
under which the file's official names (qualified types, `Model.attr` of the attributes it sets)
exist best is the one it was written for: ties go to the newest, the shortest migration. Only the
stored API index is read (its name summary), and only for a file with errors of the kinds a
version explains (unknown types and attributes, older names), so a clean file costs nothing.
"""

from __future__ import annotations

from dataclasses import dataclass


def version_sensitive() -> tuple[type, ...]:
    """The facts a version change explains (model/facts.py): an unknown type or attribute, a name
    of an older version (the last: an attribute renamed since)."""
    from plxtools.model import facts

    return (facts.UnknownType, facts.UnknownAttribute, facts.OlderName, facts.RenamedAttribute)


@dataclass(frozen=True)
class Inference:
    """The release a file was written for, and the evidence."""

    version: str
    names: int  # distinct official names the file uses, of any indexed version
    missing: int  # of them, absent in `version`
    missing_in_use: int  # absent in the version in use
    fits: tuple[str, ...] = ()  # every release that fits as well as `version` (it is the newest)

    def newest_fit(self, at_most: str) -> str | None:
        """The newest release that fits the file best and is not newer than `at_most`."""
        from plxtools.model.apiindex import version_key

        ok = [v for v in self.fits if version_key(v) <= version_key(at_most)]
        return ok[-1] if ok else None

    def why(self, using: str) -> str:
        have = self.names - self.missing
        return (f"inferred from the file's content: {have} of the {self.names} official names it uses exist in "
                f"OpenPLX {self.version}, {self.names - self.missing_in_use} in {using}")


def _dotted_names(text: str) -> set[str]:
    """Every dotted name of two parts or more in the code (not in comments or strings)."""
    from plxtools.syntax.dotted import dotted_runs

    return {".".join(str(t) for t in run) for run in dotted_runs(text) if len(run) > 1}


def _official_names(text: str, occurrences) -> dict[str, list[str]]:
    """Official name -> the indexed versions that have it: the longest defined leading part of each
    dotted name, and `Model.attr` for every attribute the file resolves to an official model's."""
    from plxtools.model.apiindex import where_defined

    found: dict[str, list[str]] = {}
    for dotted in _dotted_names(text):
        parts = dotted.split(".")
        for n in range(len(parts), 1, -1):
            name = ".".join(parts[:n])
            have = where_defined(name)
            if have:
                found[name] = have
                break
    if occurrences is not None and not isinstance(occurrences, list) and hasattr(occurrences, "all"):
        occurrences = occurrences.all()  # the language server's re-used analysis: built on first read
    if isinstance(occurrences, list):
        from plxtools.model.symbols import MemberSym

        for occ in occurrences:
            t = occ.target
            if isinstance(t, MemberSym) and t.owner is not None:
                name = f"{t.owner.qname}.{t.name}"
                if name not in found:
                    have = where_defined(name)
                    if have:
                        found[name] = have
    return found


def _missing(allv, names: dict[str, list[str]], renamed_since: list[str]) -> dict[str, int]:
    """Per release, how many of the file's official names it lacks."""
    from plxtools.model.apiindex import version_key

    missing = {v: 0 for v in allv}
    for have in names.values():
        have_set = set(have)
        for v in allv:
            missing[v] += v not in have_set
    for before in renamed_since:
        for v in allv:
            missing[v] += version_key(v) > version_key(before)
    return missing


def infer(text: str, found, occurrences, using: str | None) -> Inference | None:
    """The release the text was written for when it is not `using` (None: no version-sensitive
    fact among the model's `found`, nothing official in the text, or `using` fits it at least as well)."""
    sensitive = version_sensitive()
    if not any(isinstance(d, sensitive) for d in found):
        return None
    from plxtools.model.apiindex import version_key, versions

    allv = versions()
    names = _official_names(text, occurrences)
    # an attribute an older version renamed (U002): absent from the version of the rename on
    renamed_since = [d.older_version for d in found if isinstance(d, sensitive[3]) and d.older_version]
    if not names and not renamed_since:
        return None
    missing = _missing(allv, names, renamed_since)
    total = len(names) + len(renamed_since)
    best = min(allv, key=lambda v: (missing[v], [-x for x in version_key(v)]))
    if using is not None and using not in missing:  # AGX's bundles: compare with the release before them
        older = [v for v in allv if version_key(v) <= version_key(using)]
        using = older[-1] if older else None
    in_use = missing[using] if using else total
    if best == using or missing[best] >= in_use:
        return None
    return Inference(best, total, missing[best], in_use, tuple(v for v in allv if missing[v] == missing[best]))


def infer_file(ws, path) -> Inference | None:
    """`infer` for a file on disk, analysed in workspace `ws` (None: unreadable or not parsed: the
    command reports that itself)."""
    from plxtools.syntax import parse_text

    try:
        text = path.read_bytes().decode("utf-8-sig")
    except (OSError, UnicodeDecodeError):
        return None
    tree = parse_text(text, str(path))
    if tree.has_errors_of_syntax():
        return None
    fa = ws.analyse(tree)
    using = getattr(getattr(ws, "bundle_set", None), "official_version", None)
    return infer(text, fa.facts, fa.occurrences, using)


class MigrateHint:
    """The `plx migrate` command lint's help lines print for one file: one that works as printed.

    Without a pin, `plx migrate --to V FILE` infers the version the file was written for as lint
    does here, so that is what is printed when the inference finds one; otherwise (a pin says the
    version, or the content cannot tell) the command names `--from`: the inferred version, else the
    older version the diagnostic itself knows."""

    def __init__(self, path: str | None, text: str, found, occurrences, using: str, pinned: bool):
        self.path, self.text, self.found, self.occurrences = path, text, found, occurrences
        self.using, self.pinned = using, pinned
        self._inferred: list = []

    def inferred(self) -> Inference | None:
        if not self._inferred:
            self._inferred.append(infer(self.text, self.found, self.occurrences, self.using))
        return self._inferred[0]

    def command(self, older: str | None) -> str:
        import shlex

        target = f" {shlex.quote(self.path)}" if self.path else " FILE"
        found = self.inferred()
        if found is not None and not self.pinned:
            return f"`plx migrate --to {self.using}{target}`"
        frm = found.version if found is not None else older
        return f"`plx migrate --from {frm or 'VERSION'} --to {self.using}{target}`"
