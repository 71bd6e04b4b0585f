"""Reports of `plx check`: the text report (rich on a terminal, plain otherwise) and the JSON document."""

from __future__ import annotations

import math
import os
from typing import Any, TextIO

from plxtools.check.checks import STATIC_MOTION_CODES
from plxtools.check.pipeline import FileCheck, Skip
from plxtools.diagnostics import Diagnostic, Severity
from plxtools.rules import registry
from plxtools.check.frames import quat_xyzw_to_mat
from plxtools.rules.registry import get
from plxtools.rules.reporters import _summary_line
from plxtools.rules.reporters import render_text as lint_text


def _r(x: float, nd: int = 6) -> float:
    return float(round(float(x), nd)) + 0.0


def simulation_json(fc: FileCheck) -> dict[str, Any]:
    if fc.simulation is None:
        return {"model": fc.model, "skipped": fc.skipped or "not simulated"}
    s = fc.simulation
    bodies = {}
    for path, b in s.bodies.items():
        bodies[path] = {
            "dynamic": b.dynamic,
            "initial": {"position": [_r(x) for x in b.initial_pos], "quaternion": [_r(x) for x in b.initial_quat]},
            "final": {"position": [_r(x) for x in b.final_pos], "quaternion": [_r(x) for x in b.final_quat]},
            "distance": _r(b.distance),
            "horizontal_distance": _r(b.horizontal_distance),
            "path_length": _r(b.path_length),
            "heading_change": _r(b.heading_change),
            "max_speed": _r(b.max_speed),
            "kinetic_energy": _r(b.kinetic_energy),
            "max_kinetic_energy": _r(b.max_kinetic_energy),
            "potential_energy": _r(b.potential_energy),
        }
    d = s.to_dict()
    return {
        "model": fc.model,
        "duration": s.duration,
        "simulated_time": _r(s.simulated_time, 9),
        "steps": s.steps,
        "timestep": s.timestep,
        "integrator": s.integrator,
        "wall_time_s": _r(s.wall_time_s, 4),
        "bodies": bodies,
        "mates": d.get("mates", {}),
        "motors": d.get("motors", {}),
        "findings": {
            "blowup": d.get("blowup"),
            "fall_through": d.get("fall_through", []),
            "initial_penetrations": d.get("penetrations", []),
            "mates_pulled_apart": [m for m, r in d.get("mates", {}).items() if r.get("pulled_apart")],
            "joint_limit_violations": d.get("joint_limit_violations", []),
            "implausible_speeds": d.get("implausible_speeds", []),
            "energy_gain": ({"joules": d["energy"].get("max_unexplained_gain"),
                             "time": d["energy"].get("max_unexplained_gain_time")}
                            if _energy_gained(s) else None),
            "motion_diagnostics": [{"code": x.code, "line": x.span.start.line + 1, "message": x.message}
                                   for x in motion_diagnostics(fc)],
        },
        "energy": d.get("energy", {}),
    }


def document(results: list[FileCheck], diags: list[Diagnostic], simulate: bool) -> dict[str, Any]:
    doc: dict[str, Any] = {"diagnostics": [d.to_json() for d in diags]}
    doc["assembly"] = {
        fc.path: ({"model": fc.model, "bodies": fc.assembled_bodies()} if fc.assembled
                  else {"model": fc.model, "skipped": fc.skipped})
        for fc in results
    }
    if simulate:
        doc["simulation"] = {fc.path: simulation_json(fc) for fc in results}
        for path, sim in doc["simulation"].items():
            bad: list[str] = []
            doc["simulation"][path] = _finite_json(sim, "", bad)
            if bad and "findings" in sim:
                doc["simulation"][path]["findings"]["non_finite_values"] = bad
    found: list[str] = []
    doc = _finite_json(doc, "", found)
    return doc


def _finite_json(v: Any, where: str, found: list[str]) -> Any:
    """The value with every NaN / infinity replaced by None (JSON has no such numbers); the JSON
    paths of the replaced numbers are appended to ``found``."""
    if isinstance(v, float) or (hasattr(v, "dtype") and getattr(v, "shape", None) == ()):
        f = float(v)
        if not math.isfinite(f):
            found.append(where or "/")
            return None
        return f if isinstance(v, float) else v
    if hasattr(v, "tolist") and hasattr(v, "shape"):
        return _finite_json(v.tolist(), where, found)
    if isinstance(v, dict):
        return {k: _finite_json(x, f"{where}/{k}", found) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_finite_json(x, f"{where}/{i}", found) for i, x in enumerate(v)]
    return v


# ---------------------------------------------------------------------- text


def _use_rich(stream: TextIO) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return hasattr(stream, "isatty") and stream.isatty()


def _vec(v, nd: int = 2) -> str:
    tiny = 0.5 * 10 ** -nd  # no "-0.00"
    return "(" + ", ".join(f"{(0.0 if abs(float(x)) < tiny else float(x)):.{nd}f}" for x in v) + ")"


def assembly_line(fc: FileCheck) -> str:
    a = fc.assembly_summary()
    other = a.bodies - a.snap - a.declared
    parts = [f"{a.bodies} bod{'ies' if a.bodies != 1 else 'y'} ({a.declared} declared, {a.snap} placed by SNAP, "
             f"{other} at their system's origin)",
             f"{a.mates} mate{'s' if a.mates != 1 else ''}",
             f"{a.controllers} controller{'s' if a.controllers != 1 else ''}"]
    return f"{fc.path}: {fc.model}: " + ", ".join(parts)


def motion_rows(fc: FileCheck) -> list[tuple[str, ...]]:
    rows = []
    for path, b in fc.simulation.bodies.items():
        if not b.dynamic and b.path_length == 0.0:
            continue
        heading = f"{math.degrees(b.heading_change):+.1f} deg" if _upright(b) else "n/a"
        rows.append((path, _vec(b.initial_pos), _vec(b.final_pos), f"{b.distance:.3f} m", heading,
                     f"{b.max_speed:.3g} m/s", _joules(b.max_kinetic_energy)))
    return rows


def _joules(e: float) -> str:
    return f"{e:.3g} J" if abs(e) < 1e4 else f"{e / 1e3:.3g} kJ"


def _upright(b) -> bool:
    """Heading (yaw of the body's x axis) means something only for a body that stays upright."""
    import numpy as np

    for q in (b.initial_quat, b.final_quat):
        w, x, y, z = q
        if quat_xyzw_to_mat((x, y, z, w))[2, 2] < math.cos(math.radians(30)):
            return False
    return bool(np.isfinite(b.heading_change))


def findings(fc: FileCheck) -> list[str]:
    s = fc.simulation
    out = []
    if s.blowup:
        b = s.blowup
        out.append(f"blow-up at t={b['time']:.3f} s: {b['reason']}"
                   + (f" (fastest body: {b['fastest_body']})" if b.get("fastest_body") else ""))
    for m in s.mates.values():
        if m.pulled_apart:
            out.append(f"{m.path} pulled apart: max separation {m.max_separation:.4g} m at t="
                       f"{m.max_separation_time:.2f} s, max axis misalignment {math.degrees(m.max_misalignment):.3g} "
                       f"deg")
    for f in s.fall_through:
        if f.get("ground") is None:  # nothing under it: see checks.bodies_out_of_world
            out.append(f"{f['body']} fell out of the world (ended {f['drop']:.3g} m below where it started near)")
        else:
            out.append(f"{f['body']} fell through {f['ground']} at t={f['time']:.2f} s")
    for p in s.penetrations:
        out.append(f"{p['geom1']} and {p['geom2']} start {p['depth']:.4g} m deep in each other")
    for j in s.joint_limit_violations:
        out.append(f"{j['mate']} exceeded its range by {j['violation']:.3g} at t={j['time']:.2f} s")
    for v in s.implausible_speeds:
        out.append(f"{v['body']} reached an implausible {v['speed']:.3g} m/s at t={v['time']:.2f} s "
                   f"(bound {v['bound']:.3g} m/s)")
    if _energy_gained(s):
        out.append(f"energy gained without a motor doing the work: {s.energy['max_unexplained_gain']:.4g} J at "
                   f"t={s.energy['max_unexplained_gain_time']:.2f} s")
    for d in motion_diagnostics(fc):
        out.append(f"{d.code} (line {d.span.start.line + 1}): {d.message}")
    return out


# diagnostics that explain how the scene moves (or fails to): the summary lists them with the findings
MOTION_CODES = STATIC_MOTION_CODES  # and the run's registry.MOTOR_OFF_TARGET


def motion_diagnostics(fc: FileCheck) -> list[Diagnostic]:

    return [d for d in fc.diagnostics if d.code in MOTION_CODES or d.code == registry.MOTOR_OFF_TARGET]


def _energy_gained(s) -> bool:
    """The run reported energy that no motor supplied (its finding, not a threshold of ours)."""

    return any(n.code == registry.ENERGY_GAIN for n in s.notes)


def render_text(results: list[FileCheck], diags: list[Diagnostic], stream: TextIO, *, simulate: bool) -> None:
    rich = _use_rich(stream)
    lint_text(diags, stream, summary=False)
    console = None
    if rich:
        from rich.console import Console

        console = Console(file=stream, highlight=False, soft_wrap=True)
    for fc in results:
        if not fc.assembled:
            if fc.skip is not None and fc.skip is not Skip.NO_MODEL:
                _line(stream, console, f"{fc.path}: not assembled: {fc.skipped}", "yellow")
            continue
        if results and (diags or len(results) > 1 or simulate):
            stream.write("\n") if console is None else console.print()
        _line(stream, console, assembly_line(fc), "bold")
        if simulate:
            _render_simulation(fc, stream, console)
    if diags or results:
        stream.write("\n") if console is None else console.print()
    summary = _summary_text(results, diags)
    if console is not None:
        console.print(summary, style="bold" if diags else "green")
    else:
        stream.write(summary + "\n")


def _render_simulation(fc: FileCheck, stream: TextIO, console) -> None:
    """One file's simulation: the run, how each body moved, the energy and the findings."""
    if fc.simulation is None:
        _line(stream, console, f"  simulation skipped: {fc.skipped or 'the scene did not compile'}", "yellow")
        return
    s = fc.simulation
    head = (f"  simulated {s.simulated_time:.2f} s in {s.steps} steps of {s.timestep:g} s "
            f"({s.integrator}, {s.wall_time_s:.2f} s wall)")
    _line(stream, console, head, None)
    _render_motion_table(motion_rows(fc), stream, console)
    found = findings(fc)
    if s.energy:
        e = s.energy
        checked = "" if e.get("checked", True) else " (not checked: kinematic bodies or signal inputs do work)"
        _line(stream, console, f"  energy: {e['initial_total']:.6g} J at the start, {e['final_total']:.6g} J at the "
              f"end, motors' work {e.get('actuator_work', 0.0):.4g} J{checked}", None)
    if found:
        _line(stream, console, "  findings:", "bold red")
        for f in found:
            _line(stream, console, f"    - {f}", None)
    else:
        _line(stream, console, "  findings: none (no blow-up, no mate pulled apart, nothing fell through, "
              "no deep initial penetration, no energy gained, no implausible speed)", "green")


MOTION_COLUMNS = ("body", "start", "end", "moved", "heading", "top speed", "top kinetic energy")


def _render_motion_table(rows: list[tuple[str, ...]], stream: TextIO, console) -> None:
    cols = MOTION_COLUMNS
    if console is not None:
        from rich.padding import Padding
        from rich.table import Table

        table = Table(show_header=True, header_style="bold", box=None, padding=(0, 1), pad_edge=False)
        for c in cols:
            table.add_column(c, justify="left" if c in ("body", "start", "end") else "right")
        for r in rows:
            table.add_row(*r)
        console.print(Padding(table, (0, 0, 0, 2), expand=False))
        return
    widths = [max(len(c), *(len(r[i]) for r in rows)) if rows else len(c) for i, c in enumerate(cols)]
    fmt = "  " + "  ".join(f"{{:{'>' if i >= 3 else '<'}{w}}}" for i, w in enumerate(widths))
    stream.write(fmt.format(*cols) + "\n")
    for r in rows:
        stream.write(fmt.format(*r) + "\n")


def _summary_text(results: list[FileCheck], diags: list[Diagnostic]) -> str:
    """The last line: lint's count of findings, what the mapping notes are, and files not checked."""

    summary = _summary_line(diags, len(results))
    mapping = _mapping_notes(diags)
    if mapping:  # a first run shows these: say they are not problems in the model
        what = "notes on how the model is mapped to MuJoCo, not problems in it"
        if mapping == 1:
            what = "a note on how the model is mapped to MuJoCo, not a problem in it"
        summary = summary.rstrip(".") + (f": {what}." if mapping == len(diags) else
                                         f" ({mapping} of them {what}).")
    broken = sum(1 for fc in results if fc.internal_error is not None)
    if broken:  # never "All checks passed" when a file could not be checked
        summary = (f"{summary.rstrip('.')}; {broken} file{'s' if broken != 1 else ''} could not be checked "
                   f"(internal error).") if diags else f"{broken} of {len(results)} " \
            f"file{'s' if len(results) != 1 else ''} could not be checked (internal error)."
    return summary


def _mapping_notes(diags: list[Diagnostic]) -> int:
    """How many diagnostics are infos of the simulate stage (how a value was mapped to MuJoCo)."""

    n = 0
    for d in diags:
        rule = get(d.code)
        n += d.severity is Severity.INFO and rule is not None and rule.stage == "simulate"
    return n


def _line(stream: TextIO, console, text: str, style: str | None) -> None:
    if console is not None:
        from rich.text import Text

        console.print(Text(text, style=style or ""))
    else:
        stream.write(text + "\n")
