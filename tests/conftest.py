import glob
import os
import subprocess
import sys
import tempfile
from contextlib import contextmanager
from pathlib import Path

import pytest
from hypothesis import settings
from hypothesis.configuration import set_hypothesis_home_dir
from hypothesis.database import DirectoryBasedExampleDatabase

REPO = Path(__file__).resolve().parent.parent
CASES = REPO / "tests" / "cases"

# Hermetic: the run leaves nothing in the working tree or the user's cache (CI checks `git status`).
# One folder per user outside the tree holds plx's bundle cache (unless PLX_CACHE_DIR is set, as CI
# does) and hypothesis' example database; pytest's own cache is off (pyproject's addopts).
_TMP = Path(tempfile.gettempdir()) / f"plxtools-tests-{os.getuid() if hasattr(os, 'getuid') else 'user'}"
os.environ.setdefault("PLX_CACHE_DIR", str(_TMP / "cache"))
os.environ.setdefault("PLX_CACHE_SECRET_FILE", str(_TMP / "cache-secret"))  # the key of cache entries
set_hypothesis_home_dir(str(_TMP / "hypothesis-home"))
settings.register_profile("plxtools", database=DirectoryBasedExampleDatabase(str(_TMP / "hypothesis")))
settings.load_profile("plxtools")


# Random and property campaigns run a third of their examples (at least 2) in the default run,
# which has to stay quick; `.ci/run` runs them in full in a stage of their own (PLX_LONG_CAMPAIGNS=1).
LONG_CAMPAIGNS = os.environ.get("PLX_LONG_CAMPAIGNS") == "1"


def campaign_size(full: int) -> int:
    """How many random examples (or seeds) a campaign of `full` runs now."""
    return full if LONG_CAMPAIGNS else max(2, full // 3)


def bundle_root() -> Path:
    import openplxbundles

    return Path(openplxbundles.package_dir())


def bundle_files() -> list[Path]:
    return sorted(Path(p) for p in glob.glob(str(bundle_root() / "**" / "*.openplx"), recursive=True))


def run_plx(*args: str, stdin: str | None = None, cwd: Path | None = None, env: dict | None = None):
    """Run the real `plx` command line in a subprocess."""
    e = dict(os.environ)
    e.pop("FORCE_COLOR", None)
    e["NO_COLOR"] = "1"
    if env:
        e.update(env)
    return subprocess.run(
        [sys.executable, "-m", "plxtools", *args],
        input=stdin,
        capture_output=True,
        text=True,
        cwd=cwd or REPO,
        env=e,
        timeout=300,
    )


@pytest.fixture(scope="session")
def bundles() -> list[Path]:
    files = bundle_files()
    assert len(files) == 465, "expected the 465 files of openplx-bundles 0.19.0"
    return files



# What a first run leaves in a cache folder that any later run of any command re-uses: the bundle
# program (a cold build is about 1.5 CPU-seconds per run), the record of its bundle set, the code
# stamp and the grammar. Not the per-command kinds (results, formatted, replays) that tests count.
_SHARED_KINDS = ("programs", "bundle-sets", "stamps", "grammars")


@pytest.fixture(scope="session")
def warm_cache_seed(tmp_path_factory) -> Path:
    """A cache folder filled by one real cold `plx lint` (its forked writer waited for), from which
    `warm_cache` copies: tests of caches and replays start from a warm bundle program, as a user's
    second run does, instead of building it again in every test (the fresh answer they compare
    with is computed without any cache)."""
    import time

    top = tmp_path_factory.mktemp("warm-cache")
    f = top / "w.openplx"
    f.write_text("Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10\n")
    r = run_plx("lint", str(f), env={"PLX_CACHE_DIR": str(top / "cache")})
    assert r.returncode == 0, r.stdout + r.stderr
    folder = top / "cache" / "plxtools"
    for _ in range(600):  # the forked writer is done when its temporary file has been renamed
        if list(folder.glob("programs/*")) and not list(folder.glob("programs/.*.tmp")):
            break
        time.sleep(0.1)
    assert list(folder.glob("programs/*")), "the cold run left no bundle program behind"
    return top / "cache"


@pytest.fixture
def warm_cache(warm_cache_seed, tmp_path) -> Path:
    """A new cache folder of this test's own (tmp_path/cache) holding only the shared kinds of
    `warm_cache_seed`: empty of results, formatted files and replays."""
    import shutil

    dest = tmp_path / "cache"
    for kind in _SHARED_KINDS:
        src = warm_cache_seed / "plxtools" / kind
        if src.is_dir():
            shutil.copytree(src, dest / "plxtools" / kind, ignore=shutil.ignore_patterns(".*.tmp"))
    return dest


@contextmanager
def environment(values: dict):
    """os.environ with `values` set (None: unset), restored afterwards."""
    old = {k: os.environ.get(k) for k in values}
    try:
        for k, v in values.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
        yield
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def plx_here(*args: str, stdin: str | None = None, cwd: Path | None = None, env: dict | None = None):
    """`run_plx` in this process, for a test that needs the command's output and exit code but not a
    process of its own (no interpreter start, no imports again: a fifth of the CPU time of a run).
    Same arguments and result (a CompletedProcess); a test about the process itself (the console
    entry point, signals, what a run imports, runmemo's replay) uses run_plx."""
    import contextlib
    import io

    from plxtools.cli import main
    from plxtools.config import _config_for_dir

    _config_for_dir.cache_clear()  # a run reads the config files as they are now, as a new process does
    out, err = io.StringIO(), io.StringIO()
    old_cwd, old_stdin = os.getcwd(), sys.stdin
    try:
        with environment({"NO_COLOR": "1", "FORCE_COLOR": None, **(env or {})}):
            os.chdir(cwd or REPO)
            sys.stdin = io.TextIOWrapper(io.BytesIO((stdin or "").encode("utf-8")), encoding="utf-8")
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                try:
                    code = main(list(args))
                except SystemExit as exc:  # argparse's usage errors
                    code = exc.code if isinstance(exc.code, int) else 2
    finally:
        sys.stdin = old_stdin
        os.chdir(old_cwd)
    return subprocess.CompletedProcess(["plx", *args], code, out.getvalue(), err.getvalue())
