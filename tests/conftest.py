import glob
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
CASES = REPO / "tests" / "cases"


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
