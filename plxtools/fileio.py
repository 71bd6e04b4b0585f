"""Writing the user's files (`plx fmt`, `plx lint --fix`): the file stays theirs.

The new contents go through symlinks to the real file and keep its mode, owner and hard links.
They are first written to a temporary file next to the real one and flushed to disk, so a crash
or a full disk never leaves a half-written file:

- a regular file with one link whose owner can be kept is replaced by renaming the temporary
  file over it (atomic);
- otherwise (hard links, or an owner we cannot give to a new file) the contents are copied into
  the original inode and the temporary file, a complete copy, is removed only afterwards.

Read-only files are refused. Every failure is an `OSError` whose `strerror` says what happened
in words meant for the user; callers report it and exit 2.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path


class WriteError(OSError):
    """A file could not be written; `strerror` is the whole message."""

    def __init__(self, message: str):
        super().__init__(message)
        self.strerror = message


def _why(exc: OSError) -> str:
    return exc.strerror or str(exc)


def write_atomic(path: Path, text: str, had_bom: bool = False) -> None:
    data = (("\ufeff" if had_bom else "") + text).encode("utf-8")
    real = Path(os.path.realpath(path))  # through symlinks: the link stays a link
    try:
        st = os.stat(real)
    except OSError as exc:
        raise WriteError(f"cannot write {path}: {_why(exc)}") from None
    if not stat.S_ISREG(st.st_mode):
        raise WriteError(f"cannot write {path}: not a regular file")
    if not st.st_mode & 0o222 or not os.access(real, os.W_OK):
        raise WriteError(f"{path} is read-only; not changing it (make it writable to format it)")
    try:
        import tempfile

        fd, tmp = tempfile.mkstemp(prefix=f".{real.name}.", suffix=".plxtmp", dir=real.parent)
    except OSError as exc:
        raise WriteError(f"cannot write {path}: cannot create a temporary file in {real.parent}: "
                         f"{_why(exc)}") from None
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, stat.S_IMODE(st.st_mode))
        if st.st_nlink == 1 and _same_owner(tmp, st):
            os.replace(tmp, real)
            _sync_folder(real.parent)
            return
        # hard links or another owner: rewrite the original inode; `tmp` holds the full new text
        with open(real, "r+b") as fh:
            fh.write(data)
            fh.truncate()
            fh.flush()
            os.fsync(fh.fileno())
        os.unlink(tmp)
    except OSError as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise WriteError(f"cannot write {path}: {_why(exc)}") from None
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


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
