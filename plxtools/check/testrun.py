"""`plx test`: run scenario files against their models and report like pytest.

A scenario *passes* when every expectation holds; it *fails* (exit 1) when one does not (A140), when
its model cannot be simulated (A142) or the simulation reports an error (A101, A102, A107); it is an
*error* (exit 2, like a pytest collection error) when the scenario file itself is wrong (A141:
TOML, keys, unknown paths, values of the wrong kind, times outside the run, a root model that is
not in the file).  Output formats: text, json, github, sarif and junit (XML).
"""

from __future__ import annotations

import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TextIO

from plxtools.check.scenario import SUFFIX, Expect, Loc, Scenario, ScenarioError, bind, display_path, parse
from plxtools.diagnostics import Diagnostic, Pos, Severity, Span
from plxtools.rules import registry
from plxtools.check.api import ModelError, prepare
from plxtools.check.scenario import discover
from plxtools.check.scenecounts import scene_counts
from plxtools.check.scenario_objects import Placer, SceneObjects, read_connector
from plxtools.check.signals import SignalRuntime

PASSED, FAILED, ERROR = "passed", "failed", "error"
FORMATS = ("text", "json", "github", "sarif", "junit")


@dataclass
class Outcome:
    expect: Expect
    passed: bool | None = None  # None: never evaluated (the run stopped first)
    measured: float | None = None  # SI, at ``time`` (the first failing sample for `during`)
    time: float | None = None
    samples: int = 0
    worst: float | None = None  # `during`: the sample furthest outside, and its time
    worst_time: float | None = None

    def message(self) -> str:
        e = self.expect
        when = f"at t={self.time:.3f} s" if self.time is not None else ""
        if self.passed is None:
            return f"{e.of}: never evaluated: the simulation stopped before t=" \
                   f"{(e.at if e.at is not None else e.during[0]):g} s"  # type: ignore[index]
        measured = e.show(self.measured) if self.measured is not None else "nothing"
        text = f"{e.of} {when}: expected {e.expected_text()}, measured {measured}"
        if e.during is not None and self.worst is not None and self.worst_time != self.time:
            text += f" (first failure; worst {e.show(self.worst)} at t={self.worst_time:.3f} s)"
        return text

    def to_dict(self) -> dict[str, Any]:
        e = self.expect
        return {"line": e.loc.line, "of": e.of, "expectation": e.describe(), "passed": bool(self.passed),
                "evaluated": self.passed is not None, "time": self.time,
                "measured": _finite(self.measured / e.scale()) if self.measured is not None else None,
                "unit": e.unit if e.angular else None, "expected": e.expected_text()}


def _finite(x: float | None) -> float | None:
    return x if x is not None and math.isfinite(x) else None


@dataclass
class ScenarioResult:
    path: str
    name: str
    status: str = PASSED
    model: str | None = None
    model_file: str | None = None
    outcomes: list[Outcome] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    simulated_time: float = 0.0
    steps: int = 0
    wall_s: float = 0.0
    findings: list[Diagnostic] = field(default_factory=list)  # the run's warnings (not failing)

    @property
    def failures(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == Severity.ERROR]

    def to_dict(self) -> dict[str, Any]:
        return {"file": self.path, "name": self.name, "status": self.status, "model_file": self.model_file,
                "model": self.model, "simulated_time": round(self.simulated_time, 9), "steps": self.steps,
                "wall_time_s": round(self.wall_s, 4), "expectations": [o.to_dict() for o in self.outcomes],
                "diagnostics": [d.to_json() for d in self.diagnostics],
                "warnings": [d.to_json() for d in self.findings]}


def _span(line: int, col: int = 1) -> Span:
    p = Pos(0, max(line - 1, 0), max(col - 1, 0))
    return Span(p, p)


def diag(code: str, message: str, loc: Loc, severity: Severity = Severity.ERROR, help: str | None = None) -> Diagnostic:
    return Diagnostic(code, message, _span(loc.line, loc.column), severity, file=loc.file, help=help)


def _error(res: ScenarioResult, errors: list[ScenarioError]) -> ScenarioResult:
    res.status = ERROR
    res.diagnostics.extend(diag(registry.INVALID_SCENARIO, e.message, e.loc, help=e.help) for e in errors)
    return res


# ----------------------------------------------------------------------------- running


def run_scenario(path: Path, *, bundle_path: list[str] | tuple = (), openplx_version: str | None = None) -> ScenarioResult:
    """Parse, bind and run one scenario file.  Never raises for bad input."""
    t0 = time.perf_counter()
    sc, errors = parse(path)
    stem = path.name[: -len(SUFFIX)] if path.name.endswith(SUFFIX) else path.stem
    res = ScenarioResult(display_path(path), sc.name if sc else stem)
    if sc is None or errors:
        return _error(res, errors)
    try:
        _run(sc, res, bundle_path, openplx_version)
    finally:
        res.wall_s = time.perf_counter() - t0
    return res


def _run(sc: Scenario, res: ScenarioResult, bundle_path, openplx_version) -> None:
    import mujoco

    from plxtools.check.mujoco.simulate import simulate_compiled

    assert sc.model_file is not None
    model_file = display_path(sc.model_file)
    res.model_file = model_file
    prep = _prepare(sc, res, model_file, bundle_path, openplx_version)
    if prep is None:
        return
    res.model = prep.model
    runtime = SignalRuntime.bind(mujoco, prep.compiled, prep.signals)
    errors = bind(sc, prep.signals, prep.bodies, set(runtime.bindings), runtime.unbound, model_file,
                  scene_counts(prep.compiled.scene), SceneObjects(prep, runtime))
    errors += [ScenarioError(why, step.loc) for step in sc.inputs
               if step.signal in runtime.bindings and step.coerced is not None
               and (why := runtime.refusal(step.signal, step.coerced))]
    if errors:
        _error(res, errors)
        return
    res.outcomes = [Outcome(e) for e in sc.expects]
    driver = _Driver(sc, runtime, res.outcomes, float(prep.compiled.model.opt.timestep), Placer(prep, runtime))
    sim = simulate_compiled(prep.compiled, sc.end, controller=driver)
    res.simulated_time, res.steps = sim.simulated_time, sim.steps
    if driver.refused:  # a [[place]] that cannot be carried out: the scenario's error
        res.outcomes = []
        _error(res, driver.refused)
        return
    for o in res.outcomes:
        if not o.passed:
            res.diagnostics.append(diag(registry.EXPECTATION_FAILED, o.message(), o.expect.loc))
    _run_findings(sim.notes, res, model_file)
    if res.failures:
        res.status = FAILED


def _prepare(sc: Scenario, res: ScenarioResult, model_file: str, bundle_path, openplx_version) -> Any:
    """The model compiled for MuJoCo, or None when it cannot be (``res`` then says why: a root that
    is not in the file is the scenario's error, anything else a failure of the model)."""
    from plxtools.check.pipeline import NO_SUCH_ROOT, TRAIT_AS_ROOT

    try:
        return prepare(sc.model_file, sc.root, bundle_path=bundle_path, openplx_version=openplx_version)
    except ModelError as exc:
        codes = {d.code for d in exc.diagnostics}
        if sc.root is not None and codes & {NO_SUCH_ROOT, TRAIT_AS_ROOT}:
            d = next(d for d in exc.diagnostics if d.code in (NO_SUCH_ROOT, TRAIT_AS_ROOT))
            _error(res, [ScenarioError(f"{model_file}: {d.message}", sc.root_loc or sc.model_loc)])
            return None
        res.status = FAILED
        res.diagnostics.append(diag(registry.SCENARIO_MODEL_NOT_SIMULATED, f"{sc.name}: the model cannot be simulated: {exc}", sc.model_loc))
        res.diagnostics.extend(d for d in exc.diagnostics if d.severity == Severity.ERROR)
        return None


class _Driver:
    """The controller of a scenario's run (called before every step and once after the last): it
    sends each ``[[input]]`` and carries out each ``[[place]]`` when its time comes, and measures each
    ``[[expect]]`` at its time (or at every step of its ``during``), within half a step."""

    def __init__(self, sc: Scenario, runtime: Any, outcomes: list[Outcome], h: float, placer: Any = None) -> None:
        import mujoco

        self.mujoco = mujoco
        self.runtime = runtime
        self.placer = placer
        self.places = sorted(sc.places, key=lambda s: s.at)
        self.refused: list[ScenarioError] = []
        self.half = h / 2
        self.inputs = sorted(sc.inputs, key=lambda s: s.at)
        self.next_input = 0
        self.pending_at = [o for o in outcomes if o.expect.at is not None]
        self.during = [o for o in outcomes if o.expect.during is not None]

    def __call__(self, t: float, m: Any, d: Any) -> None:
        if self.places:
            self._place(t, m, d)
        self._send(t, m, d)
        if self.pending_at:
            self._measure_due(t, m, d)
        for o in self.during:
            t0, t1 = o.expect.during  # type: ignore[misc]
            if t0 - self.half <= t <= t1 + self.half:
                _sample(o, self.measure(o.expect, m, d), t)

    def _send(self, t: float, m: Any, d: Any) -> None:
        inputs = self.inputs
        while self.next_input < len(inputs) and inputs[self.next_input].at <= t + self.half:
            step = inputs[self.next_input]
            self.runtime.write(step.signal, step.coerced, m, d)
            self.next_input += 1

    def _place(self, t: float, m: Any, d: Any) -> None:
        while self.places and self.places[0].at <= t + self.half:
            step = self.places.pop(0)
            why = None if self.refused else self.placer.place(self.mujoco, step, t, m, d)
            if why:
                self.refused.append(ScenarioError(why, step.keys.get("path", step.loc)))

    def _measure_due(self, t: float, m: Any, d: Any) -> None:
        due = [o for o in self.pending_at if o.expect.at <= t + self.half]  # type: ignore[operator]
        for o in due:
            o.measured, o.time = self.measure(o.expect, m, d), t
            o.passed, o.samples = not o.expect.failures(o.measured), 1
        if due:
            self.pending_at = [o for o in self.pending_at if o not in due]

    def measure(self, e: Expect, m: Any, d: Any) -> float:
        if e.count is not None:
            return float(e.count)
        if e.fixed is not None:
            return e.fixed
        if e.connector is not None:
            return read_connector(d, e.connector)
        v = self.runtime.read(e.output, m, d)
        if e.norm:
            return math.sqrt(sum(x * x for x in v))
        return float(v[e.index]) if e.index is not None else float(v)


def _sample(o: Outcome, v: float, t: float) -> None:
    """One sample of a ``during`` expectation: the first failure, the worst one, or the first pass."""
    if o.expect.failures(v):
        if o.passed is not False:
            o.passed, o.measured, o.time = False, v, t
        if o.worst is None or o.expect.violation(v) > o.expect.violation(o.worst):
            o.worst, o.worst_time = v, t
    elif o.passed is None:
        o.passed, o.measured, o.time = True, v, t
    o.samples += 1


def _run_findings(notes: list, res: ScenarioResult, model_file: str) -> None:
    """The run's errors (a body that fell through among them) fail the scenario; its warnings of mates
    drifting apart and of geometries that start in each other are shown beside the result."""

    for n in notes:
        if n.severity == "error" or n.code in (registry.FELL_THROUGH, registry.MATE_DRIFT, registry.OVERLAP_AT_START):
            src = n.source
            loc = Loc(display_path(Path(src.file)) if src else model_file, src.line if src and src.line else 1,
                      src.column if src and src.column else 1)
            d = diag(n.code, n.message, loc, Severity.ERROR if n.severity == "error" else Severity.WARNING)
            (res.diagnostics if n.severity == "error" else res.findings).append(d)


# ----------------------------------------------------------------------------- reports


def render(results: list[ScenarioResult], fmt: str, out: TextIO, wall: float) -> None:
    if fmt == "json":
        json.dump(document(results, wall), out, indent=2, allow_nan=False)
        out.write("\n")
    elif fmt in ("github", "sarif"):
        from plxtools.rules.reporters import render as render_diags

        render_diags([d for r in results for d in r.diagnostics], fmt, out, files_checked=len(results))
    elif fmt == "junit":
        out.write(junit(results, wall))
    else:
        render_text(results, out, wall)


def _counts(results: list[ScenarioResult]) -> dict[str, int]:
    return {s: sum(1 for r in results if r.status == s) for s in (PASSED, FAILED, ERROR)}


def summary_line(results: list[ScenarioResult], wall: float) -> str:
    c = _counts(results)
    parts = [f"{c[s]} {s if s != ERROR else ('error' if c[s] == 1 else 'errors')}" for s in (FAILED, ERROR, PASSED)
             if c[s]]
    return f"{', '.join(parts) or 'no scenarios'} in {wall:.2f}s"


def render_text(results: list[ScenarioResult], out: TextIO, wall: float) -> None:
    for r in results:
        n = len(r.outcomes)
        detail = f" ({n} expectation{'s' if n != 1 else ''}, {r.simulated_time:.2f} s simulated)" \
            if r.status != ERROR and r.steps else ""
        out.write(f"{r.path}::{r.name} {r.status.upper()}{detail}\n")
    bad = [r for r in results if r.status != PASSED]
    if bad:
        out.write("\nFAILURES\n")
        for r in bad:
            out.write(f"--- {r.path}::{r.name}\n")
            for d in r.diagnostics:
                out.write(f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.severity.value} "
                          f"{d.code} {d.message}\n")
                if d.help:
                    out.write(f"  help: {d.help}\n")
    for r in results:
        for d in r.findings:
            out.write(f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.severity.value} "
                      f"{d.code} {d.message}\n")
    out.write(("\n" if bad else "") + summary_line(results, wall) + "\n")


def document(results: list[ScenarioResult], wall: float) -> dict[str, Any]:
    return {"scenarios": [r.to_dict() for r in results], "summary": {**_counts(results), "wall_time_s": round(wall, 3)},
            "diagnostics": [d.to_json() for r in results for d in r.diagnostics]}


def junit(results: list[ScenarioResult], wall: float) -> str:
    import xml.etree.ElementTree as ET

    c = _counts(results)
    suites = ET.Element("testsuites", name="plx test", tests=str(len(results)), failures=str(c[FAILED]),
                        errors=str(c[ERROR]), time=f"{wall:.3f}")
    suite = ET.SubElement(suites, "testsuite", name="plx test", tests=str(len(results)), failures=str(c[FAILED]),
                          errors=str(c[ERROR]), skipped="0", time=f"{wall:.3f}")
    for r in results:
        case = ET.SubElement(suite, "testcase", classname=r.path, name=r.name, file=r.path, time=f"{r.wall_s:.3f}")
        if r.status != PASSED:
            lines = [f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.code} {d.message}"
                     for d in r.diagnostics]
            el = ET.SubElement(case, "failure" if r.status == FAILED else "error",
                               message=r.diagnostics[0].message if r.diagnostics else r.status,
                               type=r.diagnostics[0].code if r.diagnostics else r.status)
            el.text = "\n".join(lines)
        out = [f"{o.expect.loc.line}: {o.expect.describe()}: " +
               ("passed" if o.passed else "FAILED") + (f" (measured {o.expect.show(o.measured)})"
                                                       if o.measured is not None else "") for o in r.outcomes]
        if out:
            ET.SubElement(case, "system-out").text = "\n".join(out)
    ET.indent(suites)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(suites, encoding="unicode") + "\n"


# ----------------------------------------------------------------------------- the command


def run_test(args) -> int:
    try:
        files = discover(args.paths)
    except FileNotFoundError as exc:
        print(f"plx test: {exc.args[0]}: no such file or folder", file=sys.stderr)
        return 2
    if not files:
        print(f"plx test: no scenario files (*.scenario.toml) under {' '.join(args.paths)}", file=sys.stderr)
        return 2
    from plxtools.progress import Bar

    t0 = time.perf_counter()
    results = []
    status = 0
    with Bar(len(files), "plx test", output_format=args.output_format) as bar:
        for f in files:
            bar.advance(f.name, by=0)
            try:
                results.append(run_scenario(f, bundle_path=args.bundle_path, openplx_version=args.openplx_version))
            except Exception as exc:  # a bug in plxtools: say so, go on with the other files
                import os
                import traceback

                from plxtools import runmode

                if runmode.interrupted():  # Ctrl-C, turned into another error by native code (MuJoCo)
                    raise KeyboardInterrupt from exc

                print(f"plx test: internal error while running {f}: {type(exc).__name__}: {exc}", file=sys.stderr)
                if os.environ.get("PLX_DEBUG"):
                    traceback.print_exc()
                status = 2
            bar.advance()
    render(results, args.output_format, sys.stdout, time.perf_counter() - t0)
    c = _counts(results)
    if c[ERROR]:
        status = 2
    elif c[FAILED]:
        status = max(status, 1)
    return status
