"""Memory per byte of input: `plx lint`, `plx fmt --check` and `plx check` on generated models.

Each model is a System of N rigid bodies with a mass each (the shape of round 4's reproduction R7),
grown to about 1, 10 and 50 MB. Every command runs in a fresh process; the figure is its peak
resident memory (the kernel's ru_maxrss of that child, read with os.wait4: the whole process, not
tracemalloc's Python objects) minus the peak of the same command on a one-body file (the peer: what
start-up and the bundles take), divided by the file's size in bytes. The target of issue 41 is 40.

The runs lift `max-file-size` (a plx.toml in the scratch folder) so the limit is not what is
measured. A run is stopped at `--timeout` seconds or when it asks for more than `--max-gb` of address
space (RLIMIT_AS), so a 50 MB `check` does not take a shared machine down: such rows say so.

Run:  python bench/memory_per_byte.py [--sizes 1 10 50] [--commands lint fmt check] [--timeout 900] [--max-gb 12]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine  # noqa: E402

COMMANDS = {"lint": ["lint", "--no-cache"], "fmt": ["fmt", "--check", "--no-cache"], "check": ["check"]}
BODY = "    b{i} is Physics3D.Bodies.RigidBody:\n        inertia.mass: {m}\n"


def generate(path: Path, megabytes: float) -> int:
    """A model of about `megabytes` MB; its size in bytes."""
    target = int(megabytes * 2**20)
    with path.open("w") as fh:
        n = fh.write("Scene is Physics3D.System:\n")
        i = 0
        while n < target:
            n += fh.write(BODY.format(i=i, m=i + 1))
            i += 1
    return path.stat().st_size


def peak(args: list[str], cwd: Path, timeout: float, max_gb: float) -> tuple[int | None, float, str]:
    """(peak RSS in bytes or None, CPU seconds, status) of one `plx` run."""
    limit = int(max_gb * 2**30)

    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    t0 = time.monotonic()
    proc = subprocess.Popen([sys.executable, "-m", "plxtools", *args], cwd=cwd, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, preexec_fn=cap, env=dict(os.environ, NO_COLOR="1"))
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        if time.monotonic() - t0 > timeout:
            proc.kill()
            pid, status, usage = os.wait4(proc.pid, 0)
            proc.returncode = -9
            return None, usage.ru_utime + usage.ru_stime, f"stopped after {timeout:g} s"
        time.sleep(0.2)
    proc.returncode = os.waitstatus_to_exitcode(status)
    cpu = usage.ru_utime + usage.ru_stime
    if proc.returncode not in (0, 1):
        return usage.ru_maxrss * 1024, cpu, f"exit {proc.returncode} (over {max_gb:g} GB?)"
    return usage.ru_maxrss * 1024, cpu, "ok"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[1, 10, 50], help="model sizes in MB")
    ap.add_argument("--commands", nargs="+", default=list(COMMANDS), choices=list(COMMANDS))
    ap.add_argument("--timeout", type=float, default=900, help="seconds per run")
    ap.add_argument("--max-gb", type=float, default=12, help="address space allowed to each run")
    args = ap.parse_args()
    print(machine())
    print("memory: peak RSS (ru_maxrss) of each plx process, minus the same command on a one-body file")
    with tempfile.TemporaryDirectory(prefix="plx-mem-") as tmp:
        top = Path(tmp)
        (top / "plx.toml").write_text("max-file-size = 1024\n")
        generate(top / "tiny.openplx", 0)
        base = {c: peak(COMMANDS[c] + ["tiny.openplx"], top, args.timeout, args.max_gb)[0] or 0
                for c in args.commands}
        print(f"{'command':8} {'size MB':>8} {'peak MB':>8} {'tiny MB':>8} {'bytes/byte':>10} {'CPU s':>7}  status")
        for mb in args.sizes:
            name = f"m{mb:g}.openplx"
            size = generate(top / name, mb)
            for c in args.commands:
                rss, cpu, status = peak(COMMANDS[c] + [name], top, args.timeout, args.max_gb)
                ratio = f"{(rss - base[c]) / size:10.1f}" if rss is not None and status == "ok" else f"{'-':>10}"
                shown = f"{rss / 2**20:8.0f}" if rss is not None else f"{'-':>8}"
                print(f"{c:8} {size / 2**20:8.1f} {shown} {base[c] / 2**20:8.0f} {ratio} {cpu:7.1f}  {status}",
                      flush=True)
            (top / name).unlink()
    print("target (issue 41): at most 40 bytes of memory per byte of input")
    return 0


if __name__ == "__main__":
    sys.exit(main())
