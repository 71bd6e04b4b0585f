"""API index: size on disk, time to load one version, to diff every consecutive pair, and `plx migrate --explain`.

Run: python bench/apiindex_bench.py
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time


def main() -> int:
    from plxtools.model import apiindex
    from plxtools.model import apichanges

    files = [apiindex.DATA / f"{v}.json.gz" for v in apiindex.versions()]
    size = sum(p.stat().st_size for p in files)
    print(f"index: {len(files)} versions, {size / 1e6:.2f} MB on disk ({size / len(files) / 1e3:.1f} kB per version)")
    times = []
    for v in apiindex.versions():
        apiindex.load.cache_clear()
        t = time.perf_counter()
        idx = apiindex.load(v)
        times.append(time.perf_counter() - t)
    print(f"load one version: median {statistics.median(times) * 1e3:.1f} ms, max {max(times) * 1e3:.1f} ms "
          f"({len(idx.models)} models in {idx.version})")
    apiindex.load.cache_clear()
    t = time.perf_counter()
    apiindex.where_defined("Physics3D.Charges.Box")
    print(f"where_defined, all versions cold: {(time.perf_counter() - t) * 1e3:.0f} ms")
    t = time.perf_counter()
    apiindex.where_defined("Physics3D.Geometries.Box")
    print(f"where_defined, warm: {(time.perf_counter() - t) * 1e3:.1f} ms")
    vs = apiindex.versions()
    t = time.perf_counter()
    n = sum(len(apichanges.step(a, b)) for a, b in zip(vs, vs[1:]))
    print(f"diff all {len(vs) - 1} consecutive pairs: {(time.perf_counter() - t) * 1e3:.0f} ms ({n} changes)")
    runs = []
    for _ in range(3):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "plxtools", "migrate", "--explain", "0.17.26", "0.19.0"],
                       check=True, capture_output=True)
        runs.append(time.perf_counter() - t)
    print(f"plx migrate --explain 0.17.26 0.19.0: best of 3 {min(runs) * 1e3:.0f} ms wall")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
