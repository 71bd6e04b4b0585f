"""Print what plx says about every example, case file and official bundle file, for refactors.

Issue 28's promise is that restructuring changes no output: run this before and after and compare
(`python dev/outputs_snapshot.py > before.txt`, change, run again, `diff before.txt after.txt`).
Lint and fmt run over every file; check (without simulation) over every example and check case.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def plx(*args: str) -> str:
    env = dict(os.environ, NO_COLOR="1", COLUMNS="200")
    r = subprocess.run([sys.executable, "-m", "plxtools", *args], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    return f"$ plx {' '.join(args)[:120]}\n{r.stdout}{r.stderr}# exit {r.returncode}\n"


def bundle_root() -> Path:
    import openplxbundles

    return Path(openplxbundles.__file__).parent


def main() -> None:
    files = sorted(str(p.relative_to(ROOT)) for top in ("examples", "tests/cases")
                   for p in (ROOT / top).rglob("*.openplx"))
    for f in files:
        print(plx("lint", "--no-cache", f), end="")
        print(plx("fmt", "--diff", f), end="")
    checks = [f for f in files if f.startswith(("examples/boxtruck", "examples/tutorial", "tests/cases/check"))]
    for f in checks:
        print(plx("check", f), end="")
    root = bundle_root()
    if root.is_dir():
        print(plx("lint", "--no-cache", str(root)).replace(str(root), "<bundles>"), end="")


if __name__ == "__main__":
    main()
