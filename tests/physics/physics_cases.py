"""Closed-form physics that `plx check --simulate` must reproduce: one OpenPLX model per case
(in ``models/``), the textbook value it must give, how it is measured from the motion that
``plx check --trace`` writes, and the tolerance with the reason for it.

Shared by ``tests/physics`` (the fast cases, in the suite) and ``bench/physics.py`` (the whole
table, printed for docs/physics.md)."""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

MODELS = Path(__file__).resolve().parent / "models"
G = 9.80665  # the gravity plx uses when the scene does not set one


class Trace(dict):
    """Columns of a ``--trace`` CSV by name, as numpy arrays; ``t`` is the time column."""

    @property
    def t(self) -> np.ndarray:
        return self["time"]


@dataclass
class Run:
    exit_code: int
    report: dict
    trace: Trace

    @property
    def codes(self) -> set[str]:
        return {d["code"] for d in self.report["diagnostics"]}


def run_model(path: Path, duration: float, model: str | None = None) -> Run:
    """``plx check PATH --simulate --trace`` in this process (the public command, not internals)."""
    from plxtools.cli import main

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "trace.csv"
        argv = ["check", str(path), "--duration", str(duration), "--trace", str(out), "--output-format", "json"]
        if model:
            argv += ["--model", model]
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            code = main(argv)
        report = json.loads(buf.getvalue())
        trace = Trace()
        if out.exists():
            with out.open(newline="") as fh:
                rows = list(csv.reader(fh))
            for k, name in enumerate(rows[0]):
                trace[name] = np.array([float(r[k]) for r in rows[1:]])
    return Run(code, report, trace)


# -- measurements -----------------------------------------------------------------------------
def crossings(t: np.ndarray, x: np.ndarray, level: float = 0.0) -> np.ndarray:
    """Times where ``x`` crosses ``level`` upwards, linearly interpolated between samples."""
    y = x - level
    i = np.nonzero((y[:-1] < 0) & (y[1:] >= 0))[0]
    return t[i] - y[i] * (t[i + 1] - t[i]) / (y[i + 1] - y[i])


def period(t: np.ndarray, x: np.ndarray) -> float:
    c = crossings(t, x)
    if len(c) < 2:
        return math.nan
    return float((c[-1] - c[0]) / (len(c) - 1))


def peaks(t: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Local maxima of ``x`` refined by a parabola through the three samples around each."""
    i = np.nonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]))[0] + 1
    out_t, out_x = [], []
    for k in i:
        y0, y1, y2 = x[k - 1], x[k], x[k + 1]
        den = y0 - 2 * y1 + y2
        d = 0.5 * (y0 - y2) / den if den != 0 else 0.0
        out_t.append(t[k] + d * (t[k + 1] - t[k]))
        out_x.append(y1 - 0.25 * (y0 - y2) * d)
    return np.array(out_t), np.array(out_x)


def decay_rate(t: np.ndarray, x: np.ndarray) -> float:
    """sigma of an envelope A exp(-sigma t), fitted to the peaks."""
    pt, px = peaks(t, x)
    px = np.abs(px)
    keep = px > 1e-6
    if keep.sum() < 3:
        return math.nan
    slope = np.polyfit(pt[keep], np.log(px[keep]), 1)[0]
    return float(-slope)


def acceleration(t: np.ndarray, s: np.ndarray, t0: float, t1: float) -> float:
    """Second derivative of a parabola fitted to s(t) on [t0, t1]."""
    keep = (t >= t0) & (t <= t1)
    return float(2 * np.polyfit(t[keep], s[keep], 2)[0])


def slope(t: np.ndarray, s: np.ndarray, t0: float, t1: float) -> float:
    keep = (t >= t0) & (t <= t1)
    return float(np.polyfit(t[keep], s[keep], 1)[0])


def at(t: np.ndarray, x: np.ndarray, when: float) -> float:
    return float(np.interp(when, t, x))


def along(tr: Trace, body: str, direction: tuple[float, float, float]) -> np.ndarray:
    """Displacement of ``body`` from its start, projected on a unit ``direction``."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    p = np.stack([tr[f"{body}.x"], tr[f"{body}.y"], tr[f"{body}.z"]], axis=1)
    return (p - p[0]) @ d


# -- the cases --------------------------------------------------------------------------------
@dataclass
class Case:
    name: str
    model: str  # file in models/
    duration: float
    what: str  # the quantity, in words, with its unit
    expected: float
    measure: Callable[[Run], float]
    tol: float  # relative, unless ``absolute``
    why: str  # the formula, and why the tolerance is what it is
    absolute: bool = False
    fast: bool = True  # run in the test suite (otherwise only by bench/physics.py)
    must_not_report: frozenset[str] = field(default_factory=lambda: frozenset({"A101", "A134", "A135"}))

    @property
    def path(self) -> Path:
        return MODELS / self.model

    def error(self, measured: float) -> float:
        if self.absolute:
            return abs(measured - self.expected)
        return abs(measured - self.expected) / abs(self.expected)


def _pendulum_period(inertia: float, mass: float, arm: float, amplitude: float) -> float:
    """Period of a physical pendulum, with the first finite-amplitude correction (1 + a^2/16)."""
    return 2 * math.pi * math.sqrt(inertia / (mass * G * arm)) * (1 + amplitude ** 2 / 16)


_BOB_I = 1.0 * 1.0 ** 2 + 0.4 * 1.0 * 0.01 ** 2
_ROD_I = 3.0 * (1.0 ** 2 + 0.02 ** 2) / 12 + 3.0 * 0.5 ** 2
_SPRING_W = math.sqrt(200.0 / 2.0)
_DAMPING = 200.0 * 2.0 / 60.0  # default dissipation: AGX's relaxation time 2/60 s x stiffness
_SIGMA = _DAMPING / (2 * 2.0)
_DOWN = {a: (math.cos(math.radians(a)), 0.0, -math.sin(math.radians(a))) for a in (20, 35)}  # down the slope
_FLYWHEEL_I = 0.5 * 10.0 * 0.3 ** 2


def _overdamped_rate(inertia: float, c: float, k: float) -> float:
    """The slow decay rate of I q'' + c q' + k q = 0 when overdamped."""
    return (c - math.sqrt(c * c - 4 * inertia * k)) / (2 * inertia)


_STIFF_I = 1.0 * (1.0 + 0.02 ** 2) / 12 + 1.0 * 0.5 ** 2
_STIFF_K = 1e6 + 1.0 * G * 0.5  # the spring plus gravity's restoring torque about the hanging rod


def rebound(z: np.ndarray, rest: float) -> float:
    """Height above ``rest`` of the first peak after the first impact (the lowest point before the
    ball comes back up)."""
    i = int(np.argmax((z[1:-1] <= z[:-2]) & (z[1:-1] < z[2:]))) + 1  # first local minimum
    j = i + int(np.argmax((z[i + 1:-1] >= z[i:-2]) & (z[i + 1:-1] > z[i + 2:]))) + 1  # next local maximum
    return float(z[j] - rest)


def _log_slope(t: np.ndarray, q: np.ndarray, t0: float, t1: float) -> float:
    keep = (t >= t0) & (t <= t1) & (np.abs(q) > 0)
    return float(-np.polyfit(t[keep], np.log(np.abs(q[keep])), 1)[0])

CASES: list[Case] = [
    Case("free fall", "free_fall.openplx", 1.0, "height after 1 s (m)", 10.0 - G / 2,
         lambda r: at(r.trace.t, r.trace["ball.z"], 1.0), 0.005,
         "z = z0 - g t^2 / 2. No contact, no damping: plx runs it with RK4, exact for a parabola (with "
         "implicitfast, semi-implicit Euler lags by g h t / 2 = 1 cm of the 4.9 m drop, 0.2 %)."),
    Case("simple pendulum period", "simple_pendulum.openplx", 6.0, "period (s)",
         _pendulum_period(_BOB_I, 1.0, 1.0, 0.05), lambda r: period(r.trace.t, r.trace["hinge.q"]), 0.001,
         "T = 2 pi sqrt(I / (m g L)) (1 + a^2/16), I including the ball's own inertia."),
    Case("physical pendulum period", "physical_pendulum.openplx", 6.0, "period (s)",
         _pendulum_period(_ROD_I, 3.0, 0.5, 0.05), lambda r: period(r.trace.t, r.trace["hinge.q"]), 0.001,
         "Rod about its end: T = 2 pi sqrt(I / (m g L/2)), I = m (L^2 + w^2)/12 + m L^2/4 (about 2 pi sqrt(2L / 3g))."),
    Case("spring-mass frequency", "spring_mass.openplx", 4.0, "angular frequency (rad/s)", _SPRING_W,
         lambda r: 2 * math.pi / period(r.trace.t, r.trace["slide.q"]), 0.001,
         "omega = sqrt(k / m) with k = 200 N/m, m = 2 kg, no damping."),
    Case("spring-mass undamped amplitude", "spring_mass.openplx", 4.0, "amplitude after 4 s (m)", 0.1,
         lambda r: float(peaks(r.trace.t, r.trace["slide.q"])[1][-1]), 0.01,
         "An undamped spring keeps its 0.1 m amplitude (RK4: conservative and contact-free; implicitfast damps "
         "it by about 1 % in 4 s)."),
    Case("spring-mass default dissipation: decay", "spring_mass_damped.openplx", 3.0, "decay rate (1/s)", _SIGMA,
         lambda r: decay_rate(r.trace.t, r.trace["slide.q"]), 0.02,
         "The bundle's DefaultDissipation is AGX's relaxation time 2/60 s: c = k 2/60, amplitude ~ exp(-c t / 2m). "
         "[I]: the relaxation time is AGX's documented default, the bundle says only 'the runtime decides'."),
    Case("spring-mass default dissipation: frequency", "spring_mass_damped.openplx", 3.0,
         "damped angular frequency (rad/s)", math.sqrt(_SPRING_W ** 2 - _SIGMA ** 2),
         lambda r: 2 * math.pi / period(r.trace.t, r.trace["slide.q"]), 0.01,
         "omega_d = sqrt(k/m - (c/2m)^2)."),
    Case("stiff torsion spring with bundle defaults: relaxation", "stiff_torsion_spring.openplx", 1.0,
         "decay rate (1/s)", _overdamped_rate(_STIFF_I, 1e6 * 2.0 / 60.0, _STIFF_K),
         lambda r: _log_slope(r.trace.t, r.trace["hinge.q"], 0.05, 0.3), 0.01,
         "TorsionSpring defaults: k = 1e6 N m/rad, default dissipation c = k 2/60: overdamped, "
         "q ~ exp(-s t) with s = (c - sqrt(c^2 - 4 I k)) / 2I. Needs the shortened time step (A133)."),
    Case("block on incline below friction angle", "incline_20.openplx", 2.0, "slip from 0.5 s to 2 s (m)", 0.0,
         lambda r: float(abs(along(r.trace, "plane.block", _DOWN[20])[-1]
                             - at(r.trace.t, along(r.trace, "plane.block", _DOWN[20]), 0.5))),
         0.001, "tan(20 deg) = 0.364 < mu = 0.5: static friction holds the block. Absolute tolerance 1 mm "
         "(MuJoCo's contacts are soft; the block creeps by micrometres).", absolute=True),
    Case("block sliding down incline", "incline_35.openplx", 2.0, "acceleration along the slope (m/s^2)",
         G * (math.sin(math.radians(35)) - 0.5 * math.cos(math.radians(35))),
         lambda r: acceleration(r.trace.t, along(r.trace, "plane.block", _DOWN[35]), 0.3, 2.0), 0.01,
         "a = g (sin 35 deg - mu cos 35 deg), mu = 0.5 (DryConeFriction, MuJoCo's elliptic cone)."),
    Case("solid cylinder rolling down incline", "rolling_cylinder.openplx", 2.0,
         "acceleration along the slope (m/s^2)", 2.0 / 3.0 * G * math.sin(math.radians(20)),
         lambda r: acceleration(r.trace.t, along(r.trace, "ramp.roller", _DOWN[20]), 0.3, 2.0), 0.01,
         "Rolling without slipping: a = 2/3 g sin 20 deg (I = m r^2 / 2)."),
    Case("velocity motor, no load", "flywheel_motor.openplx", 2.0, "speed at the end (rad/s)", 5.0,
         lambda r: float(r.trace["axle.qdot"][-1]), 0.001,
         "A velocity motor without load turns at its target speed."),
    Case("velocity motor at its torque limit", "flywheel_torque_limit.openplx", 2.0,
         "angular acceleration (rad/s^2)", (3.0 - 1.0) / _FLYWHEEL_I,
         lambda r: slope(r.trace.t, r.trace["axle.qdot"], 0.2, 2.0), 0.01,
         "Saturated at max_effort 3 N m against a 1 N m load: alpha = (3 - 1) / (m r^2 / 2).",
         must_not_report=frozenset({"A101", "A134", "A135"})),
    Case("hinge friction (constant limit)", "hinge_friction.openplx", 2.0, "deceleration (rad/s^2)", 0.9 / _FLYWHEEL_I,
         lambda r: -slope(r.trace.t, r.trace["axle.qdot"], 0.1, 2.0), 0.005,
         "ConstantLimitFriction limit 0.9 N m on the hinge (MuJoCo frictionloss): alpha = 0.9 / 0.45; the "
         "flywheel's initial angular velocity becomes the hinge speed."),
    Case("prismatic range stops a falling weight", "prismatic_range.openplx", 2.0,
         "position at rest on the stop (m)", -0.5, lambda r: float(r.trace["slide.q"][-1]), 0.002,
         "The range's start is -0.5 m; 2 mm absolute: MuJoCo limits are stiff springs, here with a time "
         "constant of two steps.", absolute=True),
    Case("prismatic range: overshoot on impact", "prismatic_range.openplx", 2.0,
         "deepest point past the stop (m)", 0.0,
         lambda r: float(max(0.0, -0.5 - r.trace["slide.q"].min())), 0.01,
         "Falling 0.5 m onto a rigid stop; 1 cm absolute: a MuJoCo limit is a stiff spring (time constant "
         "2 steps = 4 ms), so at 3.1 m/s it gives way by about 5 mm before it stops the weight.",
         absolute=True),
    Case("hinge range stops a swinging rod", "hinge_range.openplx", 2.0, "furthest angle reached (rad)", -0.4,
         lambda r: float(r.trace["hinge.q"].min()), 0.01,
         "Range start -0.4 rad; 0.01 rad absolute for the impact.", absolute=True),
    Case("gear ratio between two shafts", "gear_train.openplx", 2.0, "output / input shaft speed", 0.25,
         lambda r: float(r.trace["output_shaft.qdot"][-1] / r.trace["input_shaft.qdot"][-1]), 0.001,
         "DriveTrain.Gear with ratio 4 (input speed / output speed; connectors[0] is the input [I])."),
    Case("hinge actuator turns a wheel with its shaft", "gear_train.openplx", 2.0, "wheel speed (rad/s)", 2.0,
         lambda r: float(r.trace["wheel_drive.mate_3d.qdot"][-1]), 0.001,
         "DriveTrain.HingeActuator couples the output shaft to the wheel's hinge: 8 rad/s / 4."),
    Case("kinematic body at constant velocity", "kinematic_bodies.openplx", 2.0, "distance after 2 s (m)", 1.0,
         lambda r: float(r.trace["platform.x"][-1] - r.trace["platform.x"][0]), 1e-9,
         "is_dynamic: false with initial_local_linear_velocity 0.5 m/s: x = v t exactly."),
    Case("kinematically_controlled body holds still", "kinematic_bodies.openplx", 2.0,
         "height after 2 s (m)", 2.0, lambda r: float(r.trace["beam.z"][-1]), 1e-9,
         "A body listed in kinematically_controlled (deprecated, still honoured by AGX) does not fall.",
         absolute=True),
    Case("kinematic turntable: speed of its centre of mass", "kinematic_turntable.openplx", 1.0,
         "trace speed of the centre of mass (m/s)", 2.0 * 0.5,
         lambda r: float(np.max(np.sqrt(r.trace["table.vx"] ** 2 + r.trace["table.vy"] ** 2))), 1e-9,
         "is_dynamic: false turning at w = 2 rad/s, its mass 0.5 m off the axis: v = w r (MuJoCo reports 0 for "
         "a mocap body; plx reports the prescribed motion in the trace, top speed, scenarios, outputs and the API)."),
    Case("kinematic platform: reported top speed", "kinematic_turntable.openplx", 1.0, "top speed (m/s)", 0.5,
         lambda r: next(iter(r.report["simulation"].values()))["bodies"]["platform"]["max_speed"], 1e-9,
         "A platform driven at 0.5 m/s: its top speed in the report is 0.5 m/s."),
    Case("conveyor belt carries a box by friction", "conveyor_belt.openplx", 2.0, "distance in 2 s (m)",
         0.5 * 2.0 - 0.5 ** 2 / (2 * 0.5 * G),
         lambda r: float(r.trace["parcel.x"][-1] - r.trace["parcel.x"][0]), 0.02,
         "A box (mu 0.5) at rest on a kinematic belt at v = 0.5 m/s: friction accelerates it at mu g until it "
         "rides with the belt, x = v t - v^2 / (2 mu g). The belt is a free body of effectively infinite inertia "
         "set to its prescribed velocity every step, so the contact sees how fast it moves (before: a mocap body, "
         "and the box stayed where it was)."),
    Case("turntable carries a box by friction", "turntable_carry.openplx", 3.0,
         "speed / (w x distance from the axis) at the end", 1.0,
         lambda r: float(np.hypot(r.trace["box.vx"][-1], r.trace["box.vy"][-1])
                         / (1.0 * np.hypot(r.trace["box.x"][-1], r.trace["box.y"][-1]))), 0.02,
         "A box (mu 0.5) 0.5 m off the axis of a kinematic turntable turning at w = 1 rad/s: after the slip "
         "(mu g > w^2 r) it turns with the table, at w times its distance from the axis."),
    Case("lifting platform carries a load", "lifting_platform.openplx", 1.5, "rise from 0.5 s to 1.5 s (m)", 0.5,
         lambda r: at(r.trace.t, r.trace["load.z"], 1.5) - at(r.trace.t, r.trace["load.z"], 0.5), 0.02,
         "A box resting on a kinematic platform rising at 0.5 m/s rises with it: 0.5 m a second."),
    Case("drive-train velocity motor: driven hinge after 10 ms", "gear_train.openplx", 0.2,
         "hinge speed at t = 0.01 s (rad/s)", 8.0 / 4.0,
         lambda r: at(r.trace.t, r.trace["wheel_drive.mate_3d.qdot"], 0.01),
         0.01, "From rest, the motor's 8 rad/s through the 4:1 gear: 2 rad/s at the hinge. The whole train (shafts, "
         "gear, hinge actuator, wheel) is one MuJoCo coordinate and the motor a velocity constraint on it, so the "
         "hinge is at its speed after one step, as in the real runtime (tests/check/test_drivetrain_one_step.py, "
         "tests/check/test_velocity_constraint.py: also on a cart driven over the ground)."),
    Case("brake: a braked shaft slows at capacity / inertia", "brake_stop.openplx", 1.0,
         "shaft speed at t = 0.2 s (rad/s)", 4.0 - 0.5 * 10.0 / 0.5 * 0.2,
         lambda r: at(r.trace.t, r.trace["shaft.qdot"], 0.2), 1e-3,
         "DriveTrain.ManualBrake, torque_capacity 10 N m at engagement 0.5, on a 0.5 kg m^2 shaft at 4 rad/s: it "
         "slips with 5 N m, so w = 4 - 10 t (a friction-loss tendon whose bound is engagement x capacity)."),
    Case("brake: the stopped shaft stays held", "brake_stop.openplx", 1.0, "shaft speed at the end (rad/s)", 0.0,
         lambda r: float(r.trace["shaft.qdot"][-1]), 1e-6,
         "Stopped at t = 0.4 s, nothing loads it: dry friction holds it (no creep, no reversal).", absolute=True),
    Case("clutch: the output slips up to the input's speed", "clutch_transmit.openplx", 2.0,
         "output shaft speed at t = 0.5 s (rad/s)", 20.0 / 2.0 * 0.5,
         lambda r: at(r.trace.t, r.trace["output_shaft.qdot"], 0.5), 1e-3,
         "DriveTrain.AutomaticClutch (initially engaged) of 20 N m between an input held at 10 rad/s and a free "
         "2 kg m^2 output: it passes its capacity while slipping, 10 rad/s^2."),
    Case("clutch: then it sticks", "clutch_transmit.openplx", 2.0, "output shaft speed at the end (rad/s)", 10.0,
         lambda r: float(r.trace["output_shaft.qdot"][-1]), 1e-4,
         "From t = 1 s on the plates stick: the output turns with the input."),
    Case("differential: equal torques split the speed", "differential_split.openplx", 1.0,
         "left axle speed (rad/s)", 3.0, lambda r: float(r.trace["left.qdot"][-1]), 1e-4,
         "DriveTrain.Differential, gear_ratio 2, drive at 4 rad/s: w_l + w_r = 2 x 4 / 2 = 4; equal torques on "
         "axles of 1 and 3 kg m^2 from rest give w_l = 3 w_r, so 3 and 1 rad/s (a tendon equality)."),
    Case("differential: the sum of the axle speeds", "differential_split.openplx", 1.0,
         "(w_left + w_right) / w_drive", 2.0 / 2.0,
         lambda r: float((r.trace["left.qdot"][-1] + r.trace["right.qdot"][-1]) / r.trace["drive_shaft.qdot"][-1]),
         1e-4, "w_l + w_r = 2 w_drive / gear_ratio."),
    Case("restitution 0.5: rebound height", "bouncing_ball.openplx", 1.5, "rebound height / drop height",
         0.5 ** 2, lambda r: rebound(r.trace["ball.z"], 0.1) / 1.0, 0.03,
         "Dropped from h = 1 m with normal_restitution e = 0.5: it leaves at e v, so it rises to e^2 h. The "
         "contact's velocity target is -e v in the step the impact begins; 3 %: the step finds the impact up to "
         "v h deep (bench/restitution.py sweeps e, heights, mass ratios and steps)."),
    Case("restitution 0.8: rebound height", "bouncing_ball_08.openplx", 1.5, "rebound height / drop height",
         0.8 ** 2, lambda r: rebound(r.trace["ball.z"], 0.1) / 1.0, 0.03,
         "As above with e = 0.8: e^2 = 0.64."),
    Case("velocity motor lifting a weight (effort-limited)", "motor_lift.openplx", 2.0, "steady speed (m/s)", 0.5,
         lambda r: float(np.mean(r.trace["slide.qdot"][r.trace.t >= 1.6])), 0.001,
         "Target 0.5 m/s against the weight m g = 490 N, effort range +-1000 N. A stiff motor with a symmetric "
         "range is a velocity constraint solved with the slide (as AGX's): it rises at exactly its target speed "
         "(before: a servo of clamped gain that sagged by 3.9 %; any other range is a constraint too, an offset plus a friction bound, "
         "tests/physics/test_motor_load.py).",
         must_not_report=frozenset({"A101", "A134", "A135"})),
    Case("velocity motor lifting a weight, one-sided range", "motor_lift_one_sided.openplx", 2.0,
         "steady speed (m/s)", 0.5, lambda r: float(np.mean(r.trace["slide.qdot"][r.trace.t >= 1.6])), 0.001,
         "As above with the effort range [0, inf): the motor may only push up. Any range is a velocity "
         "constraint: a constant offset (the range's middle) plus a friction bound around it, the same set "
         "(a one-sided range gets the width that stops the driven inertia in one step and holds it against "
         "gravity). Before: a servo that sagged by 3.9 %."),
    Case("two motors, two ranges, two springs on one hinge", "crowded_hinge.openplx", 3.0, "balance angle (rad)",
         (5.0 + 3.0 + 20.0 * 0.0 + 10.0 * 0.2) / 30.0, lambda r: float(r.trace["axle.q"][-1]), 0.005,
         "Both motors stall at their effort limits (5 + 3 N m) against the springs (20 N m/rad at 0, 10 N m/rad at "
         "0.2 rad), which act as one spring of 30 N m/rad at their stiffness-weighted rest: q = (5 + 3 + 2) / 30, "
         "inside both ranges. No A134: the energy balance holds.",
         must_not_report=frozenset({"A101", "A134", "A135"})),
    Case("double pendulum: energy kept", "double_pendulum.openplx", 10.0, "largest energy drift / 2 m g L",
         0.0, lambda r: _energy(r)["max_drift"] / (2 * 1.0 * G * 1.0), 1e-4,
         "Two 1 kg, 1 m rods on frictionless hinges released horizontal: conservative, so E(t) = E(0). The scene "
         "has no contacts, damping, limits or motors, so plx runs it with RK4 (drift ~1e-7 of 2mgL in 10 s; "
         "implicitfast drifts 5 %).", absolute=True),
]


def _energy(r: Run) -> dict:
    return next(iter(r.report["simulation"].values()))["energy"]
