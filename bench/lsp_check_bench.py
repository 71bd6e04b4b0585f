"""The language server's per-edit check, in process: `AnalysisHost.update_document` + `state` on
bench/lsp_bench.py's generated document after a one-word edit (the same typo/fix edits), with the
collector off as the server runs it. Prints the CPU time per check (median, p95) and, with
--profile, a cProfile of the checks.

    python bench/lsp_check_bench.py [--lines 2000] [--edits 40] [--profile]
"""

from __future__ import annotations

import argparse
import gc
import os
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from lsp_bench import openplx_text  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=2000)
    ap.add_argument("--edits", type=int, default=40)
    ap.add_argument("--profile", action="store_true")
    ap.add_argument("--sort", default="tottime")
    ap.add_argument("--phases", action="store_true", help="CPU per phase (parse, symbols, checker, rules)")
    args = ap.parse_args()
    from plxtools.ide.host import AnalysisHost

    phases: dict[str, list[float]] = {}
    if args.phases:
        _time_phases(phases)

    text = openplx_text(args.lines)
    with tempfile.TemporaryDirectory(prefix="plx-check-bench-") as tmp:
        path = os.path.join(tmp, "bench.openplx")
        Path(path).write_text(text)
        host = AnalysisHost(root=tmp)
        host.open_document(path, text, 1)
        st = host.state(path)
        gc.collect()
        gc.freeze()
        first_diags = len(st.diagnostics)
        lines = text.split("\n")
        typo = ("density", "densty")
        cands = [n for n, ln in enumerate(lines) if typo[0] in ln]
        rng = random.Random(7)
        times = []
        version = 1
        prof = None
        if args.profile:
            import cProfile
            prof = cProfile.Profile()
        outs = []
        for _ in range(args.edits):
            n = rng.choice(cands)
            for a, b in (typo, typo[::-1]):
                lines[n] = lines[n].replace(a, b, 1)
                version += 1
                new = "\n".join(lines)
                gc.disable()
                t = time.process_time()
                if prof:
                    prof.enable()
                host.update_document(path, new, version)
                st = host.state(path)
                if prof:
                    prof.disable()
                times.append(time.process_time() - t)
                outs.append(len(st.diagnostics))
                gc.freeze()
                gc.enable()
        times.sort()
        print(f"{len(lines)} lines, {len(times)} checks: CPU median {1e3 * statistics.median(times):.1f} ms, "
              f"p95 {1e3 * times[int(0.95 * (len(times) - 1))]:.1f} ms, min {1e3 * times[0]:.1f} ms, max {1e3 * times[-1]:.1f} ms; diagnostics {first_diags} then {sorted(set(outs))}")
        for name, ts in phases.items():
            ts = ts[-len(times):]
            print(f"  {name:<28} median {1e3 * statistics.median(ts):6.1f} ms, min {1e3 * min(ts):6.1f} ms")
        if prof:
            import pstats
            pstats.Stats(prof).sort_stats(args.sort).print_stats(45)


def _time_phases(phases: dict[str, list[float]]) -> None:
    """Wrap the stages of a check with CPU timers (each stage's total per check)."""
    import plxtools.ide.host as host
    import plxtools.model.checker as checker
    import plxtools.model.workspace as workspace
    import plxtools.rules.analysis as analysis
    import plxtools.rules.literals as literals
    import plxtools.rules.style as style

    def wrap(owner, attr, name):
        f = getattr(owner, attr)

        def timed(*a, **k):
            t = time.process_time()
            try:
                return f(*a, **k)
            finally:
                phases.setdefault(name, []).append(time.process_time() - t)
        setattr(owner, attr, timed)

    wrap(host.AnalysisHost, "_parse", "parse (incremental)")
    wrap(workspace.Workspace, "unit_for", "symbols (unit_for)")
    wrap(checker.Checker, "run", "checker")
    wrap(workspace.Workspace, "_help_for_other_versions", "help for other versions")
    wrap(analysis, "unset_values", "unset values (M007/M008's facts)")
    wrap(style, "style_diagnostics", "style")
    wrap(literals, "literal_diagnostics", "literals")
    wrap(host.AnalysisHost, "_lint", "final (config, suppress)")


if __name__ == "__main__":
    main()
