"""Where plx keeps its cache, and whether that place can be trusted.

A cache entry decides what plx answers, so the folder must be the user's own: it is created
private (0700), and a folder owned by another user or writable by other users is not used (one
warning, and the run goes on uncached). The secret that authenticates entries (`store`) lives
outside the cache folder, so a cache restored from elsewhere (a CI cache, a copied home) cannot
carry its own valid entries.
"""

from __future__ import annotations

import errno
import os
import stat
import sys

_checked: dict[str, str | None] = {}  # cache folder -> itself when usable, None when not
_warned: set[str] = set()


def location() -> str:
    """The cache folder plx would use (PLX_CACHE_DIR, else XDG_CACHE_HOME, else ~/.cache; then plxtools/)."""
    base = os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or os.path.join(
        os.path.expanduser("~"), ".cache")
    return os.path.join(base, "plxtools")


def _home_missing(path: str) -> str | None:
    """When `path` lies under the home folder by default (no PLX_CACHE_DIR / XDG_*_HOME) and the
    home folder does not exist: a sentence saying so. Service accounts have HOME=/nonexistent so
    that nothing is created there; plx then runs uncached rather than create it."""
    home = os.path.expanduser("~")
    if not path.startswith(os.path.join(home, "")):
        return None
    if os.path.isdir(home):
        return None
    return f"the home folder {home} does not exist"


def _make_folders(path: str, default_home: bool) -> None:
    """Create `path` private (0700). Under the default home-based location only the parts below
    an existing home folder are created (`.cache/plxtools`, `.config/plxtools`), never the home
    folder itself."""
    if default_home:
        why = _home_missing(path)
        if why is not None:
            raise FileNotFoundError(errno.ENOENT, why)
    os.makedirs(path, mode=0o700, exist_ok=True)


def warn(message: str) -> None:
    """Say once per process why the cache is not used."""
    if message not in _warned:
        _warned.add(message)
        print(f"plx: warning: {message}; running without the cache", file=sys.stderr)


def untrusted_reason(st) -> str | None:
    """Why a folder or file with this stat must not be trusted, or None."""
    if hasattr(os, "getuid") and st.st_uid != os.getuid():
        return "is owned by another user"
    if st.st_mode & 0o022:
        return "can be written by other users"
    return None


def root(create: bool = True) -> str | None:
    """The cache folder when it can be trusted (created private if missing), else None."""
    path = location()
    if path in _checked:
        return _checked[path]
    try:
        if create:
            _make_folders(path, not (os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")))
        st = os.stat(path)
    except OSError as exc:
        if not create:
            return None
        warn(f"cannot use the cache folder {path}: {exc.strerror}")
        _checked[path] = None
        return None
    reason = untrusted_reason(st)
    if reason is not None:
        warn(f"not using the cache folder {path}: it {reason}")
    _checked[path] = None if reason else path
    return _checked[path]


def secret_path() -> str:
    """The per-user secret's file: PLX_CACHE_SECRET_FILE, else $XDG_CONFIG_HOME/plxtools/cache-secret
    (~/.config/plxtools/cache-secret)."""
    return os.environ.get("PLX_CACHE_SECRET_FILE") or os.path.join(
        os.environ.get("XDG_CONFIG_HOME") or os.path.join(os.path.expanduser("~"), ".config"),
        "plxtools", "cache-secret")


_secrets: dict[str, bytes | None] = {}
_SECRET_SIZE = 32


def secret() -> bytes | None:
    """The per-user key that authenticates entries, created on first use (0600), or None (the
    run is then uncached) when it is not private, sits inside the cache folder, or cannot be made."""
    path = secret_path()
    if path in _secrets:
        return _secrets[path]
    value = _read_secret(path)  # None: there is none yet; b"": there is one, not usable
    if value is None:
        value = _make_secret(path)
    _secrets[path] = value or None
    return value


def _read_secret(path: str) -> bytes | None:
    # O_NONBLOCK: a FIFO put at the secret's path must not block the open; fstat then refuses
    # anything that is not a regular file (a folder, a FIFO, a device) before a byte is read
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        return None
    except OSError as exc:
        warn(f"cannot read the cache secret {path}: {exc.strerror}")
        return b""
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            warn(f"cannot read the cache secret {path}: it is not a regular file")
            return b""
        data = os.read(fd, _SECRET_SIZE + 1)
    except OSError as exc:
        warn(f"cannot read the cache secret {path}: {exc.strerror}")
        return b""
    finally:
        os.close(fd)
    if hasattr(os, "getuid") and (st.st_uid != os.getuid() or st.st_mode & 0o077):
        warn(f"not using the cache secret {path}: it is readable or owned by another user")
        return b""
    if len(data) != _SECRET_SIZE:
        warn(f"not using the cache secret {path}: it is not {_SECRET_SIZE} bytes (delete it to make a new one)")
        return b""
    return data


def _make_secret(path: str) -> bytes | None:
    cache = os.path.realpath(location())
    real = os.path.realpath(path)
    if real == cache or real.startswith(cache + os.sep):
        warn(f"the cache secret {path} is inside the cache folder")
        return None
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        _make_folders(os.path.dirname(path), not (os.environ.get("PLX_CACHE_SECRET_FILE")
                                                  or os.environ.get("XDG_CONFIG_HOME")))
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            os.write(fd, os.urandom(_SECRET_SIZE))
        finally:
            os.close(fd)
        try:
            os.link(tmp, path)  # never replaces a secret another process made meanwhile
        except FileExistsError:
            pass
    except OSError as exc:
        warn(f"cannot create the cache secret {path}: {exc.strerror}")
        return None
    finally:
        try:
            os.unlink(tmp)
        except OSError:
            pass
    value = _read_secret(path)
    return value or None


def forget() -> None:
    """Drop what this process learnt about folders and secrets (tests; an in-process CLI run)."""
    _checked.clear()
    _secrets.clear()
    _warned.clear()
