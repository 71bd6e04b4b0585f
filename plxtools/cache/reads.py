"""What a computation really read, recorded by the code that read it (the rule of salsa, the
incremental engine of rust-analyzer: dependencies are recorded, never declared).

Code that reads something a cached answer may depend on goes through this module: `read_bytes`
(a file, by its content), `kind` (whether a path is a file, a folder or nothing: a config file
looked for and not found is a dependency too), `listdir` (a folder's names) and `env` (an
environment variable). Each read is noted in every open `recording()`; an answer is stored with
the reads of its recording, and believed later only when `holds` says every read would give the
same value now.

A file is compared by content. Its stat is kept only as a fast path that cannot be fooled, as in
git's index: size, mtime, ctime, inode and device must all be equal (ctime cannot be set by a
user: `touch -r`, `cp -p`, `rsync -t` or an unpacked archive change it), and a file whose mtime or
ctime is within two seconds of the moment it was recorded is "racily clean" and has its bytes
hashed again every time.
"""

from __future__ import annotations

import os
import stat as _stat
import time

from plxtools.cache.store import new_hash

_frames: list[list] = []
RACY_NS = 2 * 10**9


class recording:
    """`with recording() as deps:` collects every read made inside (nested recordings each get
    them all)."""

    def __enter__(self) -> list:
        self.deps: list = []
        _frames.append(self.deps)
        return self.deps

    def __exit__(self, *exc) -> None:
        _frames.remove(self.deps)


def active() -> bool:
    return bool(_frames)


# Reads of the semantic model (names looked up, models resolved, file-wide tables a rule built),
# recorded by the language server to re-use a statement's findings while nothing it read changed
# (rules/incremental.py). They are only meaningful inside one process, so they go to recordings of
# their own: a cached answer's recording (above) holds only what `holds` can check again.
_model_frames: list[list] = []


class model_recording:
    """`with model_recording() as seen:` collects the model reads made inside."""

    def __enter__(self) -> list:
        self.seen: list = []
        _model_frames.append(self.seen)
        return self.seen

    def __exit__(self, *exc) -> None:
        _model_frames.remove(self.seen)


def model_active() -> bool:
    return bool(_model_frames)


def note_model(dep) -> None:
    for f in _model_frames:
        f.append(dep)


def note(dep: list) -> None:
    for f in _frames:
        f.append(dep)


def note_all(deps: list) -> None:
    """Add reads recorded earlier (a cache hit's own dependencies) to every open recording."""
    for f in _frames:
        f.extend(deps)


def digest(data: bytes) -> str:
    return new_hash(data).hexdigest()


def _sig(st, data: bytes) -> list:
    return [st.st_size, st.st_mtime_ns, st.st_ctime_ns, st.st_ino, st.st_dev, digest(data), time.time_ns()]


class NotRegularFile(OSError):
    """A path that is not a regular file (a FIFO, a device, a folder, a socket): it is not read,
    since reading it could block forever (a FIFO) or never end (`/dev/zero`). `strerror` says what
    it is."""

    def __init__(self, what: str):
        super().__init__(f"it is {what}, not a regular file: not read")
        self.strerror = f"it is {what}, not a regular file: not read"


class FileTooLarge(OSError):
    """A file above the size limit the caller gave: refused before it is read."""

    def __init__(self, size: int, limit: int):
        message = (f"it is {size / 2**20:.3g} MB, above the limit of {limit / 2**20:.3g} MB: not read "
                   "(raise it with max-file-size in plx.toml)")
        super().__init__(message)
        self.strerror = message
        self.size, self.limit = size, limit


_WHAT = ((_stat.S_ISDIR, "a folder"), (_stat.S_ISCHR, "a character device"), (_stat.S_ISBLK, "a block device"),
         (_stat.S_ISFIFO, "a FIFO (named pipe)"), (_stat.S_ISSOCK, "a socket"))


def what_is(mode: int) -> str:
    """What a non-regular file is, in words."""
    for test, name in _WHAT:
        if test(mode):
            return name
    return "a special file"


# O_NONBLOCK: opening a FIFO for reading blocks until a writer comes; with it the open returns at
# once, and the fstat below refuses the FIFO before any read. A regular file ignores the flag.
_OPEN_FLAGS = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0)


def open_regular(path) -> tuple[int, os.stat_result]:
    """An open descriptor on a regular file and its stat; raises OSError (`NotRegularFile` for a
    FIFO, a device, a folder or a socket, also behind a symlink) without ever blocking."""
    fd = os.open(path, _OPEN_FLAGS)
    try:
        st = os.fstat(fd)
        if not _stat.S_ISREG(st.st_mode):
            raise NotRegularFile(what_is(st.st_mode))
    except BaseException:
        os.close(fd)
        raise
    return fd, st


def read_regular(path, limit: int | None = None) -> tuple[os.stat_result, bytes]:
    """A regular file's stat (taken from the open file, before reading) and its bytes: never
    blocks, and never reads more than the size it had when opened plus one chunk (a file that
    grows meanwhile is read to where it was), nor anything above `limit` bytes (`FileTooLarge`)."""
    fd, st = open_regular(path)
    try:
        if limit is not None and st.st_size > limit:
            raise FileTooLarge(st.st_size, limit)
        chunks = []
        left = st.st_size + 1  # one byte more than the stat said: a file that grew is still read whole up to it
        while left > 0:
            chunk = os.read(fd, min(max(left, 65536), 1 << 24))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
    finally:
        os.close(fd)
    return st, chunks[0] if len(chunks) == 1 else b"".join(chunks)


def read_stream(stream, limit: int) -> bytes:
    """Standard input, read up to `limit` bytes: more is `FileTooLarge` (`cat /dev/zero | plx lint -`
    must stop, not fill the memory)."""
    data = stream.read(limit + 1)
    if len(data) > limit:
        raise FileTooLarge(len(data), limit)
    return data


def read_bytes(path, limit: int | None = None) -> bytes:
    """The bytes of a regular file, noted by content (the stat is taken from the open file, before
    reading). Raises OSError as open() does, `NotRegularFile` (never blocking, never reading it) for
    anything else, `FileTooLarge` above `limit`; a missing file is noted as missing."""
    p = os.fspath(path)
    try:
        st, data = read_regular(p, limit)
    except OSError:
        if _frames:
            note(["k", p, _kind(p)])
        raise
    if _frames:
        note(["f", p, _sig(st, data)])
    return data


def _kind(p: str) -> str | None:
    try:
        mode = os.stat(p).st_mode
    except (OSError, ValueError):
        return None
    return "file" if _stat.S_ISREG(mode) else "dir" if _stat.S_ISDIR(mode) else "other"


def kind(path) -> str | None:
    """'file', 'dir', 'other' or None (nothing there), noted."""
    p = os.fspath(path)
    k = _kind(p)
    if _frames:
        note(["k", p, k])
    return k


def is_file(path) -> bool:
    return kind(path) == "file"


def is_dir(path) -> bool:
    return kind(path) == "dir"


def _folder_sig(names: list[str], st) -> list:
    return [names, st.st_mtime_ns, st.st_ctime_ns, st.st_ino, st.st_dev, time.time_ns()]


def listdir(path) -> list[str]:
    """A folder's names, sorted, noted with the folder's stat (raises OSError as os.listdir does)."""
    p = os.fspath(path)
    try:
        st = os.stat(p)  # before listing: a change while it lists gives a newer stat next time
        names = sorted(os.listdir(p))
    except OSError:
        if _frames:
            note(["l", p, None])
        raise
    if _frames:
        note(["d", p, _folder_sig(names, st)])
    return names


def scan(path) -> list[tuple[str, bool]]:
    """A folder's (name, is a real folder: not a link to one) pairs, sorted by name, with the
    names noted as `listdir` notes them (one scandir: no stat per entry). Raises OSError."""
    p = os.fspath(path)
    try:
        st = os.stat(p)
        with os.scandir(p) as it:
            got = sorted((e.name, e.is_dir(follow_symlinks=False)) for e in it)
    except OSError:
        if _frames:
            note(["l", p, None])
        raise
    if _frames:
        note(["d", p, _folder_sig([n for n, _d in got], st)])
    return got


def env(name: str) -> str | None:
    """An environment variable, noted."""
    value = os.environ.get(name)
    if _frames:
        note(["e", name, value])
    return value


def realpath(path) -> str:
    p = os.fspath(path)
    real = os.path.realpath(p)
    if _frames:
        note(["r", p, real])
    return real


def holds(dep) -> bool:
    """Whether reading again would give what was recorded."""
    try:
        what, p, value = dep
        if what == "f":
            return _file_holds(p, value)
        if what == "k":
            return _kind(p) == value
        if what == "d":
            return _listing_holds(p, value)
        if what == "l":
            try:
                return sorted(os.listdir(p)) == value
            except OSError:
                return value is None
        if what == "e":
            return os.environ.get(p) == value
        if what == "r":
            return os.path.realpath(p) == value
    except (TypeError, ValueError):
        pass
    return False


def _listing_holds(p: str, sig) -> bool:
    """A folder lists the same names when its stat is the one recorded: creating, removing or
    renaming an entry sets the folder's mtime and ctime (POSIX), a ctime cannot be set by a user,
    a folder replaced by another has another inode, and one changed within RACY_NS of its record
    is listed again (as a racily clean file is hashed again). Otherwise it is listed."""
    names, mtime, ctime, ino, dev, recorded = sig
    try:
        st = os.stat(p)
    except (OSError, ValueError):
        return False
    if (st.st_mtime_ns == mtime and st.st_ctime_ns == ctime and st.st_ino == ino and st.st_dev == dev
            and _stat.S_ISDIR(st.st_mode) and recorded - (mtime if mtime > ctime else ctime) > RACY_NS):
        return True
    try:
        return sorted(os.listdir(p)) == names
    except OSError:
        return False


def _file_holds(p: str, sig) -> bool:
    size, mtime, ctime, ino, dev, want, recorded = sig
    try:
        st = os.stat(p)
    except (OSError, ValueError):
        return False
    if st.st_size != size or not _stat.S_ISREG(st.st_mode):
        return False
    if (st.st_mtime_ns == mtime and st.st_ctime_ns == ctime and st.st_ino == ino and st.st_dev == dev
            and not is_racy(sig)):
        return True
    try:
        return digest(read_regular(p, size + 1)[1]) == want
    except OSError:
        return False


def is_racy(sig) -> bool:
    """Whether a file's record was taken too soon after its last change to trust its stat."""
    return sig[6] - max(sig[1], sig[2]) <= RACY_NS


def all_hold(deps) -> bool:
    """Whether every read holds. Files are checked in one tight loop (a replayed run checks a
    few hundred): the stat fast path inline, the content only when it cannot decide."""
    if not isinstance(deps, list):
        return False
    stat = os.stat
    try:
        for d in deps:
            if d[0] == "f":
                size, mtime, ctime, ino, dev, _want, recorded = sig = d[2]
                try:
                    st = stat(d[1])
                except (OSError, ValueError):
                    return False
                if (st.st_mtime_ns == mtime and st.st_ctime_ns == ctime and st.st_size == size and st.st_ino == ino
                        and st.st_dev == dev and recorded - (mtime if mtime > ctime else ctime) > RACY_NS):
                    continue
                if not _file_holds(d[1], sig):
                    return False
            elif not holds(d):
                return False
    except (TypeError, IndexError, KeyError, ValueError):
        return False
    return True


def content_digest(deps: list) -> str:
    """A digest of what was read (values and contents, not stats): two loads that read the same
    things have the same digest."""
    h = new_hash()
    for what, p, value in deps:
        v = value[5] if what == "f" else value[0] if what == "d" else value
        h.update(repr((what, p, v)).encode())
    return h.hexdigest()


def dedupe(deps: list) -> list:
    """The reads without repeats. A thing read twice with different results (a file saved during
    the run) stays twice: both cannot hold, so such an answer is never believed."""
    seen: set = set()
    out = []
    for d in deps:
        what, v = d[0], d[2]
        if what == "f" and v:
            v = v[5]  # the content, not the stat
        elif what == "d":
            v = tuple(v[0])  # the names, not the stat
        elif isinstance(v, list):
            v = tuple(v)
        k = (what, d[1], v)
        if k not in seen:
            seen.add(k)
            out.append(d)
    return out
