"""The two ends of a migration: the bundles the files are linted with today and the version asked for.

Each end is a bundle set plx can load (the same `resolve_bundle_set` rule as `plx lint` and
`plx check`: config, dependency pins, an AGX installation, the installed package) and the API
index that describes it. An official release is described by plx's stored index; bundles that are
in no release (an AGX installation ships newer ones, or AGX's copy of a release) are indexed at run
time from their folder with the same code (`model/apiindex/build.py`), so a migration between an
AGX bundle set and a PyPI release diffs like one between two releases.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from plxtools.model.apiindex import ApiIndex, load, version_key, versions
from plxtools.model.versions import VERSION_RE, BundleSet, BundleSetError, resolve_bundle_set
from plxtools.config import config_for
from plxtools.migrate.rewrite import plan, plan_of
from plxtools.model.agx import find_agx
from plxtools.model.apichanges import changes_over
from plxtools.model.apiindex.build import index_folder


class EndpointError(ValueError):
    """A version or bundle setup a migration cannot use; the message says what to pass."""


@dataclass(frozen=True)
class End:
    """One end of a migration."""

    version: str  # the OpenPLX version of its official bundles
    bundle_set: BundleSet

    @property
    def agx(self):
        """The AGX installation whose bundles this end uses (None: an openplx-bundles release)."""
        return self.bundle_set.agx if self.bundle_set.agx_used else None

    @property
    def stored(self) -> bool:
        """Whether plx's stored index describes these bundles (a release, not AGX's copy)."""
        return self.agx is None and self.version in versions()

    @property
    def label(self) -> str:
        """`0.19.0`, or `0.20.1 (AGX 2.42.0.0)` for AGX's bundles: used in every message."""
        agx = self.agx
        return self.version if agx is None else f"{self.version} (AGX {agx.agx_version or '?'})"

    def describe(self) -> str:
        """The version and why it is used: `OpenPLX 0.20.1 (AGX 2.42.0.0 at ..., OpenPLX 0.20.1 (AGX_DIR))`."""
        return f"OpenPLX {self.version} ({self.bundle_set.official_why})"

    def index(self) -> ApiIndex:
        if self.stored:
            return load(self.version)
        return _live_index(str(self.bundle_set.official_root), self.version)


@lru_cache(maxsize=4)
def _live_index(root: str, version: str) -> ApiIndex:
    return ApiIndex(index_folder(Path(root), version, use_cache=True))


def _files_named(files: list[Path]) -> str:
    return str(files[0]) if len(files) == 1 else f"{files[0]} (and {len(files) - 1} more files)"


def _found_agx(files: list[Path]):
    """The AGX installation plx finds for these files, used or not: `agx-dir` of the first config
    that sets it (the anchors `resolve_bundle_set` reads), else the environment and usual folders.
    Nothing else of the bundle set is resolved, so no version is fetched just to ask this."""

    configured = None
    for anchor in sorted({(f if f.is_dir() else f.parent) for f in files}) or [Path(".")]:
        configured = config_for(anchor / "x.openplx").agx_dir
        if configured is not None:
            break
    return find_agx(configured)


def _check_loadable(version: str, files: list[Path], flag: str) -> None:
    """A version plx can load: a release in its index, or the version of the AGX installation found."""
    if not VERSION_RE.match(version):
        raise EndpointError(f"{flag} '{version}' is not an OpenPLX version (write it as 0.19.0)")
    if version in versions():
        return
    agx = _found_agx(files)
    if agx is not None and agx.openplx_version == version:
        return
    known = versions()
    there = (f"the AGX installation found, AGX {agx.agx_version or '(version unknown)'} at {agx.root} ({agx.why}), "
             f"has OpenPLX {agx.openplx_version or '(version unknown)'}" if agx is not None else
             "no AGX installation found: set AGX_DIR, or agx-dir in the config, to one whose bundles are "
             f"{version}")
    raise EndpointError(f"{flag} {version}: OpenPLX version '{version}' is neither an openplx-bundles release in "
                        f"plx's API index ({known[0]} to {known[-1]}) nor the version of AGX's bundles ({there})")


def _end(files: list[Path], version: str | None, flag: str) -> End:
    try:
        bs = resolve_bundle_set(files, [], version, version_why=flag)
    except BundleSetError as exc:
        raise EndpointError(str(exc)) from None
    if bs.official_version is None or not VERSION_RE.match(bs.official_version):
        raise EndpointError(f"{_files_named(files)}: cannot tell which OpenPLX version the bundles in use are "
                            f"({bs.official_root or 'no official bundles'}: {bs.official_why}); pass --from VERSION")
    return End(bs.official_version, bs)


def source(files: list[Path], from_flag: str | None, flag: str = "--from") -> End:
    """The end the files start from: --from, else the bundles `plx lint` uses for them."""
    if from_flag is not None:
        _check_loadable(from_flag, files, flag)
    return _end(files, from_flag, flag)


def target(files: list[Path], to_v: str, flag: str = "--to") -> End:
    """The end asked for with --to: a release, or the version of the AGX installation found."""
    _check_loadable(to_v, files, flag)
    return _end(files, to_v, flag)


def check_direction(files: list[Path], src: End, dst: End) -> None:
    """plx migrate moves forward only; going back is refused with what to pass instead."""
    if version_key(src.version) <= version_key(dst.version):
        return
    raise EndpointError(f"{_files_named(files)}: written for {src.describe()}, which is newer than --to "
                        f"{dst.label} (plx migrate only moves forward): pass --to {src.version} or newer, or "
                        f"--from VERSION when the files were written for an older OpenPLX")


def chain(src: End, dst: End) -> list[ApiIndex]:
    """The indexes from one end to the other: the releases in between, by version, each once."""
    lo, hi = version_key(src.version), version_key(dst.version)
    middle = [load(v) for v in versions() if lo < version_key(v) < hi]
    return [src.index(), *middle, dst.index()]


def plan_between(src: End, dst: End):
    """The rewrite plan from one end to the other: the stored index's changes for two releases,
    else the changes along `chain` (bundles in no release indexed now)."""

    if src.stored and dst.stored:
        return plan(src.version, dst.version)
    return plan_of(src.label, dst.label, changes_over(chain(src, dst)))


def plan_for_sets(from_set: BundleSet, to_set: BundleSet):
    """The plan between two loaded bundle sets (the editor's migrate action): the same as the CLI's."""
    ends = []
    for bs in (from_set, to_set):
        if bs.official_version is None or not VERSION_RE.match(bs.official_version):
            raise EndpointError(f"cannot tell which OpenPLX version the bundles at {bs.official_root} are")
        ends.append(End(bs.official_version, bs))
    return plan_between(ends[0], ends[1])
