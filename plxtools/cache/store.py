"""Cache entries: authenticated, written atomically, pruned least recently used first.

Each entry is one file `<cache>/<kind>/<key>`: a 32-byte keyed BLAKE2b tag, then the payload.
The tag covers the kind, the key and the payload and is made with the per-user secret
(`folder.secret`), so an entry planted or edited by anyone without that secret (another user, a
cache restored from another machine or branch), truncated or moved to another key is simply a
miss, and is rewritten by the next run. Payloads are marshal data (the entries a replayed run
reads) or JSON, except the bundle program (a pickle); each is decoded only after its tag is checked.

Writes go to a temporary file in the same folder and are renamed over the entry; a failed write
(a full disk) removes its temporary file. When the cache grows over its cap (PLX_CACHE_MAX_MB,
default 512) the least recently used entries are removed: a hit refreshes an entry's mtime (at
most once a minute, to keep hits cheap).
"""

from __future__ import annotations

import errno
import os
import stat as _stat

from plxtools.cache import folder

TAG_SIZE = 32
KINDS = ("replays", "results", "formatted", "bundle-sets", "programs", "renames", "stamps", "lsp", "grammars")
_DEFAULT_CAP_MB = 512
_REFRESH_NS = 60 * 10**9


try:
    from _blake2 import blake2b as _blake2b  # without hashlib's OpenSSL start-up (a replayed run is short)
except ImportError:  # pragma: no cover - another Python implementation
    from hashlib import blake2b as _blake2b


def new_hash(data: bytes = b""):
    """A 256-bit BLAKE2b hash object (keys and content digests)."""
    return _blake2b(data, digest_size=32)


def _tag(secret: bytes, kind: str, key: str, payload: bytes) -> bytes:
    h = _blake2b(digest_size=TAG_SIZE, key=secret)
    h.update(f"{kind}\0{key}\0".encode())
    h.update(payload)
    return h.digest()


def _equal(a: bytes, b: bytes) -> bool:
    try:
        from _operator import _compare_digest
    except ImportError:  # pragma: no cover
        from hmac import compare_digest as _compare_digest
    return _compare_digest(a, b)


def _valid_key(key: str) -> bool:
    return bool(key) and len(key) <= 200 and key.replace("-", "").replace("_", "").replace(".", "").isalnum() \
        and not key.startswith(".")


def entry_path(kind: str, key: str) -> str | None:
    root = folder.root()
    return None if root is None else os.path.join(root, kind, key)


def read_whole(path, flags: int = 0) -> tuple[os.stat_result, bytes]:
    """A file's stat (taken from the open file, before reading) and its bytes, in a few system
    calls (a cold run reads hundreds of files this way). Raises OSError."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | flags)  # a FIFO planted here never blocks
    try:
        st = os.fstat(fd)
        if not _stat.S_ISREG(st.st_mode):
            raise OSError(errno.EINVAL, "not a regular file")
        chunks = []
        while True:
            chunk = os.read(fd, max(st.st_size + 1, 65536))
            if not chunk:
                break
            chunks.append(chunk)
    finally:
        os.close(fd)
    return st, b"".join(chunks)


def get(kind: str, key: str) -> bytes | None:
    """The payload stored under (kind, key), or None: no usable cache, no entry, or an entry
    that is not authentic (planted, corrupt, truncated)."""
    if not _valid_key(key):
        return None
    path = entry_path(kind, key)
    secret = folder.secret() if path is not None else None
    if secret is None:
        return None
    try:
        st, data = read_whole(path, getattr(os, "O_NOFOLLOW", 0))
    except OSError:
        return None
    if len(data) < TAG_SIZE or not _equal(data[:TAG_SIZE], _tag(secret, kind, key, memoryview(data)[TAG_SIZE:])):
        return None
    import time

    now = time.time_ns()
    if now - st.st_mtime_ns > _REFRESH_NS:  # least recently used: a hit counts as a use
        try:
            os.utime(path, ns=(now, now))
        except OSError:
            pass
    return data[TAG_SIZE:]


def put(kind: str, key: str, payload: bytes) -> bool:
    """Store `payload` under (kind, key); False when it was not stored (no cache, full disk)."""
    if not _valid_key(key):
        return False
    path = entry_path(kind, key)
    secret = folder.secret() if path is not None else None
    if secret is None:
        return False
    sub = os.path.dirname(path)
    tmp = os.path.join(sub, f".{key}.{os.getpid()}.tmp")
    try:
        os.makedirs(sub, mode=0o700, exist_ok=True)
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0), 0o600)
        try:
            view = memoryview(_tag(secret, kind, key, payload) + payload)
            while view:
                view = view[os.write(fd, view):]
        finally:
            os.close(fd)
        os.replace(tmp, path)
    except BaseException as exc:  # a full disk, a vanished folder, an interrupt: leave nothing behind
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if not isinstance(exc, OSError):
            raise
        return False
    if len(payload) > (1 << 20) or os.urandom(1)[0] < 4:  # now and then, and after a large entry
        prune()
    return True


def get_json(kind: str, key: str):
    data = get(kind, key)
    if data is None:
        return None
    import json

    try:
        return json.loads(data)
    except ValueError:
        return None


def put_json(kind: str, key: str, value) -> bool:
    import json

    return put(kind, key, json.dumps(value, separators=(",", ":")).encode())


# Entries a replayed run reads (replays, stamps, bundle-sets, results) are marshal data: the module
# is built into the interpreter (no import, unlike json's 2-3 ms) and loads several times faster.
# marshal is unsafe only on data an attacker wrote; these payloads are read after their tag
# proved this user's plx wrote them. The prefix names the form, so an entry of an older form
# (JSON) is a miss, not a misread.
_DATA_FORM = b"m4\n"


def get_data(kind: str, key: str):
    """A value stored by `put_data` (plain lists, dicts, strings, numbers, None), or None."""
    data = get(kind, key)
    if data is None or not data.startswith(_DATA_FORM):
        return None
    import marshal

    try:
        return marshal.loads(memoryview(data)[len(_DATA_FORM):])
    except (ValueError, EOFError, TypeError):
        return None


def put_data(kind: str, key: str, value) -> bool:
    import marshal

    try:
        payload = marshal.dumps(value, 4)
    except ValueError:  # a subclass of str or int (marshal takes exact types): as JSON would store it
        import json

        try:
            payload = marshal.dumps(json.loads(json.dumps(value)), 4)
        except (TypeError, ValueError):
            return False
    return put(kind, key, _DATA_FORM + payload)


def cap_bytes() -> int:
    try:
        mb = float(os.environ.get("PLX_CACHE_MAX_MB", _DEFAULT_CAP_MB))
    except ValueError:
        mb = _DEFAULT_CAP_MB
    return max(0, int(mb * (1 << 20)))


def entries(root: str | None = None) -> list[tuple[str, str, int, int]]:
    """(kind, path, size, mtime_ns) of every entry."""
    root = root or folder.root(create=False)
    out = []
    if root is None:
        return out
    for kind in KINDS:
        try:
            names = os.listdir(os.path.join(root, kind))
        except OSError:
            continue
        for name in names:
            p = os.path.join(root, kind, name)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            out.append((kind, p, st.st_size, st.st_mtime_ns))
    return out


def prune(cap: int | None = None) -> int:
    """Remove least recently used entries until the cache holds at most 80 % of its cap (when it
    is over the cap). Returns the number of entries removed."""
    cap = cap_bytes() if cap is None else cap
    found = entries()
    total = sum(e[2] for e in found)
    if total <= cap:
        return 0
    removed = 0
    for _kind, p, size, _m in sorted(found, key=lambda e: e[3]):
        if total <= cap * 0.8:
            break
        try:
            os.unlink(p)
        except OSError:
            continue
        total -= size
        removed += 1
    return removed


# what earlier versions of plx left in the cache folder (pickles, marshal data): removed by `clean`
LEGACY = ("lint-results", "fmt-formatted", "lsp-initialize", "runs")
LEGACY_PREFIXES = ("official-", "renames-", "grammar.lark-cache")


def clean() -> tuple[int, int]:
    """Remove every entry (and what older versions of plx left). Returns (files, bytes)."""
    import shutil

    root = folder.root(create=False)
    if root is None:
        return 0, 0
    files = size = 0
    for kind, p, s, _m in entries(root):
        try:
            os.unlink(p)
            files += 1
            size += s
        except OSError:
            pass
    for name in os.listdir(root):
        p = os.path.join(root, name)
        if name in LEGACY or name.startswith(LEGACY_PREFIXES):
            try:
                if os.path.isdir(p) and not os.path.islink(p):
                    shutil.rmtree(p)
                else:
                    os.unlink(p)
                files += 1
            except OSError:
                pass
    return files, size
