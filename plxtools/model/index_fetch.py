"""Fetch one wheel from the package index without pip.

`plx bundles install` runs inside plx's own interpreter, which has no pip under `pipx install`,
`uv tool install` or in a `uv venv`. There the wheel of `openplx-bundles==VERSION` is found on the
index pip (or uv) is configured for, through the simple repository API (PEP 503 pages), and
downloaded with urllib; its sha256 is checked when the index gives one. Only the standard library.

Where the index comes from, first found wins: PIP_INDEX_URL, UV_DEFAULT_INDEX / UV_INDEX_URL,
`index-url` in pip's configuration files (PIP_CONFIG_FILE, else the global, user and environment
files), else https://pypi.org/simple/. Extra indexes and find-links folders add to it the same way
(PIP_EXTRA_INDEX_URL, UV_INDEX / UV_EXTRA_INDEX_URL, PIP_FIND_LINKS, `extra-index-url`,
`find-links`).
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

DEFAULT_INDEX = "https://pypi.org/simple/"


class FetchError(Exception):
    """The wheel could not be found or downloaded; `network` tells an unreachable index apart."""

    def __init__(self, message: str, network: bool = False):
        super().__init__(message)
        self.network = network


@dataclass
class Sources:
    """The indexes (simple-API base URLs) and find-links folders or pages to look in, in order."""

    indexes: list[str] = field(default_factory=list)
    find_links: list[str] = field(default_factory=list)


def _split(value: str | None) -> list[str]:
    return [v for v in re.split(r"\s+", value or "") if v]


def _config_files() -> list[Path]:
    """pip's configuration files, lowest priority first (pip's documented order)."""
    if os.environ.get("PIP_CONFIG_FILE"):
        return [Path(os.environ["PIP_CONFIG_FILE"])]
    dirs = os.environ.get("XDG_CONFIG_DIRS", "/etc/xdg").split(os.pathsep)
    files = [Path(d) / "pip" / "pip.conf" for d in reversed(dirs) if d] + [Path("/etc/pip.conf")]
    home = Path.home()
    xdg_home = Path(os.environ.get("XDG_CONFIG_HOME") or home / ".config")
    files += [home / ".pip" / "pip.conf", xdg_home / "pip" / "pip.conf", Path(sys.prefix) / "pip.conf"]
    if sys.platform == "win32":  # pragma: no cover - the same names pip reads there
        appdata = os.environ.get("APPDATA", "")
        files += [Path(appdata) / "pip" / "pip.ini", Path(sys.prefix) / "pip.ini"]
    return files


def _from_config() -> dict[str, str]:
    """index-url, extra-index-url and find-links from pip's files ([global], then [download])."""
    import configparser

    found: dict[str, str] = {}
    for path in _config_files():
        parser = configparser.RawConfigParser()
        try:
            parser.read(path, encoding="utf-8")
        except (configparser.Error, OSError, UnicodeDecodeError):
            continue
        for section in ("global", "download"):
            for key in ("index-url", "extra-index-url", "find-links", "no-index"):
                if parser.has_option(section, key):
                    found[key] = parser.get(section, key)
    return found


def configured_sources(env: dict[str, str] | None = None) -> Sources:
    """Where pip would look for a package, as far as its environment variables and files say."""
    env = os.environ if env is None else env
    conf = _from_config()
    no_index = (env.get("PIP_NO_INDEX") or conf.get("no-index") or "").lower() in ("1", "true", "yes", "on")
    index = (env.get("PIP_INDEX_URL") or env.get("UV_DEFAULT_INDEX") or env.get("UV_INDEX_URL")
             or conf.get("index-url") or DEFAULT_INDEX)
    extra = _split(env.get("PIP_EXTRA_INDEX_URL")) or _split(conf.get("extra-index-url"))
    extra += _split(env.get("UV_INDEX")) + _split(env.get("UV_EXTRA_INDEX_URL"))
    links = _split(env.get("PIP_FIND_LINKS")) or _split(conf.get("find-links"))
    return Sources([] if no_index else [index, *extra], links)


def _normalise(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _wheel_name_matches(filename: str, project: str, version: str) -> bool:
    """A pure-Python wheel of exactly `project==version` (the bundles are data: py3-none-any)."""
    if not filename.endswith(".whl"):
        return False
    parts = filename[:-4].split("-")
    return (len(parts) >= 5 and _normalise(parts[0]) == _normalise(project) and parts[1] == version
            and parts[-1] == "any")


_HREF = re.compile(r"""<a\s[^>]*href\s*=\s*["']([^"']+)["']""", re.IGNORECASE)


def _read(url: str, timeout: float) -> bytes:
    from urllib.request import Request, urlopen

    if url.startswith("file:"):
        from urllib.request import url2pathname
        from urllib.parse import urlparse

        path = Path(url2pathname(urlparse(url).path))
        if path.is_dir():
            path = path / "index.html"  # a simple index laid out as folders on disk
        return path.read_bytes()
    request = Request(url, headers={"Accept": "text/html", "User-Agent": "plxtools"})
    with urlopen(request, timeout=timeout) as response:  # noqa: S310 - the configured index
        return response.read()


def _links(page_url: str, timeout: float) -> list[str]:
    """The absolute URLs a simple-API page (or a find-links page) links to; [] when it has none."""
    from urllib.error import HTTPError
    from urllib.parse import urljoin
    import html

    try:
        text = _read(page_url, timeout).decode("utf-8", "replace")
    except HTTPError as exc:
        if exc.code == 404:
            return []
        raise
    except FileNotFoundError:
        return []
    return [urljoin(page_url, html.unescape(href)) for href in _HREF.findall(text)]


def _candidates(sources: Sources, project: str, version: str, timeout: float) -> tuple[list[str], list[str]]:
    """Wheel URLs of project==version, and the errors of indexes that could not be read."""
    from urllib.parse import urlparse, unquote

    found: list[str] = []
    errors: list[str] = []
    for folder in sources.find_links:
        local = Path(unquote(urlparse(folder).path)) if folder.startswith("file:") else Path(folder)
        if "://" not in folder or folder.startswith("file:"):
            if local.is_dir():
                found += [p.as_uri() for p in sorted(local.glob("*.whl")) if _wheel_name_matches(p.name, project, version)]
            continue
        try:
            found += [u for u in _links(folder, timeout) if _wheel_name_matches(_filename(u), project, version)]
        except (OSError, ValueError) as exc:
            errors.append(f"{folder}: {_reason(exc)}")
    for index in sources.indexes:
        page = index.rstrip("/") + "/" + _normalise(project) + "/"
        try:
            found += [u for u in _links(page, timeout) if _wheel_name_matches(_filename(u), project, version)]
        except (OSError, ValueError) as exc:
            errors.append(f"{index}: {_reason(exc)}")
        if found:
            break
    return found, errors


def _filename(url: str) -> str:
    from urllib.parse import unquote, urlparse

    return unquote(urlparse(url).path.rsplit("/", 1)[-1])


def _reason(exc: BaseException) -> str:
    reason = getattr(exc, "reason", None)
    return str(reason or exc.strerror or exc) if isinstance(exc, OSError) else str(exc)


def download(project: str, version: str, folder: Path, *, timeout: float = 15.0,
             sources: Sources | None = None,
             progress: Callable[[int, int | None], None] | None = None) -> Path:
    """Download the wheel of `project==version` into `folder` (written whole, then renamed);
    `progress(done, total)` is told the bytes as they come."""
    import hashlib
    from urllib.parse import urldefrag

    sources = configured_sources() if sources is None else sources
    if not sources.indexes and not sources.find_links:
        raise FetchError("no package index is configured (pip's no-index is set)")
    urls, errors = _candidates(sources, project, version, timeout)
    if not urls:
        if errors:
            raise FetchError("the package index cannot be reached (" + "; ".join(errors) + ")", network=True)
        raise FetchError(f"{project} {version} is not on the package index "
                         f"({', '.join(sources.indexes + sources.find_links)})")
    url, fragment = urldefrag(urls[0])
    expected = fragment[len("sha256="):].lower() if fragment.startswith("sha256=") else None
    target = folder / _filename(url)
    partial = folder / f".{target.name}.{os.getpid()}.part"
    folder.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha256()
    done = 0
    try:
        with open(partial, "wb") as out:
            for chunk, total, done in _chunks(url, timeout):
                out.write(chunk)
                digest.update(chunk)
                if progress is not None:
                    progress(done, total)
        if progress is not None:
            progress(done, done)  # complete: a bar of unknown size closes too
        if expected is not None and digest.hexdigest() != expected:
            raise FetchError(f"{target.name} from {url} does not match the index's sha256 (a broken download?)")
        os.replace(partial, target)
    except OSError as exc:
        raise FetchError(f"cannot download {url}: {_reason(exc)}", network=True) from None
    finally:
        partial.unlink(missing_ok=True)
    return target


def _chunks(url: str, timeout: float):
    """(bytes, total or None, bytes so far) as the file arrives."""
    if url.startswith("file:"):
        data = _read(url, timeout)
        yield data, len(data), len(data)
        return
    from urllib.request import Request, urlopen

    with urlopen(Request(url, headers={"User-Agent": "plxtools"}), timeout=timeout) as response:  # noqa: S310
        length = response.headers.get("Content-Length")
        total = int(length) if length and length.isdigit() else None
        done = 0
        while True:
            chunk = response.read(1 << 16)
            if not chunk:
                return
            done += len(chunk)
            yield chunk, total, done
