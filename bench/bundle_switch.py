"""Time to switch a one-file `plx lint` between openplx-bundles versions, cold and warm.

cold: a fresh cache, so the first run of each version downloads the wheel (pip), unpacks it and
parses its bundle files; warm: the same versions again, served by the per-set symbol cache.
Wall-clock per run of the real CLI. Needs network for the cold runs.

    python bench/bundle_switch.py [VERSION ...]     (default: 0.16.10 0.17.26 0.18.11)
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(version: str, model: Path, cache: Path) -> float:
    env = dict(os.environ, PLX_CACHE_DIR=str(cache), NO_COLOR="1")
    t = time.perf_counter()
    r = subprocess.run([sys.executable, "-m", "plxtools", "lint", "-q", "--openplx-version", version, str(model)],
                       capture_output=True, text=True, env=env)
    dt = time.perf_counter() - t
    if r.returncode not in (0, 1):
        sys.exit(f"plx lint --openplx-version {version} failed: {r.stderr.strip()}")
    return dt


def main() -> None:
    versions = sys.argv[1:] or ["0.16.10", "0.17.26", "0.18.11"]
    with tempfile.TemporaryDirectory() as tmp:
        model = Path(tmp) / "scene.openplx"
        model.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n", encoding="utf-8")
        cache = Path(tmp) / "cache"
        cold = {v: run(v, model, cache) for v in versions}
        warm = {v: min(run(v, model, cache) for _ in range(3)) for v in versions}
    print(f"{'version':10} {'cold s':>8} {'warm s':>8}")
    for v in versions:
        print(f"{v:10} {cold[v]:8.2f} {warm[v]:8.2f}")


if __name__ == "__main__":
    main()
