"""Finding an AGX Dynamics installation and the OpenPLX bundles it ships, without configuration.

AGX ships its own OpenPLX bundles, often newer than any `openplx-bundles` release on PyPI (AGX 2.41
ships OpenPLX 0.20.1), and its users' models are written against them. So plx looks for an AGX
installation the way a shell set up for AGX would find it, in this order:

1. `agx-dir` in the configuration (a folder; `""` turns the search off);
2. the environment AGX's own setup scripts export (`setup_env.bash` / `setup_env.bat`): `AGX_DIR`,
   then `AGX_DATA_DIR` and `AGX_PLUGIN_PATH` (whose parent folders are inside the installation);
3. the `agx` Python package when it can be imported (found, not imported: it loads native libraries);
4. the usual install folders: `/opt/Algoryx/AGX-*` on Linux, `%ProgramFiles%\\Algoryx\\AGX-*` on Windows.

Inside an installation, the official bundles (Math, Physics, ...) are in `<AGX_DIR>/openplxbundles`
and AGX's own bundle in `<AGX_DIR>/data/openplx/agxBundle` (`$AGX_DATA_DIR/openplx/agxBundle`): the
layout Algoryx's AGX Dynamics for Unreal build script copies from an installed AGX on Linux and
Windows (docs/bundles.md cites it). Those documented places are looked at first; an installation
laid out otherwise is searched a few levels deep for the folder holding `Math/config.openplx` and
`Physics/config.openplx`. Only the file system is read here; nothing is run.
"""

from __future__ import annotations

import fnmatch
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

from plxtools.cache import reads

ENV_VARS = ("AGX_DIR", "AGX_DATA_DIR", "AGX_PLUGIN_PATH")
# where an installed AGX keeps them, relative to the installation (see the module docstring)
OFFICIAL_BUNDLES = ("openplxbundles",)
AGX_BUNDLE = ("data", "openplx", "agxBundle")
_VERSION_IN_NAME = re.compile(r"(?i)agx[-_ ]?(\d+\.\d+(?:\.\d+)*)")


@dataclass(frozen=True, slots=True)
class AgxInstall:
    """An AGX installation with OpenPLX bundles."""

    root: Path  # the installation folder
    bundles: Path  # the folder holding Math/, Physics/, ... (and AGX's own bundles)
    agx_version: str | None  # "2.42.0.0", from the folder name or the agx package; None when unknown
    openplx_version: str | None  # the bundles' own version (Math/config.openplx)
    why: str  # how it was found
    agx_bundle: Path | None = None  # AGX's own bundle (data/openplx/agxBundle), when there is one

    def describe(self) -> str:
        """`AGX 2.42.0.0 at /opt/Algoryx/AGX-2.42.0.0, OpenPLX 0.20.1 (AGX_DIR)`."""
        return (f"AGX {self.agx_version or '(version unknown)'} at {self.root}, "
                f"OpenPLX {self.openplx_version or '?'} ({self.why})")


def usual_folders() -> list[str]:
    """Glob patterns of the folders AGX's installers use, matched without regard to case: the Linux
    and macOS packages install into /opt/Algoryx/AGX-x.y.z.w (AgX-x.y.z.w in older releases), the
    Windows installer into Program Files\\Algoryx\\AGX-x.y.z.w (agx-/AgX- in older ones)."""
    if sys.platform.startswith("win"):
        bases = [os.environ.get("ProgramFiles") or r"C:\Program Files", os.environ.get("ProgramW6432") or ""]
        return list(dict.fromkeys(os.path.join(b, "Algoryx", "AGX-*") for b in bases if b))
    return ["/opt/Algoryx/AGX-*", "/usr/local/Algoryx/AGX-*",
            os.path.join(os.path.expanduser("~"), "Algoryx", "AGX-*")]


def _has_bundles(folder: Path) -> bool:
    return reads.is_file(folder / "Math" / "config.openplx") and reads.is_file(folder / "Physics" / "config.openplx")


def bundles_in(root: Path, max_depth: int = 4) -> Path | None:
    """The folder of OpenPLX bundles inside an AGX installation: the documented place first, else
    the shallowest folder that holds Math/ and Physics/ (None: neither)."""
    if not reads.is_dir(root):
        return None
    documented = root.joinpath(*OFFICIAL_BUNDLES)
    if _has_bundles(documented):
        return documented
    level = [root]
    for _depth in range(max_depth + 1):
        nxt: list[Path] = []
        for d in level:
            if _has_bundles(d):
                return d
            try:
                nxt += [d / name for name in reads.listdir(d) if not name.startswith(".")
                        and name not in ("__pycache__", "include", "lib", "bin", "Math", "Physics")
                        and reads.is_dir(d / name)]
            except OSError:
                continue
        level = nxt
    return None


def _openplx_version(bundles: Path) -> str | None:
    try:
        text = reads.read_bytes(bundles / "Math" / "config.openplx").decode("utf-8", errors="replace")
    except OSError:
        return None
    m = re.search(r'^\s*version:\s*"([^"]+)"', text, re.M)
    return m.group(1) if m else None


def _agx_version(root: Path) -> str | None:
    for part in reversed(root.parts):
        m = _VERSION_IN_NAME.search(part)
        if m:
            return m.group(1)
    for name in ("VERSION", "version.txt"):
        try:
            text = reads.read_bytes(root / name).decode("utf-8", errors="replace").strip()
        except OSError:
            continue
        m = re.search(r"\d+\.\d+(?:\.\d+)*", text)
        if m:
            return m.group(0)
    return None


def _release_key(path: str) -> tuple[int, ...]:
    m = _VERSION_IN_NAME.search(os.path.basename(path))
    return tuple(int(x) for x in m.group(1).split(".")) if m else ()


def agx_bundle_in(root: Path, data_dir: Path | None = None) -> Path | None:
    """AGX's own bundle in an installation (`data/openplx/agxBundle`, or under AGX_DATA_DIR)."""
    for cand in ([data_dir.joinpath(*AGX_BUNDLE[1:])] if data_dir is not None else []) + [root.joinpath(*AGX_BUNDLE)]:
        if reads.is_dir(cand):
            return cand.resolve()
    return None


def _install_at(root: Path, why: str, look_in: Path | None = None, data_dir: Path | None = None) -> AgxInstall | None:
    """The installation at `root` with bundles in their documented place, else found in `look_in`
    (default: the root), else in the root."""
    root = root.expanduser()
    documented = root.joinpath(*OFFICIAL_BUNDLES)
    b = documented if _has_bundles(documented) else (
        bundles_in(look_in or root) or (bundles_in(root) if look_in is not None else None))
    if b is None:
        return None
    return AgxInstall(root.resolve(), b.resolve(), _agx_version(root), _openplx_version(b), why,
                      agx_bundle_in(root, data_dir))


def _install_holding(folder: Path, why: str) -> AgxInstall | None:
    """The installation that holds a folder AGX's setup script exports (AGX_DATA_DIR is
    `<root>/data`; AGX_PLUGIN_PATH is inside the root too): the nearest parent whose documented
    bundle folder exists, else the parent searched, starting in the folder itself."""
    data_dir = folder if why == "AGX_DATA_DIR" else None
    for cand in folder.parents[:3]:
        if _has_bundles(cand.joinpath(*OFFICIAL_BUNDLES)):
            return _install_at(cand, why, data_dir=data_dir)
    return _install_at(folder.parent, why, folder, data_dir)


def _install_above(folder: Path, why: str, levels: int = 3) -> AgxInstall | None:
    """The installation holding `folder` (the agx package's folder): the nearest parent with bundles."""
    for cand in folder.parents[:levels]:
        found = _install_at(cand, why)
        if found is not None:
            return found
    return None


def _agx_package_folder() -> Path | None:
    from importlib.util import find_spec

    for entry in sys.path:  # noted for a cached answer: an agx package that appears later must be seen
        base = os.path.abspath(entry or os.curdir)
        reads.kind(os.path.join(base, "agx"))
        reads.kind(os.path.join(base, "agx.py"))

    try:
        spec = find_spec("agx")
    except (ImportError, ValueError):
        return None
    # a real module or package only: a folder that happens to be called agx (a namespace package,
    # say in the working folder) is not AGX's package
    if spec is None or not spec.origin or spec.origin in ("namespace", "built-in", "frozen") \
            or not os.path.isfile(spec.origin):
        return None
    return Path(spec.origin).resolve().parent


def _glob(pattern: str) -> list[str]:
    """`glob` of a pattern whose wildcards are in its last part, without regard to case (AGX-, AgX-
    and agx- folders are all AGX's), with the folder's names noted."""
    folder, leaf = os.path.split(pattern)
    try:
        names = reads.listdir(folder)
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names if fnmatch.fnmatchcase(n.lower(), leaf.lower())]


def find_agx(configured: str | None = None, env: dict | None = None,
             usual: list[str] | None = None) -> AgxInstall | None:
    """The AGX installation plx uses, in the order of the module docstring (None: none found).

    `configured`: `agx-dir` from the configuration (`""` turns the search off)."""
    if env is None:
        env = {var: reads.env(var) for var in ENV_VARS}
    if configured is not None:
        return _install_at(Path(configured), "agx-dir in the configuration") if configured else None
    for var in ENV_VARS:
        value = env.get(var)
        if not value:
            continue
        folder = Path(value)
        # AGX_DIR is the installation; AGX_DATA_DIR (<root>/data) and AGX_PLUGIN_PATH (<root>/plugins) are in it
        found = _install_at(folder, var) if var == "AGX_DIR" else _install_holding(folder, var)
        if found is not None:
            return found
    pkg = _agx_package_folder()
    if pkg is not None:
        found = _install_above(pkg, "the agx Python package", levels=4)
        if found is not None:
            return found
    for pattern in usual_folders() if usual is None else usual:
        for cand in sorted(_glob(pattern), key=_release_key, reverse=True):  # the newest release first
            found = _install_at(Path(cand), "a usual install folder")
            if found is not None:
                return found
    return None


def defines(bundles: Path, qname: str) -> bool:
    """Whether a folder of bundles defines a model or trait of that qualified name (its namespace
    folder holds a file with a top-level `Name is ...` / `trait Name`)."""
    parts = qname.split(".")
    if len(parts) < 2:
        return False
    folder = bundles.joinpath(*parts[:-1])
    pattern = re.compile(rf"^(?:const\s+)?(?:trait\s+)?{re.escape(parts[-1])}\b", re.M)
    try:
        files = [folder / n for n in reads.listdir(folder) if n.endswith(".openplx") and n != "config.openplx"]
    except OSError:
        return False
    for f in files:
        try:
            if pattern.search(reads.read_bytes(f).decode("utf-8", errors="replace")):
                return True
        except OSError:
            continue
    return False


def newer_bundles(written: str, bundle_set, newest_release: str, typo: bool = False) -> tuple | None:
    """For an unknown official-looking name that no `openplx-bundles` release has: where newer
    bundles are (an AGX installation found but not in use, whose bundles define it: ("agx", the
    name, the version in use, AGX's version, its OpenPLX version, its bundles folder)), or that
    they may be needed (("release", the name, the newest release); not when `typo`: a near miss of
    an existing name has its suggestion). The rules layer words it (rules/names/unresolved_type.py)."""
    agx = getattr(bundle_set, "agx", None)
    using = getattr(bundle_set, "official_version", None) or "?"
    if agx is not None and not getattr(bundle_set, "agx_used", False):
        if defines(agx.bundles, written):
            return ("agx", written, using, agx.agx_version or "", agx.openplx_version or "?", str(agx.bundles))
        return None
    if agx is None and not typo:
        return ("release", written, newest_release)
    return None
