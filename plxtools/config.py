"""Project configuration: `[tool.plx]` in pyproject.toml or a `plx.toml`; the closest file wins.

Keys (kebab-case): select, ignore, extend-select, per-file-ignores, exclude, extend-exclude,
bundle-path, openplx-version, agx-dir, fmt.exclude, check.integrator, check.timestep. A `plx.toml`
holds the keys at its top level.
"""

from __future__ import annotations

import fnmatch
import os
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

DEFAULT_EXCLUDE = (".git", ".hg", ".venv", "venv", "node_modules", "__pycache__", ".tox", "build", "dist")
KNOWN_KEYS = {"select", "ignore", "extend-select", "per-file-ignores", "exclude", "extend-exclude",
              "bundle-path", "openplx-version", "agx-dir", "fmt", "check", "max-file-size"}
# the largest .openplx file lint, fmt and check read (MB); docs/reliability.md gives memory per byte
DEFAULT_MAX_FILE_MB = 16
MAX_FILE_MB_CEILING = 1024
INTEGRATORS = ("auto", "implicitfast", "implicit", "rk4", "euler")  # `plx check --integrator`, check.integrator


class ConfigError(Exception):
    """A config file that cannot be used; the message names the file and the key."""


@dataclass(slots=True)
class Config:
    root: Path | None = None  # folder of the config file
    source: Path | None = None
    select: list[str] | None = None  # None: all rules
    ignore: list[str] = field(default_factory=list)
    extend_select: list[str] = field(default_factory=list)
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    exclude: list[str] = field(default_factory=list)
    bundle_paths: list[Path] = field(default_factory=list)
    openplx_version: str | None = None  # official openplx-bundles release to lint against
    agx_dir: str | None = None  # an AGX installation (model/agx.py); "" turns the search off; None: search
    fmt_exclude: list[str] = field(default_factory=list)
    check_integrator: str | None = None  # [check] integrator: one of INTEGRATORS; None = auto
    check_timestep: float | None = None  # [check] timestep in seconds; None = the backend's default
    max_file_mb: float = DEFAULT_MAX_FILE_MB  # max-file-size: larger source files are refused unread

    @property
    def max_file_bytes(self) -> int:
        return int(self.max_file_mb * 2**20)

    def rule_enabled(self, code: str, path: str | None = None) -> bool:
        if code.startswith("S"):
            return True  # syntax errors cannot be turned off
        selected = self.select is None or _matches(code, self.select) or _matches(code, self.extend_select)
        if not selected:
            return False
        if _matches(code, self.ignore):
            # a more specific select wins over a broader ignore, as in ruff
            best_ignore = max((len(p) for p in self.ignore if code.startswith(p)), default=-1)
            best_select = max((len(p) for p in (self.select or []) + self.extend_select
                               if code.startswith(p)), default=-1)
            if best_ignore >= best_select:
                return False
        if path is not None and self.per_file_ignores:
            rel = self.relative(path)
            for pattern, codes in self.per_file_ignores.items():
                if _glob(rel, pattern) and _matches(code, codes):
                    return False
        return True

    def relative(self, path: str) -> str:
        p = Path(path).resolve()
        if self.root is not None:
            try:
                return p.relative_to(self.root.resolve()).as_posix()
            except ValueError:
                pass
        return p.as_posix()

    def is_excluded(self, path: Path, patterns: list[str] | None = None) -> bool:
        pats = self.exclude if patterns is None else patterns
        if not pats:
            return False
        rel = self.relative(str(path))
        return any(_glob(rel, p) for p in pats)


def _matches(code: str, prefixes: list[str]) -> bool:
    return any(p == "ALL" or code.startswith(p) for p in prefixes)


def _glob(rel: str, pattern: str) -> bool:
    pattern = pattern.rstrip("/")
    if fnmatch.fnmatch(rel, pattern) or fnmatch.fnmatch(rel, pattern + "/*"):
        return True
    # a bare name matches any path component
    if "/" not in pattern:
        return any(fnmatch.fnmatch(part, pattern) for part in rel.split("/"))
    return False


def find_config_file(start: Path) -> tuple[Path, dict] | None:
    """Closest plx.toml or pyproject.toml with a [tool.plx] table, walking up from `start`.

    Every file looked for is noted (`plxtools.cache.reads`), found or not: a config file that
    appears later in a parent folder changes the answer of a cached run."""
    from plxtools.cache import reads

    folder = start if reads.is_dir(start) else start.parent
    folder = Path(reads.realpath(folder))
    for d in (folder, *folder.parents):
        plx = d / "plx.toml"
        if reads.is_file(plx):
            return plx, _read_toml(plx)
        pyproject = d / "pyproject.toml"
        if reads.is_file(pyproject):
            data = _read_toml(pyproject)
            tool = data.get("tool", {}).get("plx")
            if tool is not None:
                return pyproject, tool
    return None


def _read_toml(path: Path) -> dict:
    import tomllib  # only when there is a config file to read

    from plxtools.cache import reads

    try:
        return tomllib.loads(reads.read_bytes(path).decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: not UTF-8 ({exc.reason})") from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read: {exc.strerror}") from None


def _str_list(path: Path, key: str, value) -> list[str]:
    if isinstance(value, str):
        return [value]
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ConfigError(f"{path}: '{key}' must be a list of strings")
    return list(value)


def parse_config(path: Path, table: dict) -> Config:
    unknown = set(table) - KNOWN_KEYS
    if unknown:
        raise ConfigError(f"{path}: unknown key(s) {', '.join(sorted(unknown))}; "
                          f"known keys: {', '.join(sorted(KNOWN_KEYS))}")
    cfg = Config(root=path.parent.resolve(), source=path)
    if "select" in table:
        cfg.select = _str_list(path, "select", table["select"])
    cfg.ignore = _str_list(path, "ignore", table.get("ignore", []))
    cfg.extend_select = _str_list(path, "extend-select", table.get("extend-select", []))
    pfi = table.get("per-file-ignores", {})
    if not isinstance(pfi, dict):
        raise ConfigError(f"{path}: 'per-file-ignores' must be a table of glob = [codes]")
    cfg.per_file_ignores = {k: _str_list(path, f"per-file-ignores.{k}", v) for k, v in pfi.items()}
    cfg.exclude = _str_list(path, "exclude", table.get("exclude", [])) + _str_list(
        path, "extend-exclude", table.get("extend-exclude", []))
    bp = table.get("bundle-path", [])
    cfg.bundle_paths = [(path.parent / p).resolve() for p in _str_list(path, "bundle-path", bp)]
    ov = table.get("openplx-version")
    if ov is not None:
        import re

        if not isinstance(ov, str) or not re.match(r"^\d+\.\d+\.\d+$", ov):
            raise ConfigError(f"{path}: 'openplx-version' must be a version string such as \"0.17.26\"")
        cfg.openplx_version = ov
    agx_dir = table.get("agx-dir")
    if agx_dir is not None:
        if not isinstance(agx_dir, str):
            raise ConfigError(f"{path}: 'agx-dir' must be a folder (a string; \"\" turns the AGX search off)")
        cfg.agx_dir = str((path.parent / agx_dir).resolve()) if agx_dir else ""
    mfs = table.get("max-file-size")
    if mfs is not None:
        if isinstance(mfs, bool) or not isinstance(mfs, (int, float)) or not 0 < mfs <= MAX_FILE_MB_CEILING:
            raise ConfigError(f"{path}: 'max-file-size' must be a number of megabytes in (0, {MAX_FILE_MB_CEILING}]; "
                              f"got {mfs!r}")
        cfg.max_file_mb = float(mfs)
    fmt = table.get("fmt", {})
    if not isinstance(fmt, dict):
        raise ConfigError(f"{path}: 'fmt' must be a table")
    cfg.fmt_exclude = _str_list(path, "fmt.exclude", fmt.get("exclude", []))
    check = table.get("check", {})
    if not isinstance(check, dict):
        raise ConfigError(f"{path}: 'check' must be a table")
    extra = set(check) - {"integrator", "timestep"}
    if extra:
        raise ConfigError(f"{path}: unknown key(s) check.{', check.'.join(sorted(extra))}; "
                          f"known: check.integrator, check.timestep")
    integ = check.get("integrator")
    if integ is not None:
        if integ not in INTEGRATORS:
            raise ConfigError(f"{path}: 'check.integrator' must be one of {', '.join(INTEGRATORS)}; got {integ!r}")
        cfg.check_integrator = integ
    ts = check.get("timestep")
    if ts is not None:
        if isinstance(ts, bool) or not isinstance(ts, (int, float)) or not 1e-5 <= ts <= 0.1:
            raise ConfigError(f"{path}: 'check.timestep' must be a number of seconds in [1e-5, 0.1]; got {ts!r}")
        cfg.check_timestep = float(ts)
    return cfg


@lru_cache(maxsize=256)
def _config_for_dir(folder: str) -> Config:
    found = find_config_file(Path(folder))
    if found is None:
        return Config()
    return parse_config(*found)


def config_for(path: str | Path) -> Config:
    p = Path(path)
    folder = p if p.is_dir() else p.parent
    return _config_for_dir(str(folder.resolve()) if str(folder) else os.getcwd())
