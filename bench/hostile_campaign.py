"""Hostile files and cache secrets: round 4's campaign (issue 41), repeatable, as a pass/fail table.

Every case builds its fixture in a scratch folder (FIFOs, links to /dev/zero, a folder or a FIFO at
the cache secret path, a nonexistent HOME, control characters in an `@"..."` path, a file above
`max-file-size`, standard input without end) and runs the real `plx` with a time limit. A case
passes when plx answers as docs/reliability.md says, quickly: never a hang, a traceback, an
"internal error", a raw control character, a created HOME, or a gate passed on a file never read.

Run:  python bench/hostile_campaign.py [--short] [--timeout 60]
(`--short`: the cases `.ci/run` repeats, about half a minute. Exit 1 if any case fails.)
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

GOOD = "Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2\n"
RAW = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


@dataclass
class Result:
    code: int | None  # None: stopped at the time limit
    out: str
    err: str
    seconds: float


@dataclass
class Case:
    name: str
    short: bool
    run: Callable[[Path, Callable[..., Result]], str | None]  # None: passed; else why not


def _plx(timeout: float):
    def run(cwd: Path, *args: str, env: dict | None = None, stdin=None) -> Result:
        e = dict(os.environ, NO_COLOR="1")
        e.pop("FORCE_COLOR", None)
        e.update(env or {})
        t0 = time.monotonic()
        try:
            r = subprocess.run([sys.executable, "-m", "plxtools", *args], cwd=cwd, env=e, capture_output=True,
                               text=True, timeout=timeout, stdin=stdin)
        except subprocess.TimeoutExpired as exc:
            return Result(None, str(exc.stdout or ""), str(exc.stderr or ""), time.monotonic() - t0)
        return Result(r.returncode, r.stdout, r.stderr, time.monotonic() - t0)
    return run


def _sane(r: Result) -> str | None:
    """What every answer must be: finished, no traceback, no internal error, no raw control character."""
    if r.code is None:
        return f"hung (stopped after {r.seconds:.0f} s)"
    both = r.out + r.err
    if "Traceback" in both or "internal error" in both:
        return "traceback / internal error: " + both.strip().splitlines()[-1][:120]
    if RAW.search(both):
        return "a raw control character reached the output"
    return None


def _named(kind: str, command: list[str]):
    def case(d: Path, plx) -> str | None:
        (d / "ok.openplx").write_text(GOOD)
        target = d / "x.openplx"
        if kind == "fifo":
            os.mkfifo(target)
        elif kind == "zero":
            target.symlink_to("/dev/zero")
        else:
            os.mkfifo(d / "p")
            target.symlink_to(d / "p")
        r = plx(d, *command, "ok.openplx", "x.openplx")
        bad = _sane(r)
        if bad:
            return bad
        if r.code != 2 or "x.openplx: it is" not in r.err or "not a regular file" not in r.err:
            return f"exit {r.code}: {(r.out + r.err).strip()[:120]}"
        return None
    return case


def _walked(command: list[str]):
    def case(d: Path, plx) -> str | None:
        w = d / "walk"
        w.mkdir()
        (w / "ok.openplx").write_text(GOOD)
        os.mkfifo(w / "p.openplx")
        (w / "z.openplx").symlink_to("/dev/zero")
        r = plx(d, *command, "walk")
        bad = _sane(r)
        if bad:
            return bad
        if r.code != 0 or r.err.count("not a regular file: not read; skipped") != 2:
            return f"exit {r.code}: {(r.out + r.err).strip()[:120]}"
        return None
    return case


def _secret(kind: str, command: list[str]):
    def case(d: Path, plx) -> str | None:
        (d / "a.openplx").write_text(GOOD)
        s = d / "secret"
        if kind == "folder":
            s.mkdir()
        elif kind == "fifo":
            os.mkfifo(s)
        else:
            s.symlink_to("/dev/zero")
        r = plx(d, *command, "a.openplx", env={"PLX_CACHE_SECRET_FILE": str(s), "PLX_CACHE_DIR": str(d / "c")})
        bad = _sane(r)
        if bad:
            return bad
        if r.code != 0 or "cache secret" not in r.err or "running without the cache" not in r.err:
            return f"exit {r.code}: {(r.out + r.err).strip()[:120]}"
        return None
    return case


def _cache_folder_is_a_fifo(d: Path, plx) -> str | None:
    (d / "a.openplx").write_text(GOOD)
    (d / "c").mkdir()
    os.mkfifo(d / "c" / "plxtools")
    r = plx(d, "lint", "a.openplx", env={"PLX_CACHE_DIR": str(d / "c")})
    bad = _sane(r)
    return bad or (None if r.code == 0 and "running without the cache" in r.err else f"exit {r.code}: {r.err[:120]}")


def _control_characters(fmt: str):
    def case(d: Path, plx) -> str | None:
        (d / "s.openplx").write_text(
            "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
            "        visual is Visuals.Geometries.ExternalTriMeshGeometry:\n"
            '            path: @"\x1b]0;PWNED\x07\x1b[1A\x1b[2K\u202e.obj"\n', encoding="utf-8")
        r = plx(d, "check", "s.openplx", "--output-format", fmt)
        bad = _sane(r)
        if bad:
            return bad
        if r.code != 1 or "A031" not in r.out:
            return f"exit {r.code}: {(r.out + r.err).strip()[:120]}"
        if fmt in ("json", "sarif"):
            import json

            json.loads(r.out)
        return None
    return case


def _fifo_mesh(d: Path, plx) -> str | None:
    os.mkfifo(d / "m.obj")
    (d / "s.openplx").write_text(
        "Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n"
        "        visual is Visuals.Geometries.ExternalTriMeshGeometry:\n            path: @\"m.obj\"\n")
    r = plx(d, "check", "--timeout", "5", "s.openplx")
    return _sane(r) or (None if r.code in (0, 1) else f"exit {r.code}: {(r.out + r.err).strip()[:120]}")


def _no_home(d: Path, plx) -> str | None:
    (d / "a.openplx").write_text(GOOD)
    r = plx(d, "lint", "a.openplx", env={"HOME": str(d / "nonexistent" / "home"), "XDG_CACHE_HOME": "",
                                         "XDG_CONFIG_HOME": "", "PLX_CACHE_DIR": "", "PLX_CACHE_SECRET_FILE": ""})
    bad = _sane(r)
    if bad:
        return bad
    if (d / "nonexistent").exists():
        return "the nonexistent HOME was created"
    return None if r.code == 0 else f"exit {r.code}: {r.err[:120]}"


def _too_big(command: list[str]):
    def case(d: Path, plx) -> str | None:
        (d / "plx.toml").write_text("max-file-size = 0.05\n")
        (d / "big.openplx").write_text("Scene is Physics3D.System:\n" + "".join(
            f"    b{i} is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1\n" for i in range(1000)))
        r = plx(d, *command, "big.openplx")
        bad = _sane(r)
        if bad:
            return bad
        if r.code == 0 or "above the limit" not in r.out + r.err:
            return f"exit {r.code}: {(r.out + r.err).strip()[:120]}"
        return None
    return case


def _endless_stdin(command: list[str]):
    def case(d: Path, plx) -> str | None:
        (d / "plx.toml").write_text("max-file-size = 1\n")
        with open("/dev/zero", "rb") as zero:
            r = plx(d, *command, "-", stdin=zero)
        bad = _sane(r)
        if bad:
            return bad
        return None if r.code != 0 and "above the limit" in r.out + r.err else f"exit {r.code}: {r.err[:120]}"
    return case


CASES = [
    *(Case(f"named {k} on `{' '.join(c)}`", c == ["lint"] or k == "zero", _named(k, c))
      for k in ("fifo", "zero", "link to a fifo") for c in (["lint"], ["fmt", "--check"], ["check"])),
    *(Case(f"fifo and /dev/zero link in a folder, `{' '.join(c)}`", c[0] == "check", _walked(c))
      for c in (["lint"], ["fmt", "--check"], ["check", "--timeout", "5"])),
    *(Case(f"cache secret is a {k}, `{c[0]}`", c == ["lint"], _secret(k, c))
      for k in ("folder", "fifo", "link to /dev/zero") for c in (["lint"], ["check"])),
    Case("cache folder is a fifo", False, _cache_folder_is_a_fifo),
    *(Case(f"control characters in a path, {f} output", f in ("text", "github"), _control_characters(f))
      for f in ("text", "github", "json", "sarif")),
    Case("a mesh path names a fifo", False, _fifo_mesh),
    Case("nonexistent HOME", True, _no_home),
    *(Case(f"file above max-file-size, `{' '.join(c)}`", c == ["lint"], _too_big(c))
      for c in (["lint"], ["fmt", "--check"], ["check"])),
    *(Case(f"endless standard input, `{' '.join(c)}`", False, _endless_stdin(c)) for c in (["lint"], ["fmt"])),
]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--short", action="store_true", help="only the cases .ci/run repeats")
    ap.add_argument("--timeout", type=float, default=60, help="seconds after which a run counts as hung")
    args = ap.parse_args()
    plx = _plx(args.timeout)
    failed = 0
    cases = [c for c in CASES if c.short or not args.short]
    print(f"{'case':58} {'result':6} {'s':>5}  detail")
    t_all = time.monotonic()
    for case in cases:
        with tempfile.TemporaryDirectory(prefix="plx-hostile-") as tmp:
            t0 = time.monotonic()
            try:
                why = case.run(Path(tmp), plx)
            except Exception as exc:  # the campaign's own failure counts as a failure too
                why = f"campaign error: {type(exc).__name__}: {exc}"
            failed += why is not None
            print(f"{case.name:58} {'pass' if why is None else 'FAIL':6} {time.monotonic() - t0:5.1f}  {why or ''}",
                  flush=True)
    print(f"{len(cases) - failed} of {len(cases)} cases passed in {time.monotonic() - t_all:.0f} s")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
