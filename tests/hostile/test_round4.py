"""Round 4 of the hostile-input campaign (issue 41): each reproduction R1-R7 of
`shared/repros/round4` as a test of the real command line, its fixtures made here at run time.

- a FIFO or a device (or a symlink to one) named on the command line: exit 2 and a line naming it,
  never "All checks passed in 0 files";
- the same inside a walked folder: named in a warning and skipped, never opened (no hang, no read
  without end), the other files checked;
- a folder or a FIFO at the cache secret path: one warning, the normal answer, uncached;
- control characters of an `@"..."` path: escaped in text and GitHub output, valid JSON escapes;
- a nonexistent HOME: never created;
- a file above `max-file-size`: refused unread, at once.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import run_plx

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")

GOOD = "Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2\n"
HANG = 60  # seconds: far above any of these runs; reaching it means plx blocked


def plx(tmp: Path, *args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    e = dict(os.environ, NO_COLOR="1")
    e.pop("FORCE_COLOR", None)
    e.update(env or {})
    return subprocess.run([sys.executable, "-m", "plxtools", *args], capture_output=True, text=True, cwd=tmp,
                          env=e, timeout=HANG)


def _specials(folder: Path) -> dict[str, str]:
    """A FIFO, a link to /dev/zero and a link to the FIFO, each named *.openplx: name -> what plx says it is."""
    os.mkfifo(folder / "pipe.openplx")
    (folder / "zero.openplx").symlink_to("/dev/zero")
    (folder / "via-link.openplx").symlink_to(folder / "pipe.openplx")
    return {"pipe.openplx": "a FIFO (named pipe)", "zero.openplx": "a character device",
            "via-link.openplx": "a FIFO (named pipe)"}


# ---------------------------------------------------------------- R3: named on the command line


@pytest.mark.parametrize("command", [["lint"], ["fmt", "--check"], ["check"]])
def test_a_named_fifo_or_device_is_an_error_naming_it(tmp_path, command):
    kinds = _specials(tmp_path)
    (tmp_path / "ok.openplx").write_text(GOOD)
    for name, what in kinds.items():
        r = plx(tmp_path, *command, "ok.openplx", name)
        assert r.returncode == 2, (name, r.stdout, r.stderr)
        assert f"{name}: it is {what}, not a regular file: not read" in r.stderr
        assert "passed" not in r.stdout and "No .openplx files" not in r.stderr + r.stdout


# ---------------------------------------------------------------- R4: inside a walked folder


@pytest.mark.parametrize("command", [["lint"], ["fmt", "--check"], ["check", "--timeout", "5"]])
def test_fifos_and_devices_in_a_walked_folder_are_skipped_unread(tmp_path, command):
    walk = tmp_path / "walk"
    walk.mkdir()
    (walk / "ok.openplx").write_text(GOOD)
    kinds = _specials(walk)
    r = plx(tmp_path, *command, "walk")  # a hang or a read of /dev/zero ends in the timeout / MemoryError
    assert r.returncode == 0, (r.stdout, r.stderr)
    for name, what in kinds.items():
        assert f"walk/{name}: it is {what}, not a regular file: not read; skipped" in r.stderr
    if command[0] != "fmt":
        assert "1 file" in r.stdout  # ok.openplx was checked, and only it
    assert "internal error" not in r.stderr + r.stdout


def test_a_fifo_in_a_user_bundle_is_not_read(tmp_path):
    """A bundle folder (bundle-path) is walked too: a FIFO there must not block the load."""
    b = tmp_path / "MyBundle"
    b.mkdir()
    (b / "config.openplx").write_text('config:\n    .name: "MyBundle"\n    .version: "1.0.0"\n')
    (b / "Parts.openplx").write_text("Part is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n")
    os.mkfifo(b / "Stuck.openplx")
    (tmp_path / "m.openplx").write_text(GOOD)
    r = plx(tmp_path, "lint", "--bundle-path", str(b), "m.openplx")
    assert r.returncode in (0, 1), (r.stdout, r.stderr)
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr


# ---------------------------------------------------------------- R1, R2: the cache secret path


@pytest.mark.parametrize("kind", ["folder", "fifo"])
@pytest.mark.parametrize("command", [["lint"], ["check"]])
def test_a_folder_or_fifo_at_the_cache_secret_path_runs_uncached(tmp_path, kind, command):
    (tmp_path / "a.openplx").write_text(GOOD)
    secret = tmp_path / "secret"
    secret.mkdir() if kind == "folder" else os.mkfifo(secret)
    r = plx(tmp_path, *command, "a.openplx",
            env={"PLX_CACHE_SECRET_FILE": str(secret), "PLX_CACHE_DIR": str(tmp_path / "cache")})
    assert r.returncode == 0, (r.stdout, r.stderr)
    assert "All checks passed in 1 file" in r.stdout
    assert f"cannot read the cache secret {secret}: it is not a regular file; running without the cache" in r.stderr
    assert r.stderr.count("cache secret") == 1  # one warning, not one per entry
    assert "Traceback" not in r.stderr and "internal error" not in r.stderr
    assert secret.is_dir() if kind == "folder" else secret.is_fifo()  # left as it was


# ---------------------------------------------------------------- R5: control characters


HOSTILE_PATH = "\x1b]0;PWNED\x07\x1b[1A\x1b[2K\u202e.obj"


def _hostile_model(folder: Path) -> Path:
    f = folder / "s6.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
                 "        visual is Visuals.Geometries.ExternalTriMeshGeometry:\n"
                 f'            path: @"{HOSTILE_PATH}"\n', encoding="utf-8")
    return f


def _no_controls(text: str) -> None:
    bad = [c for c in text if (ord(c) < 32 and c not in "\n\t") or 0x7f <= ord(c) <= 0x9f or c == "\u202e"]
    assert not bad, f"raw control characters reach the output: {bad!r}"


@pytest.mark.parametrize("fmt", ["text", "github"])
def test_control_characters_of_a_path_are_escaped(tmp_path, fmt):
    _hostile_model(tmp_path)
    r = plx(tmp_path, "check", "s6.openplx", "--output-format", fmt)
    assert r.returncode == 1, (r.stdout, r.stderr)
    _no_controls(r.stdout)
    _no_controls(r.stderr)
    assert "A031" in r.stdout
    assert r"\x1b]0;PWNED\x07\x1b[1A\x1b[2K\u202e.obj" in r.stdout  # said, escaped, where it was raw
    if fmt == "github":
        assert all(line.startswith("::") for line in r.stdout.splitlines())  # no line forged by the path


@pytest.mark.parametrize("fmt", ["json", "sarif"])
def test_control_characters_stay_valid_json_escapes(tmp_path, fmt):
    _hostile_model(tmp_path)
    r = plx(tmp_path, "check", "s6.openplx", "--output-format", fmt)
    assert r.returncode == 1, r.stderr
    _no_controls(r.stdout)
    assert "\\u001b" in r.stdout  # JSON's own escape
    strings: list[str] = []
    json.loads(r.stdout, object_hook=lambda d: strings.extend(v for v in d.values() if isinstance(v, str)) or d)
    assert any(HOSTILE_PATH in s for s in strings)  # the value itself, intact once decoded


def test_a_walked_file_name_with_control_characters_is_escaped(tmp_path):
    walk = tmp_path / "w"
    walk.mkdir()
    os.mkfifo(walk / "\x1b[2Kx.openplx")
    (walk / "ok.openplx").write_text(GOOD)
    r = plx(tmp_path, "lint", "w")
    _no_controls(r.stderr)
    assert r"w/\x1b[2Kx.openplx: it is a FIFO" in r.stderr


# ---------------------------------------------------------------- R6: a nonexistent HOME


def test_a_nonexistent_home_is_not_created(tmp_path):
    (tmp_path / "a.openplx").write_text(GOOD)
    home = tmp_path / "nonexistent" / "home"
    r = plx(tmp_path, "lint", "a.openplx", env={"HOME": str(home), "XDG_CACHE_HOME": "", "XDG_CONFIG_HOME": "",
                                                 "PLX_CACHE_DIR": "", "PLX_CACHE_SECRET_FILE": ""})
    assert r.returncode == 0, (r.stdout, r.stderr)
    assert "All checks passed in 1 file" in r.stdout
    assert not (tmp_path / "nonexistent").exists()
    assert f"the home folder {home} does not exist; running without the cache" in r.stderr


def test_an_existing_home_gets_only_its_cache_folders(tmp_path):
    (tmp_path / "a.openplx").write_text(GOOD)
    home = tmp_path / "home"
    home.mkdir()
    r = plx(tmp_path, "lint", "a.openplx", env={"HOME": str(home), "XDG_CACHE_HOME": "", "XDG_CONFIG_HOME": "",
                                                 "PLX_CACHE_DIR": "", "PLX_CACHE_SECRET_FILE": ""})
    assert r.returncode == 0 and "warning" not in r.stderr, r.stderr
    assert (home / ".cache" / "plxtools").is_dir()
    assert (home / ".config" / "plxtools" / "cache-secret").is_file()


# ---------------------------------------------------------------- R7: size limit and memory


def _generated(path: Path, bodies: int) -> Path:
    with path.open("w") as fh:
        fh.write("Scene is Physics3D.System:\n")
        for i in range(bodies):
            fh.write(f"    b{i} is Physics3D.Bodies.RigidBody:\n        inertia.mass: {i + 1}\n")
    return path


@pytest.mark.parametrize("command", [["lint"], ["fmt", "--check"], ["check"]])
def test_a_file_above_max_file_size_is_refused_unread(tmp_path, command):
    (tmp_path / "plx.toml").write_text("max-file-size = 0.05\n")  # 50 KiB
    big = _generated(tmp_path / "big.openplx", 1000)
    assert big.stat().st_size > 0.05 * 2**20
    r = plx(tmp_path, *command, "big.openplx")
    assert r.returncode != 0 and "passed" not in r.stdout, (r.stdout, r.stderr)
    assert "above the limit of 0.05 MB: not read (raise it with max-file-size in plx.toml)" in r.stdout + r.stderr


def test_a_stdin_above_max_file_size_is_refused(tmp_path):
    (tmp_path / "plx.toml").write_text("max-file-size = 0.01\n")
    e = dict(os.environ, NO_COLOR="1")
    r = subprocess.run([sys.executable, "-m", "plxtools", "lint", "-"], input="# x\n" * 10000, capture_output=True,
                       text=True, cwd=tmp_path, env=e, timeout=HANG)
    assert r.returncode != 0 and "above the limit of 0.01 MB" in r.stdout + r.stderr, (r.stdout, r.stderr)


def _peak_kb(tmp: Path, *args: str) -> int:
    """The peak resident memory (ru_maxrss, KiB) of one `plx` run, from the kernel's accounting."""
    proc = subprocess.Popen([sys.executable, "-m", "plxtools", *args], cwd=tmp, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, env=dict(os.environ, NO_COLOR="1"))
    _pid, _status, usage = os.wait4(proc.pid, 0)
    proc.returncode = 0  # reaped here: Popen must not wait for it again
    return usage.ru_maxrss


@pytest.mark.parametrize("command,ratio", [(["lint", "--no-cache"], 150), (["fmt", "--check", "--no-cache"], 230)])
def test_memory_stays_in_proportion_to_the_file(tmp_path, command, ratio):
    """Peak memory above a tiny file's run, per byte of input: the bound this round reached (lint was
    about 150, fmt about 250 before); bench/memory_per_byte.py measures it at 1, 10 and 50 MB."""
    tiny = tmp_path / "tiny.openplx"
    tiny.write_text(GOOD)
    big = _generated(tmp_path / "big.openplx", 8000)  # about 0.5 MB
    base = _peak_kb(tmp_path, *command, "tiny.openplx")
    peak = _peak_kb(tmp_path, *command, "big.openplx")
    per_byte = (peak - base) * 1024 / big.stat().st_size
    assert per_byte < ratio, f"{per_byte:.0f} bytes of memory per byte of input"
