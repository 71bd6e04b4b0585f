"""Which bundles a project loads (the bundle set), and official `openplx-bundles` versions in plx's cache.

Order, the same for the CLI, the language server and check:

1. bundle folders: `--bundle-path`, `bundle-path` in the config, `OPENPLX_BUNDLE_PATH`, then bundles
   found in the linted tree / workspace root. A bundle found there replaces the official bundle of the
   same name, so a copy of the official bundles (an AGX installation) is read instead of the package.
2. `--openplx-version` / `openplx-version` in the config: that version, from an AGX installation whose
   bundles are that version, else that `openplx-bundles` release, fetched with pip into the cache on
   first use.
3. a version written in a user bundle's dependency (`"Physics3D==0.17.26"`), however the bundle was
   found; a bundle's own `version:` is its own and selects nothing (an AGX installation whose
   bundles are that version is used for it).
4. the bundles of an AGX installation found without configuration (model/agx.py).
5. the installed `openplx-bundles` package.

A `BundleSet` is a plain value (hashable `key()`), so several sets, hence several versions, can be
loaded side by side in one process, each into its own `Workspace`.
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from plxtools.cache import reads

VERSION_RE = re.compile(r"^\d+\.\d+\.\d+$")
DEP_PIN_RE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?:==|@)(\d+(?:\.\d+)*)$")
PACKAGE = "openplx-bundles"

# Releases of openplx-bundles on PyPI when this was written (a fact list, used to tell a bundle's own
# `version:` apart from an OpenPLX version pin, and by `plx bundles list`; the registry stays the judge).
KNOWN_VERSIONS: tuple[str, ...] = tuple(
    [f"0.15.{i}" for i in range(23)] + [f"0.16.{i}" for i in range(11)] + [f"0.17.{i}" for i in range(34)]
    + [f"0.18.{i}" for i in range(12)] + ["0.19.0"]
)
# every minor's latest patch, plus the one users pin: what the slow test and the docs cover
SUPPORTED_LATEST = ("0.15.22", "0.16.10", "0.17.26", "0.17.33", "0.18.11", "0.19.0")


class BundleSetError(ValueError):
    """A bundle setup plx cannot use; the message names the path, key or version involved."""


def cache_dir() -> Path:
    base = os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "plxtools"


def version_key(v: str) -> tuple[int, ...]:
    return tuple(int(x) for x in v.split(".") if x.isdigit())


# ---------------------------------------------------------------------------- official versions


def installed() -> tuple[Path, str | None] | None:
    """The installed openplx-bundles package: (folder holding Math/, Physics/..., version)."""
    module = sys.modules.get("openplxbundles")
    if module is not None:
        root = Path(module.package_dir())
    else:
        # found, not imported: the package's __init__ imports logging (~10 ms) only to say where it is
        from importlib.util import find_spec

        try:
            spec = find_spec("openplxbundles")
        except (ImportError, ValueError):
            return None
        if spec is None or not spec.origin:
            return None
        root = Path(os.path.dirname(os.path.abspath(spec.origin)))
    from plxtools.cache import reads

    for entry in sys.path:  # a package of that name earlier on the path would be found first
        entry = os.path.abspath(entry or os.curdir)
        if entry == str(root.parent):
            break
        reads.kind(os.path.join(entry, "openplxbundles"))
        reads.kind(os.path.join(entry, "openplxbundles.py"))
    reads.realpath(root)
    if not reads.is_file(root / "Math" / "config.openplx"):
        return None
    v = _dist_info_version(root.parent)
    if v is None:
        try:
            from importlib.metadata import version

            v = version(PACKAGE)
        except Exception:  # metadata missing: the bundles still work, the version is just unknown
            v = _version_in(root)
    return root, v


def _dist_info_version(site: Path) -> str | None:
    """The Version of the one openplx_bundles-*.dist-info beside the package: what
    importlib.metadata would answer, without its ~30 ms import (email parsing) at every start."""
    from plxtools.cache import reads

    try:
        found = [site / n for n in reads.listdir(site) if n.startswith("openplx_bundles-") and n.endswith(".dist-info")]
        if len(found) != 1:
            return None
        if True:
            for line in reads.read_bytes(found[0] / "METADATA").decode("utf-8", "replace").splitlines():
                if line.startswith("Version:"):
                    return line.split(":", 1)[1].strip() or None
                if not line.strip():
                    return None
    except OSError:
        return None
    return None


def _version_in(root: Path) -> str | None:
    from plxtools.cache import reads

    try:
        text = reads.read_bytes(root / "Math" / "config.openplx").decode("utf-8", "replace")
    except OSError:
        return None
    m = re.search(r'version:\s*"([^"]+)"', text)
    return m.group(1) if m else None


def _versions_dir() -> Path:
    return cache_dir() / "bundles"


def cached_root(version: str) -> Path | None:
    root = _versions_dir() / version / "openplxbundles"
    if (_versions_dir() / version / ".complete").is_file() and (root / "Math" / "config.openplx").is_file():
        return root
    return None


def cached_versions() -> list[str]:
    d = _versions_dir()
    if not d.is_dir():
        return []
    return sorted((p.name for p in d.iterdir() if cached_root(p.name) is not None), key=version_key)


def version_root(version: str, fetch: bool = True) -> Path:
    """The bundle folder of an official version: installed package, cache, or fetched now."""
    if not VERSION_RE.match(version):
        raise BundleSetError(f"'{version}' is not an OpenPLX version (write it as 0.17.26)")
    inst = installed()
    if inst is not None and inst[1] == version:
        return inst[0]
    root = cached_root(version)
    if root is not None:
        return root
    if not fetch:
        raise BundleSetError(f"openplx-bundles {version} is not in the cache; run 'plx bundles install {version}'")
    return install(version)


def _wheel_dir() -> Path:
    return cache_dir() / "wheels"


def _cached_wheel(version: str) -> Path | None:
    d = _wheel_dir()
    if not d.is_dir():
        return None
    found = sorted(d.glob(f"openplx_bundles-{version}-*.whl"))
    return found[0] if found else None


def install(version: str, force: bool = False) -> Path:
    """Fetch `openplx-bundles==version` with pip (no dependencies) and unpack its bundles into the cache."""
    if not VERSION_RE.match(version):
        raise BundleSetError(f"'{version}' is not an OpenPLX version (write it as 0.17.26)")
    if not force:
        root = cached_root(version)
        if root is not None:
            return root
    wheel = None if force else _cached_wheel(version)
    corrupt_note = ""
    if wheel is not None:
        try:
            return _unpack(wheel, version)
        except BundleSetError as exc:
            corrupt_note = f"{exc}; it was removed. "
            wheel.unlink(missing_ok=True)
            wheel = None
    try:
        wheel = _download(version)
    except BundleSetError as exc:
        raise BundleSetError(corrupt_note + str(exc)) from None
    return _unpack(wheel, version)


def _download(version: str) -> Path:
    """The wheel, by `python -m pip download` where this interpreter has pip (it knows every way pip
    is configured), else from the configured index over HTTP (pipx, uv tool and uv venvs have no pip)."""
    from importlib.util import find_spec

    try:
        has_pip = find_spec("pip") is not None
    except (ImportError, ValueError):
        has_pip = False
    if has_pip and not os.environ.get("PLX_FETCH_WITHOUT_PIP"):
        return _pip_download(version)
    return _index_download(version)


def _index_download(version: str) -> Path:
    from plxtools.model import index_fetch

    try:
        return index_fetch.download(PACKAGE, version, _wheel_dir(),
                                    timeout=float(os.environ.get("PLX_PIP_TIMEOUT", "15")),
                                    progress=_progress_for(f"{PACKAGE} {version}"))
    except index_fetch.FetchError as exc:
        if exc.network:
            raise BundleSetError(f"cannot fetch {PACKAGE} {version}: {exc}; install it once with network "
                                 f"('plx bundles install {version}') or use --bundle-path") from None
        raise BundleSetError(str(exc)) from None
    except OSError as exc:
        raise BundleSetError(f"cannot fetch {PACKAGE} {version}: {exc}") from None


def _progress_for(label: str):
    """A download progress bar on stderr (a terminal only), or None."""
    from plxtools import progress

    return progress.bytes_callback(label)


def _pip_download(version: str) -> Path:
    import shutil
    import subprocess

    target = _wheel_dir()
    tmp = target / f".download-{os.getpid()}"
    try:
        tmp.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BundleSetError(f"cannot create the cache folder {target}: {exc.strerror}") from None
    cmd = [sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:", "--disable-pip-version-check",
           "--no-input", "--timeout", os.environ.get("PLX_PIP_TIMEOUT", "15"), "--retries", "1",
           "-d", str(tmp), f"{PACKAGE}=={version}"]
    from plxtools.progress import Bar

    try:
        try:
            with Bar(None, f"fetching {PACKAGE} {version} with pip", unit="bytes"):
                proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        except (OSError, subprocess.TimeoutExpired) as exc:
            raise BundleSetError(f"cannot run pip to fetch {PACKAGE} {version}: {exc}") from None
        wheels = sorted(tmp.glob("openplx_bundles-*.whl"))
        if proc.returncode != 0 or not wheels:
            raise BundleSetError(_pip_failure(version, proc.stdout + proc.stderr))
        dest = target / wheels[0].name
        os.replace(wheels[0], dest)
        return dest
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _pip_failure(version: str, out: str) -> str:
    lines = [ln.strip() for ln in out.splitlines() if ln.strip() and not ln.startswith("WARNING: Location")]
    network = any(w in out for w in ("NewConnectionError", "Connection refused", "Max retries exceeded",
                                      "Temporary failure in name resolution", "Network is unreachable",
                                      "Could not fetch URL", "ConnectTimeout", "timed out"))
    m = re.search(r"\(from versions: ([^)]*)\)", out)
    available = [v.strip() for v in m.group(1).split(",") if v.strip() and v.strip() != "none"] if m else []
    if available and version not in available:
        near = [v for v in available if v.rsplit(".", 1)[0] == version.rsplit(".", 1)[0]]
        hint = f"; {version.rsplit('.', 1)[0]}.x releases: {', '.join(near)}" if near else \
            f"; releases go from {available[0]} to {available[-1]}"
        return f"{PACKAGE} {version} is not on the package index{hint}"
    if network:
        return (f"cannot fetch {PACKAGE} {version}: the package index cannot be reached (no network?); "
                f"install it once with network ('plx bundles install {version}') or use --bundle-path")
    if "No matching distribution" in out:
        return f"{PACKAGE} {version} is not on the package index (pip found no matching distribution)"
    last = lines[-1] if lines else "no output"
    return f"cannot fetch {PACKAGE} {version}: pip failed: {last}"


def _unpack(wheel: Path, version: str) -> Path:
    """Unzip the wheel's bundle files into cache/bundles/VERSION (atomically: all or nothing)."""
    import shutil
    import zipfile

    final = _versions_dir() / version
    tmp = _versions_dir() / f".{version}.{os.getpid()}.tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        with zipfile.ZipFile(wheel) as zf:
            names = [n for n in zf.namelist() if n.startswith("openplxbundles/") and not n.endswith("/")]
            for n in names:
                parts = Path(n).parts
                if ".." in parts or Path(n).is_absolute():
                    raise BundleSetError(f"the wheel {wheel} has an unsafe member {n}")
                out = tmp / n
                out.parent.mkdir(parents=True, exist_ok=True)
                out.write_bytes(zf.read(n))
        if not (tmp / "openplxbundles" / "Math" / "config.openplx").is_file():
            raise BundleSetError(f"the wheel {wheel} holds no OpenPLX bundles (no openplxbundles/Math/config.openplx)")
        (tmp / ".complete").write_text(f"{version}\n{wheel.name}\n", encoding="utf-8")
        shutil.rmtree(final, ignore_errors=True)
        os.replace(tmp, final)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, EOFError, ValueError, KeyError) as exc:
        if isinstance(exc, BundleSetError):
            raise
        raise BundleSetError(f"the cached wheel {wheel} is corrupt ({exc})") from None
    except OSError as exc:
        raise BundleSetError(f"cannot unpack {wheel} into {final}: {exc.strerror or exc}") from None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return final / "openplxbundles"


# ---------------------------------------------------------------------------- the bundle set


@dataclass(slots=True)
class BundleSource:
    """A folder of bundles (or one bundle) and why it is in the set."""

    path: Path
    why: str


@dataclass(slots=True)
class BundleSet:
    """What a project loads: an official base folder plus bundle folders that add or replace bundles."""

    official_root: Path | None
    official_version: str | None
    official_why: str
    sources: list[BundleSource] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)  # said once by --show-settings / the server
    agx: object | None = None  # the AGX installation found (model/agx.AgxInstall), used or not
    agx_used: bool = False  # its bundles are the official base
    pinned: bool = True  # a flag, the config, a dependency or a folder of official bundles chose the version

    def key(self) -> tuple:
        # `pinned` decides lint's migrate hints (model/written_for.py), so it is part of what a result depends on
        return (str(self.official_root), tuple(str(s.path) for s in self.sources), self.pinned)

    def announcement(self) -> str | None:
        """A line to print when the version was chosen for the user rather than by them."""
        if self.official_why.startswith("pinned"):
            return f"using openplx-bundles {self.official_version} ({self.official_why})"
        return None


def bundle_roots_in(folder: Path) -> list[Path]:
    """A bundle folder itself, or the bundle folders directly inside a folder of bundles."""
    from plxtools.cache import reads

    if reads.is_file(folder / "config.openplx"):
        return [folder]
    try:
        return [folder / n for n in reads.listdir(folder) if reads.is_file(folder / n / "config.openplx")]
    except OSError:
        return []


def _config_name(root: Path) -> str:
    from plxtools.cache import reads

    try:
        text = reads.read_bytes(root / "config.openplx").decode("utf-8", "replace")
    except OSError:
        return root.name
    m = re.search(r'^\s*name:\s*"([^"]+)"', text, re.M)
    return m.group(1) if m else root.name


def check_unique_names(folder: Path) -> None:
    """Two bundles of one name in one folder of bundles: plx cannot tell which one is meant."""
    seen: dict[str, Path] = {}
    for r in bundle_roots_in(folder):
        n = _config_name(r)
        if n in seen:
            raise BundleSetError(f"{folder}: two bundles are named '{n}' ({seen[n].name}/config.openplx and "
                                 f"{r.name}/config.openplx); rename one or keep them in separate folders")
        seen[n] = r


def discover_bundles(paths: list[Path], stop_at: set[Path] | None = None, max_depth: int = 6) -> list[Path]:
    """Bundle roots (folders with a config.openplx) inside the given folders or holding the given files."""
    from plxtools.config import DEFAULT_EXCLUDE

    stop = {p.resolve() for p in stop_at or set()}
    found: list[Path] = []
    seen: set[Path] = set()

    def add(root: Path) -> None:
        r = root.resolve()
        if r not in seen and not any(s == r or s in r.parents for s in stop):
            seen.add(r)
            found.append(r)

    from plxtools.cache import reads

    for p in paths:
        if reads.kind(p) != "dir":
            folder = Path(reads.realpath(p)).parent
            for d in (folder, *folder.parents):
                if d in stop:
                    break
                if reads.is_file(d / "config.openplx"):
                    add(d)
                    break
            continue
        base = p.resolve()
        for d in (base, *base.parents):  # a folder inside a bundle belongs to it
            if d in stop:
                break
            if (d / "config.openplx").is_file():
                add(d)
                break
        for dirpath, dirnames, filenames in os.walk(base):
            depth = len(Path(dirpath).relative_to(base).parts)
            dirnames[:] = sorted(d for d in dirnames if d not in DEFAULT_EXCLUDE and not d.startswith(".")
                                 and depth < max_depth)
            if "config.openplx" in filenames:
                add(Path(dirpath))
    return found


def dependency_pins(roots: list[Path], official_names: set[str]) -> list[tuple[str, str]]:
    """OpenPLX versions selected by user bundles' dependencies: (version, 'file:line:col: dependency "..."').

    Only a dependency on an official bundle written with a version (`"Physics3D==0.17.26"`, the form
    every official bundle's own config uses, or `"Physics3D@0.17.26"`) selects a release. A bundle's
    own `version:` is the bundle's version, never a choice of OpenPLX release (issue 29: a test bundle
    whose own version looked like a release number pinned a whole folder to old bundles). A bundle
    that is itself an official bundle (a copy, an AGX installation) pins nothing: it replaces that bundle.
    """
    out: list[tuple[str, str]] = []
    for r in roots:
        cfg = r / "config.openplx"
        if _config_name(r) in official_names:
            continue
        try:
            text = reads.read_bytes(cfg).decode("utf-8", "replace")
        except OSError:
            continue
        m = re.search(r"^[ \t]*dependencies[ \t]*:[ \t]*\[([^\]]*)\]", text, re.M)
        if m is None:
            continue
        for sm in re.finditer(r'"([^"\n]*)"', m.group(1)):
            dm = DEP_PIN_RE.match(sm.group(1).strip())
            if dm and dm.group(1) in official_names:
                at = m.start(1) + sm.start(0)
                line = text.count("\n", 0, at) + 1
                col = at - (text.rfind("\n", 0, at) + 1) + 1
                out.append((dm.group(2), f"{cfg}:{line}:{col}: dependency \"{sm.group(1)}\""))
    return out


class _Folders:
    """The bundle folders of a set in the order they were given, each checked once (step 1 above)."""

    def __init__(self) -> None:
        self.sources: list[BundleSource] = []
        self.seen: set[Path] = set()

    def add(self, p: Path, why: str, must_exist: bool = True) -> None:
        found = reads.kind(p)
        if found is None:
            if must_exist:
                raise BundleSetError(f"bundle path {p} does not exist ({why})")
            return
        if found != "dir":
            raise BundleSetError(f"bundle path {p} is not a folder ({why})")
        rp = Path(reads.realpath(p))
        if rp in self.seen:
            return
        if not bundle_roots_in(rp):
            raise BundleSetError(f"bundle path {p} holds no bundle: no config.openplx in it or in its "
                                 f"subfolders ({why})")
        check_unique_names(rp)
        self.seen.add(rp)
        self.sources.append(BundleSource(rp, why))

    def add_configured(self, anchors: list[Path]) -> tuple[tuple[str, str] | None, str | None]:
        """`bundle-path` of each anchor's config; also the first `openplx-version` (with where it is
        written) and the first `agx-dir` found on the way."""
        from plxtools.config import config_for

        cfg_version: tuple[str, str] | None = None
        cfg_agx: str | None = None
        for a in anchors:
            cfg = config_for(a / "x.openplx")
            if cfg.agx_dir is not None and cfg_agx is None:
                cfg_agx = cfg.agx_dir
            for p in cfg.bundle_paths:
                self.add(p, f"bundle-path in {cfg.source}")
            if cfg.openplx_version and cfg_version is None:
                cfg_version = (cfg.openplx_version, f"openplx-version in {cfg.source}")
        return cfg_version, cfg_agx

    def add_environment(self) -> None:
        for part in (os.environ.get("OPENPLX_BUNDLE_PATH") or "").split(os.pathsep):
            if part:
                self.add(Path(part), "OPENPLX_BUNDLE_PATH")

    def add_agx_bundle(self, agx) -> None:
        """AGX's own bundle (`data/openplx/agxBundle`) beside its official bundles, when those are
        in use: models written for AGX name it (`AGX.*`) as they name Physics3D."""
        p = getattr(agx, "agx_bundle", None)
        if p is None or Path(p) in self.seen or not bundle_roots_in(Path(p)):
            return
        self.seen.add(Path(p))
        self.sources.append(BundleSource(Path(p), f"AGX's own bundle; {agx.describe()}"))

    def add_found(self, found: list[Path], official_root: Path | None, workspace_root: Path | None) -> None:
        """Bundles found in the linted tree or the workspace, after the configured folders."""
        for r in found:
            if r.parent.resolve() in self.seen or r in self.seen:
                continue
            if official_root is not None and official_root.resolve() in r.parents:
                continue  # linting the very bundles in use: they are already the official set
            self.sources.append(BundleSource(r, "found in the linted tree" if workspace_root is None or
                                             workspace_root.resolve() not in (r, *r.parents)
                                             else "found in the workspace"))
            self.seen.add(r)


@dataclass(slots=True)
class _Choice:
    """Where the official bundles come from (steps 2-5 above), as it is being decided."""

    version: str | None = None
    why: str = ""
    agx_official: tuple[Path, str | None, str] | None = None
    installed_why: str = f"the installed {PACKAGE} package: no dependency selects a version"
    notes: list[str] = field(default_factory=list)


def _official_names(inst: tuple[Path, str] | None) -> set[str]:
    names = {d.name for d in bundle_roots_in(inst[0])} if inst else set()
    return names | {"Math", "Physics", "Physics1D", "Physics3D", "DriveTrain", "Robotics", "Sensors",
                    "Simulation", "Terrain", "Urdf", "Vehicles", "Visuals"}


def _follow_pin(c: _Choice, pins: list[tuple[str, str]], agx, inst) -> None:
    """The first dependency pin chooses the version; an AGX installation or the installed package of
    that very version serves it."""
    c.version, where = pins[0]
    c.why = f"pinned by {where}"
    others = sorted({v for v, _w in pins if v != c.version})
    if others:
        c.notes.append(f"other pins ignored: {', '.join(others)} (the first pin, {where}, wins)")
    if _agx_serves(c, agx):
        return
    if inst is not None and inst[1] == c.version:  # what is installed anyway: nothing to announce
        c.version = None
        c.installed_why = f"the installed {PACKAGE} package, the version {where.split(': ', 1)[0]} asks for"


def _agx_serves(c: _Choice, agx) -> bool:
    """An AGX installation whose bundles are the version chosen serves it (nothing is fetched)."""
    if agx is None or c.version is None or agx.openplx_version != c.version:
        return False
    c.agx_official = (agx.bundles, c.version, f"{c.why}; {agx.describe()}")
    c.version = None
    return True


def _choose(cli: tuple[str | None, str], cfg_version: tuple[str, str] | None, pins: list[tuple[str, str]],
            replacing: list[BundleSource], agx, inst) -> _Choice:
    c = _Choice()
    if cli[0]:
        c.version, c.why = cli
        _agx_serves(c, agx)
    elif cfg_version:
        c.version, c.why = cfg_version
        _agx_serves(c, agx)
    elif pins and replacing:
        c.notes.append(f"the dependency version {pins[0][1]} is not used: the official bundles come from "
                       f"{replacing[0].path} ({replacing[0].why})")
    elif pins:
        _follow_pin(c, pins, agx, inst)
    elif agx is not None and not replacing:
        c.agx_official = (agx.bundles, agx.openplx_version, agx.describe())
    if agx is not None and c.agx_official is None:
        c.notes.append(f"{agx.describe()}: not used ({c.why or 'bundle folders are configured'}); "
                       f"'agx-dir' in the config chooses another installation, \"\" turns the search off")
    return c


def _official(c: _Choice, inst) -> tuple[Path | None, str | None, str]:
    """The official base folder, its version and why, for the choice made."""
    if c.agx_official is not None:
        return c.agx_official
    if c.version is not None:
        try:
            root = version_root(c.version)
        except BundleSetError as exc:
            raise BundleSetError(f"{exc} (the version comes from {c.why})") from None
        return (root, c.version, c.why)
    if inst is not None:
        return (inst[0], inst[1], c.installed_why)
    return (None, None, f"{PACKAGE} is not installed")


def _has_math(sources: list[BundleSource]) -> bool:
    return any((s.path / "Math" / "config.openplx").is_file() or
               (s.path / "config.openplx").is_file() and _config_name(s.path) == "Math" for s in sources)


def _pinned(*choices) -> bool:
    """Whether the user chose the version: a flag, the config, a dependency, official bundles of their own."""
    return any(bool(c) for c in choices)


def resolve_bundle_set(
    targets: list[Path],
    cli_paths: list[str | Path] = (),
    cli_version: str | None = None,
    workspace_root: Path | None = None,
    use_env: bool = True,
    discover: bool = True,
    use_config: bool = True,
    version_why: str = "--openplx-version",
) -> BundleSet:
    """The bundle set for files/folders `targets` (and an editor's workspace root), in the documented
    order: the bundle folders given, then the official base they choose, then the bundles found.
    `version_why`: what asked for `cli_version` (`plx migrate` passes `--to` / `--from`)."""
    folders = _Folders()
    for p in cli_paths:
        folders.add(Path(p), "--bundle-path")
    anchors = [workspace_root] if workspace_root is not None else []
    anchors += sorted({(t if t.is_dir() else t.parent) for t in targets}) or [Path(".")]
    cfg_version, cfg_agx = folders.add_configured(anchors) if use_config else (None, None)
    if use_env:
        folders.add_environment()
    inst = installed()
    official_names = _official_names(inst)
    found: list[Path] = []
    if discover:
        stop = {s.path for s in folders.sources}
        if inst is not None:
            stop.add(inst[0].resolve())
        found = discover_bundles(([workspace_root] if workspace_root else []) + list(targets), stop)

    # every user bundle counts the same, however it was found (flag, config, environment, the tree)
    sources = folders.sources
    user_roots = [r for s in sources for r in bundle_roots_in(s.path)] + list(found)
    replacing = [s for s in sources if any(_config_name(r) in official_names for r in bundle_roots_in(s.path))]
    pins = dependency_pins(user_roots, official_names)
    agx = None
    if discover and use_env:
        from plxtools.model.agx import find_agx

        agx = find_agx(cfg_agx)
    choice = _choose((cli_version, version_why), cfg_version, pins, replacing, agx, inst)
    official = _official(choice, inst)
    if choice.agx_official is not None:
        folders.add_agx_bundle(agx)
    folders.add_found(found, official[0], workspace_root)
    bs = BundleSet(official[0].resolve() if official[0] else None, official[1], official[2], sources,
                   choice.notes, agx, choice.agx_official is not None,
                   pinned=_pinned(cli_version, cfg_version, pins, replacing))
    if bs.official_root is None and not _has_math(sources):
        raise BundleSetError("cannot find the OpenPLX bundles: install openplx-bundles, set openplx-version, "
                             "OPENPLX_BUNDLE_PATH, or pass --bundle-path")
    return bs


def explicit_bundle_set(paths: list[Path], use_env: bool = True) -> BundleSet:
    """The set for an explicit list of bundle folders (the library API): no config, no discovery."""
    return resolve_bundle_set([], list(paths), None, None, use_env=use_env, discover=False, use_config=False)
