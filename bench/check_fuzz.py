"""Fuzzing campaign: `plx check --simulate --export-mjcf --output-format json` on generated bad scenes.

    python bench/check_fuzz.py [--count 200] [--seed 1] [--keep DIR]

Each scene is the hinged-link control scene of tests/check/test_check_reliability.py with one to
three values (mass, size, connector position, initial velocity, motor gain and speed, anchor
position) replaced by non-finite or absurd ones. The properties checked for every scene (the
bounded test in the suite runs the same check on 4 seeds):

* the exit code is 0, 1 or 2, with no internal error or traceback;
* stdout is one valid JSON document (no NaN / Infinity);
* exit 0 only without error diagnostics;
* an exported MJCF exists only when the run did not exit 2, and MuJoCo loads it.

Prints the number of scenes, the exit codes, the codes reported and every failure (with the scene
kept under --keep, or a temporary folder). Exits with 1 when any scene broke a property.
"""

from __future__ import annotations

import argparse
import collections
import json
import random
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "tests" / "check"))

from tests.check.test_check_reliability import check_one, mutate, run_plx  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", type=Path, default=None, help="folder for the generated scenes")
    args = ap.parse_args()
    folder = args.keep or Path(tempfile.mkdtemp(prefix="plx-check-fuzz-"))
    folder.mkdir(parents=True, exist_ok=True)
    rng = random.Random(args.seed)
    exits: collections.Counter[int] = collections.Counter()
    codes: collections.Counter[str] = collections.Counter()
    failures: list[tuple[Path, str]] = []
    t0 = time.perf_counter()
    for i in range(args.count):
        scene = folder / f"scene-{i:04d}.openplx"
        scene.write_text(mutate(rng), encoding="utf-8")
        try:
            check_one(scene, folder / f"scene-{i:04d}.xml")
        except (AssertionError, ValueError, json.JSONDecodeError) as exc:
            failures.append((scene, f"{type(exc).__name__}: {str(exc)[:300]}"))
        r = run_plx("check", "--output-format", "json", str(scene))
        exits[r.returncode] += 1
        try:
            codes.update(d["code"] for d in json.loads(r.stdout)["diagnostics"])
        except json.JSONDecodeError:
            pass
    wall = time.perf_counter() - t0
    print(f"{args.count} scenes (seed {args.seed}) in {wall:.1f} s; scenes under {folder}")
    print("exit codes of plain `plx check`:", dict(sorted(exits.items())))
    print("codes reported:", ", ".join(f"{c} x{n}" for c, n in sorted(codes.items())))
    print(f"failures: {len(failures)}")
    for path, why in failures:
        print(f"  {path}: {why}")
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
