"""The one safe writer for every file plxtools writes for the user: the file stays theirs.

`write_atomic` rewrites a user's source file (`plx fmt`, `plx lint --fix`, `plx migrate`);
`write_output` writes a file the user asked for by name (`plx check --trace`, `--export-mjcf`).
Both hold these guarantees (docs/reliability.md lists the test that proves each):

- A symlink is written through: the link stays a link and its target gets the new text.
- Anything that is not a regular file (a device, a FIFO, a socket, a folder) is refused with a
  message that says what it is; nothing is created in its place.
- The new contents are first written to a temporary file next to the real one and flushed to disk.
  Until they are complete, the original is not touched, so a crash or a full disk (ENOSPC) leaves
  it as it was, byte for byte, and the temporary file is removed.
- A regular file with one link whose owner can be kept is replaced by renaming the temporary file
  over it (atomic). A file with hard links (or an owner we cannot give to a new file) must keep its
  inode: the space for the new size is reserved first (`posix_fallocate`), then the contents are
  copied in; if that still fails, the old contents are written back, and if even that fails the
  complete temporary copy is kept and the message names it. The only complete copy is never deleted.
- The mode of a replaced file is kept; a new file gets the usual mode (0666 less the umask).
- `expected` (the bytes the caller read) is compared with what is on disk right before replacing:
  if another program (an editor's save) changed the file in between, it is left alone and
  `ChangedOnDisk` says so, as editors do.

Every failure is an `OSError` whose `strerror` is the whole message, meant for the user; callers
report it and exit 2. Nothing here imports beyond the standard library.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Callable
from pathlib import Path


class WriteError(OSError):
    """A file could not be written; `strerror` is the whole message."""

    def __init__(self, message: str, keeps_copy: bool = False):
        super().__init__(message)
        self.strerror = message
        self.keeps_copy = keeps_copy  # the temporary file is the only complete copy: not removed


class ChangedOnDisk(WriteError):
    """The file on disk is no longer what the caller read: another program saved it meanwhile."""


_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def _why(exc: OSError) -> str:
    return exc.strerror or str(exc)


def _kind(mode: int) -> str:
    for test, name in _KINDS:
        if test(mode):
            return name
    return "not a regular file"


def write_atomic(path: Path, text: str, had_bom: bool = False, expected: bytes | None = None) -> None:
    """Replace the user's source file `path` with `text` (see the module docstring).

    `expected`: the bytes read from `path` before the new text was computed; if the file no longer
    holds them, it is left as it is and `ChangedOnDisk` is raised."""
    data = (("\ufeff" if had_bom else "") + text).encode("utf-8")
    _write(Path(path), data, expected=expected, create=False, check=None)


def write_output(path: Path | str, content: str | bytes, check: Callable[[str], None] | None = None) -> None:
    """Write a generated file the user named (created if missing, replaced if a regular file).

    `check(tmp_path)` may look at the complete temporary file before it takes the file's place
    (the MJCF export loads it back); whatever it raises leaves the old file as it was."""
    data = content.encode("utf-8") if isinstance(content, str) else content
    _write(Path(path), data, expected=None, create=True, check=check)


def _write(path: Path, data: bytes, *, expected: bytes | None, create: bool,
           check: Callable[[str], None] | None) -> None:
    try:
        st = os.stat(path)  # follows symlinks: the kind of file that would receive the text
    except FileNotFoundError:
        if not create:
            raise WriteError(f"cannot write {path}: it no longer exists") from None
        st = None
    except OSError as exc:
        raise WriteError(f"cannot write {path}: {_why(exc)}") from None
    if st is not None and not stat.S_ISREG(st.st_mode):
        raise WriteError(f"cannot write {path}: it is {_kind(st.st_mode)}, not a regular file; "
                         "plx writes only regular files (name a file instead)")
    real = Path(os.path.realpath(path))  # through symlinks: the link stays a link
    if st is not None and (not st.st_mode & 0o222 or not os.access(real, os.W_OK)):
        raise WriteError(f"{path} is read-only; not changing it (make it writable first)")
    if st is None and not real.parent.is_dir():
        raise WriteError(f"cannot write {path}: the folder {real.parent} does not exist")
    tmp = _complete_copy(path, real, data, st)
    try:
        if check is not None:
            check(tmp)
        old = _still_expected(path, real, expected) if st is not None else None
        if st is None or (st.st_nlink == 1 and _same_owner(tmp, st)):
            try:
                os.replace(tmp, real)
            except OSError as exc:
                raise WriteError(f"cannot write {path}: {_why(exc)}") from None
            _sync_folder(real.parent)
            return
        if old is None:
            old = _read(path, real)
        _rewrite_inode(path, real, data, old, tmp)  # removes tmp itself once it is not needed
    except WriteError as exc:
        if not exc.keeps_copy:
            _remove(tmp)
        raise
    except BaseException:
        _remove(tmp)
        raise


def _complete_copy(path: Path, real: Path, data: bytes, st: os.stat_result | None) -> str:
    """The new contents, complete and on disk, in a temporary file next to `real`."""
    import tempfile

    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{real.name}.", suffix=".plxtmp", dir=real.parent)
    except OSError as exc:
        raise WriteError(f"cannot write {path}: cannot create a temporary file in {real.parent}: "
                         f"{_why(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~_umask())
    except OSError as exc:
        _remove(tmp)
        raise WriteError(f"cannot write {path}: {_why(exc)}; it was left as it was") from None
    except BaseException:
        _remove(tmp)
        raise
    return tmp


def _read(path: Path, real: Path) -> bytes:
    try:
        with open(real, "rb") as fh:
            return fh.read()
    except OSError as exc:
        raise WriteError(f"cannot write {path}: cannot read it back: {_why(exc)}") from None


def _still_expected(path: Path, real: Path, expected: bytes | None) -> bytes | None:
    """What is on disk now (None when the caller did not say what it read); raises ChangedOnDisk
    when it is not what the caller read. Content, not a time stamp: a save within the same
    clock tick, or one that restores the old size, is still seen."""
    if expected is None:
        return None
    now = _read(path, real)
    if now != expected:
        raise ChangedOnDisk(f"{path} changed on disk after it was read (saved by another program?); "
                            "left as it is: run the command again")
    return now


def _rewrite_inode(path: Path, real: Path, data: bytes, old: bytes, tmp: str) -> None:
    """Copy `data` into the file's own inode (hard links keep sharing it). On failure the old
    contents are put back; if that fails too, `tmp` (the complete new text) is kept and named."""
    try:
        fd = os.open(real, os.O_RDWR)
    except OSError as exc:
        raise WriteError(f"cannot write {path}: {_why(exc)}") from None
    try:
        if len(data) > len(old):
            _reserve(fd, path, len(data), len(old))
        try:
            _pwrite_all(fd, data)
            os.ftruncate(fd, len(data))
            os.fsync(fd)
        except OSError as exc:
            why = _why(exc)
            try:
                _pwrite_all(fd, old)
                os.ftruncate(fd, len(old))
                os.fsync(fd)
            except OSError:
                raise WriteError(f"cannot write {path}: {why}; it could not be restored either, so it may "
                                 f"be incomplete: its complete new text is in {tmp}", keeps_copy=True) from None
            raise WriteError(f"cannot write {path}: {why}; it was left as it was") from None
    finally:
        os.close(fd)
    _remove(tmp)


def _reserve(fd: int, path: Path, size: int, old_size: int) -> None:
    """Make sure the file can grow to `size` before its first byte is overwritten."""
    try:
        os.posix_fallocate(fd, 0, size)
    except OSError as exc:
        if exc.errno in (errno.EOPNOTSUPP, errno.EINVAL, errno.ENOSYS):
            return  # the file system cannot reserve: the write below is restored on failure
        try:
            os.ftruncate(fd, old_size)  # a partial reservation may have grown it
        except OSError:
            pass
        raise WriteError(f"cannot write {path}: {_why(exc)}; it was left as it was") from None


def _pwrite_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    done = 0
    while done < len(data):
        n = os.pwrite(fd, view[done:], done)
        if n <= 0:
            raise OSError(errno.EIO, "short write")
        done += n


def _remove(tmp: str) -> None:
    try:
        os.unlink(tmp)
    except OSError:
        pass


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _same_owner(tmp: str, st: os.stat_result) -> bool:
    """Give the temporary file the original's owner; False if that is not allowed."""
    mine = os.stat(tmp)
    if (mine.st_uid, mine.st_gid) == (st.st_uid, st.st_gid):
        return True
    try:
        os.chown(tmp, st.st_uid, st.st_gid)
    except OSError:
        return False
    return True


def _sync_folder(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def unified_diff(path: str, old: str, new: str) -> str:
    import difflib

    return "".join(
        difflib.unified_diff(old.splitlines(True), new.splitlines(True), f"a/{path}", f"b/{path}")
    )
