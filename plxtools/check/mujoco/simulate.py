"""Run a compiled scene in MuJoCo and report what happened, in plain JSON-ready data."""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from plxtools.check.mujoco.compile import VISUAL_GROUP, CompiledScene, MateMonitor
from plxtools.check.mujoco.integrator import not_conservative
from plxtools.check.mujoco.kinematic import KinematicMover, Stepper, body_velocity, kinematic_dofs
from plxtools.check.mujoco.poses import angle_between
from plxtools.check.mujoco.velocity_constraint import reference_dof, reference_energy
from plxtools.check.mujoco.notes import ERROR, INFO, WARNING, BackendNote
from plxtools.rules import registry

# The codes of the run's findings that other modules recognise (plx test, the report, the static
# checks): each is named here, where it is raised, and imported from here.


@dataclass(slots=True)
class BodyReport:
    path: str
    dynamic: bool
    initial_pos: list[float]
    initial_quat: list[float]  # w, x, y, z
    final_pos: list[float]
    final_quat: list[float]
    displacement: list[float]  # final - initial, world
    distance: float  # |displacement|
    horizontal_distance: float  # |displacement| in the world XY plane
    path_length: float  # summed over samples
    heading_change: float  # rad, yaw of the body x axis about world Z, unwrapped (+ = counter-clockwise)
    max_speed: float  # m/s, centre of mass
    min_z: float
    fell_through_time: float | None = None
    kinetic_energy: float = 0.0  # J at the end (translation + rotation)
    max_kinetic_energy: float = 0.0  # J, largest over the samples
    potential_energy: float = 0.0  # J at the end, gravity only (-m g . x_cm)


@dataclass(slots=True)
class MateReport:
    path: str
    kind: str
    role: str  # tree (a MuJoCo joint) | loop (equality) | distance | open (not enforced) | pulled (started apart)
    initial_separation: (
        float  # m (perpendicular to the axis for prismatic/cylindrical; |d - target| for distance)
    )
    max_separation: float
    max_separation_time: float
    initial_misalignment: float  # rad between the main axes (and normals for a lock)
    max_misalignment: float
    max_misalignment_time: float
    pulled_apart: bool
    final_separation: float = 0.0
    final_misalignment: float = 0.0


@dataclass(slots=True)
class MotorReport:
    path: str
    kind: str
    target: float  # target speed (velocity motors) or effort (torque / force motors)
    mean_speed: float  # over the last 20 % of the run, in the controller's own coordinate
    mean_effort: float
    kv: float | None
    tracking_error: float | None  # |mean_speed - target| for velocity motors


@dataclass(slots=True)
class SimulationResult:
    ok: bool  # no error notes from compilation or simulation
    scene: str
    duration: float
    simulated_time: float
    steps: int
    timestep: float
    wall_time_s: float
    compile_ms: float
    integrator: str = "implicitfast"  # MuJoCo's integrator (mujoco.integrator.choose says why)
    blowup: dict[str, Any] | None = None
    penetrations: list[dict[str, Any]] = field(default_factory=list)
    fall_through: list[dict[str, Any]] = field(default_factory=list)
    joint_limit_violations: list[dict[str, Any]] = field(default_factory=list)
    bodies: dict[str, BodyReport] = field(default_factory=dict)
    mates: dict[str, MateReport] = field(default_factory=dict)
    motors: dict[str, MotorReport] = field(default_factory=dict)
    energy: dict[str, Any] = field(default_factory=dict)
    implausible_speeds: list[dict[str, Any]] = field(default_factory=list)
    notes: list[BackendNote] = field(default_factory=list)
    trace: dict[str, Any] | None = None  # record=True: see :class:`Trace`

    def to_dict(self) -> dict[str, Any]:
        d = {k: v for k, v in asdict(self).items() if k != "notes"}
        d["notes"] = [n.to_dict() for n in self.notes]
        return _jsonable(d)


def _jsonable(x: Any) -> Any:
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return _jsonable(x.tolist())
    if isinstance(x, (np.floating, float)):
        f = float(x)
        return f if math.isfinite(f) else None
    if isinstance(x, np.integer):
        return int(x)
    return x


def _vec(a: Any) -> list[float]:
    return [float(v) for v in a]


class _Supports:
    """Static, non-visual geometry a body started above (for fall-through detection).

    A body "falls through" when its centre of mass, which started above the top of a static
    geometry (world AABB top, or a plane), gets more than ``fall_margin`` below it while still
    inside its XY footprint.  A resting body always has its centre of mass above its support."""

    def __init__(self, model: Any, data: Any) -> None:
        import mujoco

        self.planes: list[tuple[int, np.ndarray, np.ndarray]] = []
        self.boxes: list[tuple[int, np.ndarray, np.ndarray]] = []  # (geom, lo, hi) world AABB
        for g in range(model.ngeom):
            if model.body_weldid[model.geom_bodyid[g]] != 0 or model.geom_group[g] == VISUAL_GROUP:
                continue
            r = data.geom_xmat[g].reshape(3, 3)
            if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE:
                self.planes.append((g, data.geom_xpos[g].copy(), r[:, 2].copy()))
                continue
            c, h = model.geom_aabb[g][:3], model.geom_aabb[g][3:]
            center = data.geom_xpos[g] + r @ c
            half = np.abs(r) @ h
            self.boxes.append((g, center - half, center + half))

    def below(self, g_index: int, p: np.ndarray, margin: float) -> bool:
        for g, pt, n in self.planes:
            if g == g_index:
                return float(np.dot(p - pt, n)) < -margin
        for g, lo, hi in self.boxes:
            if g == g_index:
                inside = lo[0] <= p[0] <= hi[0] and lo[1] <= p[1] <= hi[1]
                return inside and p[2] < hi[2] - margin
        return False

    def above(self, p: np.ndarray, tol: float = 1e-6) -> list[int]:
        out = [g for g, pt, n in self.planes if float(np.dot(p - pt, n)) >= -tol]
        out += [
            g
            for g, lo, hi in self.boxes
            if lo[0] <= p[0] <= hi[0] and lo[1] <= p[1] <= hi[1] and p[2] >= hi[2] - tol
        ]
        return out


def _monitor_measure(mon: MateMonitor, ids: tuple[int, int], data: Any) -> tuple[float, float | None]:
    b0, b1 = ids
    r0 = data.xmat[b0].reshape(3, 3)
    r1 = data.xmat[b1].reshape(3, 3)
    p0 = data.xpos[b0] + r0 @ mon.pos0
    p1 = data.xpos[b1] + r1 @ mon.pos1
    a0, a1 = r0 @ mon.axis0, r1 @ mon.axis1
    d = p1 - p0
    if mon.kind == "distance":
        return abs(float(np.linalg.norm(d)) - mon.target_distance), None
    if mon.kind in ("prismatic", "cylindrical"):
        d = d - float(np.dot(d, a0)) * a0
    sep = float(np.linalg.norm(d))
    if mon.kind == "ball":
        return sep, None
    mis = angle_between(a0, a1)
    if mon.kind == "lock":
        mis = max(mis, angle_between(r0 @ mon.normal0, r1 @ mon.normal1))
    return sep, mis


@dataclass(frozen=True, slots=True)
class SimOptions:
    """Thresholds of the monitors (see :func:`plxtools.check.mujoco.backend.simulate`)."""

    sample_dt: float = 0.01
    timeout: float | None = None  # s of wall-clock time; None: no limit
    deadline: float | None = None  # time.perf_counter() by which the file's whole check ends (--timeout)
    energy_tol: float = 0.05  # energy gain tolerated, as a fraction of the run's energy scale
    drift_tol: float = 0.01  # conservative, contact-free scenes: energy drift either way tolerated, same scale
    penetration_tol: float = 0.005
    max_speed: float = 1e3
    fall_margin: float = 0.01
    mate_tol: float = 5e-3
    angle_tol: float = 0.05
    limit_tol: float = 0.02
    record: bool = False


@dataclass
class SimRun:
    """What every monitor sees: the MuJoCo model and data, the result being filled, and ``add``
    for the backend's findings (A1xx notes)."""

    mujoco: Any
    compiled: CompiledScene
    model: Any
    data: Any
    res: SimulationResult
    opt: SimOptions
    duration: float
    bodies: list[tuple[str, int, bool]]  # (path, MuJoCo body id, dynamic)
    speed: dict[str, float] = field(default_factory=dict)  # body path -> speed at the last sample
    movers: list["KinematicMover"] = field(default_factory=list)
    controlled: bool = False  # a controller (signal inputs) writes to the state between steps

    @property
    def dyn(self) -> list[tuple[str, int]]:
        """The dynamic bodies (built once: `bodies` does not change during a run, and monitors ask
        at every sample)."""
        got = self.__dict__.get("_dyn")
        if got is None or got[0] is not self.bodies:
            got = self.__dict__["_dyn"] = (self.bodies, [(p, i) for p, i, d in self.bodies if d])
        return got[1]

    @property
    def moving(self) -> list[tuple[str, int]]:
        """Dynamic bodies and kinematic bodies that move as prescribed."""
        kin = {m.path for m in self.movers}
        return [(p, i) for p, i, d in self.bodies if d or p in kin]

    # while a batch of samples is evaluated (`Samples.flush`): the findings, keyed by (sample,
    # monitor, order), put in sample order once every monitor has seen the batch
    pending: list[tuple[int, int, int, BackendNote]] | None = None
    monitor_index: int = 0
    batch_speed: np.ndarray | None = None  # (samples, moving bodies): speeds of the batch (BodyMotion)
    moving_col: dict[str, int] = field(default_factory=dict)  # body path -> column of batch_speed

    def add(self, sev: str, code: str, msg: str, path: str | None, at: int | None = None) -> None:
        """A finding; ``at`` is the sample of the batch it was found at (batched monitors)."""
        src = self.compiled.names.sources.get(path) if path else None
        note = BackendNote(sev, code, msg, src, path)
        if at is not None and self.pending is not None:
            self.pending.append((at, self.monitor_index, len(self.pending), note))
        else:
            self.res.notes.append(note)


class Monitor:
    """One thing watched during the run: set up at t=0, then every ``sample_dt`` either
    ``sample`` (the state is in ``run.data``) or, for a ``batched`` monitor, ``samples`` with many
    samples at once (:class:`Samples`: the state of each sample, copied into arrays when it was
    taken); ``finish`` writes its part of the result.  A new check of the motion is a Monitor.  One
    with ``per_step`` set also sees every single step (``before_step`` / ``after_step``)."""

    per_step = False
    batched = False

    def before_step(self, run: SimRun) -> None:
        pass

    def after_step(self, run: SimRun) -> None:
        pass

    def sample(self, run: SimRun, t: float) -> None:
        pass

    def samples(self, run: SimRun, b: "Samples") -> None:
        pass

    def finish(self, run: SimRun) -> None:
        pass


# what a sample records for the batched monitors (MjData fields, copied whole)
SAMPLE_FIELDS = ("xpos", "xmat", "xipos", "ximat", "cvel", "subtree_com", "qpos", "qvel", "qfrc_constraint", "energy",
                 "actuator_velocity", "actuator_force")
_SAMPLE_BYTES = 4_000_000  # buffer size that sets how many samples a batch holds (8 to 256)
MOTOR_WINDOW = 0.8  # MotorTracking averages over t >= MOTOR_WINDOW * duration
TRACKING_TOL, TRACKING_ABS = 0.02, 0.005  # A106: a velocity motor off its target by more than 2 % + 0.005


class Samples:
    """The state at the last ``n`` samples: each field of :data:`SAMPLE_FIELDS` as an array
    ``(capacity, *shape)``, filled by ``record`` (one copy per field), with the sample times ``t``
    and the steps done ``step``.  The batched monitors read rows ``[:n]``; ``flush`` hands them the
    batch and starts a new one."""

    def __init__(self, data: Any, capacity: int | None = None) -> None:
        srcs = [getattr(data, f) for f in SAMPLE_FIELDS]
        if capacity is None:
            per = 8 * (2 + sum(a.size for a in srcs))
            capacity = min(256, max(8, _SAMPLE_BYTES // per))
        self.capacity = capacity
        self.n = 0
        self.t = np.zeros(capacity)
        self.step = np.zeros(capacity, dtype=np.int64)
        self._copy: list[tuple[np.ndarray, np.ndarray]] = []
        for f, src in zip(SAMPLE_FIELDS, srcs):
            buf = np.zeros((capacity, *src.shape))
            setattr(self, f, buf)
            self._copy.append((buf, src))

    @classmethod
    def now(cls, data: Any, t: float = 0.0, step: int = 0) -> "Samples":
        """A batch of one sample: the current state."""
        b = cls(data, 1)
        b.record(t, step)
        return b

    def record(self, t: float, step: int) -> bool:
        """Copy the current state; True when the batch is full."""
        k = self.n
        self.t[k] = t
        self.step[k] = step
        for buf, src in self._copy:
            buf[k] = src
        self.n = k + 1
        return self.n == self.capacity

    def flush(self, run: SimRun, monitors: list[Monitor]) -> None:
        """Every batched monitor sees the batch, in MONITORS order; their findings are reported
        in the order the samples were taken (then monitor order), as when they saw one sample at
        a time."""
        if not self.n:
            return
        run.pending = []
        try:
            for k, m in enumerate(monitors):
                run.monitor_index = k
                m.samples(run, self)
            pending = sorted(run.pending, key=lambda e: e[:3])
        finally:
            run.pending = None
            run.batch_speed = None
        run.res.notes.extend(e[3] for e in pending)
        self.n = 0


def _running_sum(total: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``total + rows[0] + rows[1] + ...`` added one row at a time, as a loop doing
    ``total += row`` would (``np.add.accumulate`` is sequential, unlike ``sum``)."""
    return np.add.accumulate(np.concatenate([total[None], rows]), axis=0)[-1]


def _running_max(best: np.ndarray, when: np.ndarray, vals: np.ndarray, times: np.ndarray) -> np.ndarray:
    """The loop ``if v > best: best, when = v, t`` over the rows of ``vals`` (samples x items),
    in place: the largest value above ``best`` and the first time it was reached (NaN never wins).
    Returns the mask of the items that changed."""
    cand = np.where(vals > best, vals, -np.inf)
    i = cand.argmax(axis=0)
    top = cand[i, np.arange(cand.shape[1])]
    up = top > best
    if up.any():
        best[up] = top[up]
        when[up] = times[i[up]]
    return up


MAX_OVERLAPS_LISTED = 1000  # A104 pairs listed one by one; the rest are counted (a heap of bodies has n^2/2)


def _limit(opt: SimOptions) -> str:
    return f"{opt.timeout:g} s of wall time" if opt.timeout is not None else "the deadline given"


def initial_penetrations(run: SimRun, deadline: float | None = None) -> bool:
    """Geometries that start deeper than ``penetration_tol`` in each other (A104), from the contacts
    MuJoCo's own broad and narrow phase found at t=0. The contact fields are read once as arrays and
    grouped per pair with numpy (linear in the contacts; indexing ``data.contact[k]`` copies the
    whole list each time). Pairs are reported deepest first until ``deadline``; False when it cut
    the report short (what was found so far is reported, and how many pairs were left)."""
    model, data, names = run.model, run.data, run.compiled.names
    n = int(data.ncon)
    if n == 0:
        return True
    con = data.contact
    dist = np.asarray(con.dist[:n], dtype=float)
    deep = np.flatnonzero(dist < -run.opt.penetration_tol)
    if deep.size == 0:
        return True
    geom = np.asarray(con.geom[:n])[deep].astype(np.int64)
    pos = np.asarray(con.pos[:n])[deep]
    dist = dist[deep]
    key = geom[:, 0] * max(int(model.ngeom), 1) + geom[:, 1]
    order = np.lexsort((dist, key))  # by pair, the deepest contact first within each pair
    first = np.flatnonzero(np.r_[True, key[order][1:] != key[order][:-1]])
    counts = np.diff(np.r_[first, order.size])
    heads = order[first]
    by_depth = np.argsort(dist[heads], kind="stable")  # the deepest pairs are reported first
    paths: dict[int, str] = {}

    def path(g: int) -> str:
        p = paths.get(g)
        if p is None:
            p = paths[g] = names.path("geom", model.geom(g).name)
        return p

    for done, j in enumerate(by_depth):
        if done == MAX_OVERLAPS_LISTED:
            run.add(WARNING, registry.OVERLAP_AT_START, f"{len(by_depth) - done} more pairs of geometries overlap at t=0 (the "
                    f"{done} deepest are listed)", None)
            break
        if deadline is not None and done % 256 == 0 and time.perf_counter() > deadline:
            left = len(by_depth) - done
            run.add(ERROR, registry.SIMULATION_TIMEOUT, f"the check of initial overlaps was stopped by the time limit "
                    f"({_limit(run.opt)}) after {done} of {len(by_depth)} overlapping pairs "
                    f"({left} not reported); the simulation did not run", None)
            return False
        k = heads[j]
        ga, gb = int(geom[k, 0]), int(geom[k, 1])
        g1, g2 = path(ga), path(gb)
        depth = float(-dist[k])
        run.res.penetrations.append({"geom1": g1, "geom2": g2, "depth": depth, "contacts": int(counts[j]),
                                     "pos": _vec(pos[k])})
        run.add(WARNING, registry.OVERLAP_AT_START, f"{g1} and {g2} overlap by {depth:.4g} m at t=0", g1)
    return True


class BlowUp:
    """NaN/Inf, MuJoCo's bad-state warnings or a generalised velocity above ``max_speed`` (A101).

    Checked at every sample on the raw state (``qpos``, ``qvel``, warning counters), before
    anything is computed from it."""

    def __init__(self, run: SimRun) -> None:
        mj = run.mujoco
        self.warn_ids = [int(w) for w in (mj.mjtWarning.mjWARN_BADQPOS, mj.mjtWarning.mjWARN_BADQVEL,
                                          mj.mjtWarning.mjWARN_BADQACC)]
        self.counts = run.data.warning.number  # a view: the counters as MuJoCo updates them
        self.qpos, self.qvel = run.data.qpos, run.data.qvel
        self._abs_p, self._abs_v = np.zeros_like(self.qpos), np.zeros_like(self.qvel)
        self.warn0 = self._warnings()
        self.bounded = True  # at the last check: |qpos|, |qvel| <= mjMAXVAL (MuJoCo's own checks pass)
        self.max_val = float(mj.mjMAXVAL)

    def _warnings(self) -> int:
        c = self.counts
        a, b, d = self.warn_ids
        return int(c[a]) + int(c[b]) + int(c[d])

    def check(self, run: SimRun) -> str | None:
        """Why the run blew up, or None."""
        warns = self._warnings()
        top = np.maximum.reduce
        p = float(top(np.abs(self.qpos, out=self._abs_p))) if self.qpos.size else 0.0
        v = float(top(np.abs(self.qvel, out=self._abs_v))) if self.qvel.size else 0.0
        finite = math.isfinite(p) and math.isfinite(v)  # a NaN anywhere makes the max NaN
        vel_max = v if finite else 0.0
        self.bounded = p <= self.max_val and v <= self.max_val
        if warns > self.warn0:
            return "MuJoCo reported a NaN/Inf/huge state (mjWARN_BADQPOS/QVEL/QACC) and reset"
        if not finite:
            return "NaN or Inf in the state"
        if vel_max > run.opt.max_speed:
            return f"generalised velocity {vel_max:.3g} exceeds {run.opt.max_speed:g}"
        return None

    def report(self, run: SimRun, t: float, step: int, reason: str) -> None:
        worst = max(run.speed, key=lambda p: run.speed[p]) if run.speed else None
        run.res.blowup = {"time": t, "step": step, "reason": reason, "fastest_body": worst}
        run.add(ERROR, registry.SIMULATION_BLOWUP, f"numerical blow-up at t={t:.3f} s: {reason}"
                + (f" (fastest body before: {worst})" if worst else ""), worst)


class BadControl(Monitor):
    """MuJoCo zeroing NaN or huge controls (A107)."""

    def __init__(self, run: SimRun) -> None:
        self.count0 = self._count(run)

    @staticmethod
    def _count(run: SimRun) -> int:
        return int(run.data.warning[run.mujoco.mjtWarning.mjWARN_BADCTRL].number)

    def finish(self, run: SimRun) -> None:
        if self._count(run) > self.count0:
            run.add(ERROR, registry.BAD_CONTROL, "MuJoCo rejected a NaN/huge actuator control (> 1e10) and zeroed the controls", None)


class Trace(Monitor):
    """``record=True``: at every sample, the coordinate and speed of every mate's joint (in
    OpenPLX's sign) and the world pose, centre-of-mass velocity and angular velocity of every body
    (what ``plx check --trace`` writes)."""

    def __init__(self, run: SimRun) -> None:
        model, compiled = run.model, run.compiled
        # (key, qpos address, dof address, sign or speed ratio, offset)
        self.traced: list[tuple[str, int, int, float, float]] = []
        for mate_path, jnames in compiled.joints.items():
            for jn in jnames:
                j = model.joint(jn)
                if model.jnt_type[j.id] in (2, 3):
                    key = mate_path + (jn[jn.rfind(":") :] if len(jnames) > 1 else "")
                    self.traced.append((key, int(model.jnt_qposadr[j.id]), int(model.jnt_dofadr[j.id]),
                                        compiled.joint_sign[mate_path], 0.0))
        for shaft, coord in compiled.shafts.items():  # a shaft of a rigid drive train turns with its joint
            if shaft not in compiled.joints:
                j = model.joint(coord.joint)
                self.traced.append((shaft, int(model.jnt_qposadr[j.id]), int(model.jnt_dofadr[j.id]),
                                    coord.factor, coord.offset))
        self.vel6 = np.zeros(6)
        run.res.trace = {"time": [], "joints": {k: [] for k, *_ in self.traced},
                         "joint_speeds": {k: [] for k, *_ in self.traced},
                         "bodies": {p: {"position": [], "quaternion": [], "velocity": [], "angular_velocity": []}
                                    for p, _, _ in run.bodies}}
        self.sample(run, 0.0)

    def sample(self, run: SimRun, t: float) -> None:
        tr, data = run.res.trace, run.data
        tr["time"].append(t)
        for key, qa, da, sgn, off in self.traced:
            tr["joints"][key].append(sgn * float(data.qpos[qa]) + off if off else sgn * float(data.qpos[qa]))
            tr["joint_speeds"][key].append(sgn * float(data.qvel[da]))
        for p, i, _ in run.bodies:
            b = tr["bodies"][p]
            b["position"].append(_vec(data.xpos[i]))
            b["quaternion"].append(_vec(data.xquat[i]))
            body_velocity(run.mujoco, run.model, data, run.compiled, i, self.vel6)
            b["velocity"].append(_vec(self.vel6[3:]))
            b["angular_velocity"].append(_vec(self.vel6[:3]))


class BodyMotion(Monitor):
    """Per moving body: path length, heading change, top speed, lowest point, kinetic and
    potential energy; the body reports.

    A batch of samples is read at once (numpy over samples x bodies): the velocity of a centre
    of mass is MuJoCo's com-based `cvel` moved from the subtree's centre of mass to `xipos` (what
    `mj_objectVelocity` does for one body).  The speeds of the batch are left in
    ``run.batch_speed`` for Plausibility."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        data, model = run.data, run.model
        self.start = {p: (data.xpos[i].copy(), data.xquat[i].copy()) for p, i, _ in run.bodies}
        moving = run.moving
        self.paths = [p for p, _ in moving]
        run.moving_col = {p: k for k, p in enumerate(self.paths)}
        self.ids = np.array([i for _, i in moving], dtype=int)
        self.roots = np.array([model.body_rootid[i] for _, i in moving], dtype=int)
        self.mass = np.array([model.body_mass[i] for _, i in moving], dtype=float)
        self.inertia = np.array([model.body_inertia[i] for _, i in moving], dtype=float).reshape(-1, 3)
        x = data.xpos[self.ids]
        self.last_pos = x.copy()
        self.yaw_last = self._yaw(data.xmat[self.ids])
        self.min_z = x[:, 2].copy()
        n = len(self.paths)
        self.path_length = np.zeros(n)
        self.yaw_total = np.zeros(n)
        self.max_speed = np.zeros(n)
        self.ke_max = np.zeros(n)
        self.vel6 = np.zeros(6)
        self._motion(run, Samples.now(data), first=True)
        run.batch_speed = None

    @staticmethod
    def _yaw(m: np.ndarray) -> np.ndarray:
        # row-major 3x3 in the last axis: r[1, 0] is column 3, r[0, 0] column 0
        return np.arctan2(m[..., 3], m[..., 0])

    def kinetic(self, run: SimRun, i: int) -> float:
        """Kinetic energy of body ``i`` now (used once per body at the end)."""
        model, data = run.model, run.data
        body_velocity(run.mujoco, model, data, run.compiled, i, self.vel6)
        v, w = self.vel6[3:], self.vel6[:3]
        w_local = data.ximat[i].reshape(3, 3).T @ w
        return 0.5 * float(model.body_mass[i]) * float(v @ v) + 0.5 * float(model.body_inertia[i] @ (w_local ** 2))

    def samples(self, run: SimRun, b: Samples) -> None:
        self._motion(run, b)

    def _motion(self, run: SimRun, b: Samples, first: bool = False) -> None:
        if not self.paths:
            return
        s, n = b.n, len(self.paths)
        x = b.xpos[:s, self.ids]  # (samples, bodies, 3)
        if not first:
            prev = np.concatenate([self.last_pos[None], x[:-1]])
            step = x - prev
            self.path_length = _running_sum(self.path_length, np.sqrt((step * step).sum(axis=2)))
            self.last_pos = x[-1].copy()
            y = self._yaw(b.xmat[:s, self.ids])
            prev_y = np.concatenate([self.yaw_last[None], y[:-1]])
            self.yaw_total = _running_sum(self.yaw_total, (y - prev_y + math.pi) % (2 * math.pi) - math.pi)
            self.yaw_last = y[-1].copy()
        # every (sample, body) as one row, as the per-sample formulas had one row per body
        cvel = b.cvel[:s, self.ids].reshape(-1, 6)
        w = cvel[:, :3]
        lin = cvel[:, 3:] - _cross((b.xipos[:s, self.ids] - b.subtree_com[:s, self.roots]).reshape(-1, 3), w)
        v2 = (lin * lin).sum(axis=1)
        sp = np.sqrt(v2).reshape(s, n)
        rot = b.ximat[:s, self.ids].reshape(-1, 3, 3)
        w_local = np.einsum("nji,nj->ni", rot, w).reshape(s, n, 3)
        v2 = v2.reshape(s, n)
        ke = 0.5 * self.mass * v2 + 0.5 * (self.inertia * w_local * w_local).sum(axis=2)
        np.maximum(self.max_speed, sp.max(axis=0), out=self.max_speed)
        np.maximum(self.ke_max, ke.max(axis=0), out=self.ke_max)
        run.speed.update(zip(self.paths, sp[-1].tolist()))
        run.batch_speed = sp
        np.minimum(self.min_z, x[:, :, 2].min(axis=0), out=self.min_z)

    def finish(self, run: SimRun) -> None:
        data, model = run.data, run.model
        g = np.asarray(model.opt.gravity, dtype=float)
        k_of = {p: k for k, p in enumerate(self.paths)}
        fell = {f["body"]: f["time"] for f in run.res.fall_through}
        for p, i, d in run.bodies:
            p0, q0 = self.start[p]
            p1, q1 = data.xpos[i].copy(), data.xquat[i].copy()
            disp = p1 - p0
            k = k_of.get(p)
            ke = self.kinetic(run, i) if k is not None else 0.0
            pe = -float(model.body_mass[i]) * float(g @ data.xipos[i])
            run.res.bodies[p] = BodyReport(
                p, d, _vec(p0), _vec(q0), _vec(p1), _vec(q1), _vec(disp), float(np.linalg.norm(disp)),
                float(np.linalg.norm(disp[:2])),
                float(self.path_length[k]) if k is not None else 0.0,
                float(self.yaw_total[k]) if k is not None else 0.0,
                float(self.max_speed[k]) if k is not None else 0.0,
                float(self.min_z[k]) if k is not None else float(p0[2]), fell.get(p),
                ke, float(self.ke_max[k]) if k is not None else 0.0, pe)


def fell_out_of_world(path: str, message: str, source: Any) -> BackendNote:
    """The A102 note for a body that left the world without crossing static geometry (which
    :class:`FallThrough` would have seen): ``check.aftersim.bodies_out_of_world`` decides that after the
    run from where the bodies started and ended."""
    return BackendNote(ERROR, registry.FELL_THROUGH, message, source, path)


class FallThrough(Monitor):
    """A dynamic body whose centre of mass sinks through static geometry it started above (A102).

    Every (sample, body, support) triple of a batch is screened at once with numpy; only the
    pairs the screen flags (a body at or near its support's surface) go through
    `_Supports.below`, which decides exactly."""

    batched = True

    SCREEN_SLACK = 1e-9  # m: the screen errs towards asking `below`, never away from it

    def __init__(self, run: SimRun) -> None:
        self.supports = _Supports(run.model, run.data)
        self.below_of = {p: self.supports.above(run.data.xipos[i]) for p, i in run.dyn}  # by centre of mass
        self.fell: dict[str, float] = {}
        planes = {g: (pt, n) for g, pt, n in self.supports.planes}
        boxes = {g: (lo, hi) for g, lo, hi in self.supports.boxes}
        pairs = [(k, p, i, g) for k, (p, i) in enumerate(run.dyn) for g in self.below_of[p]]
        self.pairs = pairs
        self.body = np.array([i for _, _, i, _ in pairs], dtype=int)
        self.is_plane = np.array([g in planes for *_, g in pairs], dtype=bool)
        zero = np.zeros(3)
        self.pt = np.array([planes[g][0] if g in planes else zero for *_, g in pairs], dtype=float).reshape(-1, 3)
        self.nrm = np.array([planes[g][1] if g in planes else zero for *_, g in pairs], dtype=float).reshape(-1, 3)
        self.lo = np.array([boxes[g][0] if g in boxes else zero for *_, g in pairs], dtype=float).reshape(-1, 3)
        self.hi = np.array([boxes[g][1] if g in boxes else zero for *_, g in pairs], dtype=float).reshape(-1, 3)

    def samples(self, run: SimRun, b: Samples) -> None:
        if not self.pairs or len(self.fell) == len(self.below_of):
            return
        margin = run.opt.fall_margin
        c = b.xipos[:b.n, self.body]  # (samples, pairs, 3)
        plane = ((c - self.pt) * self.nrm).sum(axis=2) < -margin + self.SCREEN_SLACK
        box = ((self.lo[:, 0] <= c[..., 0]) & (c[..., 0] <= self.hi[:, 0]) & (self.lo[:, 1] <= c[..., 1])
               & (c[..., 1] <= self.hi[:, 1]) & (c[..., 2] < self.hi[:, 2] - margin + self.SCREEN_SLACK))
        flagged = np.where(self.is_plane, plane, box)
        for k in np.flatnonzero(flagged.any(axis=1)).tolist():
            which = sorted({self.pairs[j][0] for j in np.flatnonzero(flagged[k]).tolist()})
            self._check(run, float(b.t[k]), which, b.xipos[k], k)

    def _check(self, run: SimRun, t: float, which, xipos: np.ndarray, at: int) -> None:
        margin, dyn = run.opt.fall_margin, run.dyn
        for k in which:
            p, i = dyn[k]
            if p in self.fell:
                continue
            for g in self.below_of[p]:
                if self.supports.below(g, xipos[i], margin):
                    self.fell[p] = t
                    gp = run.compiled.names.path("geom", run.model.geom(g).name)
                    run.res.fall_through.append({"body": p, "time": t, "ground": gp, "com": _vec(xipos[i])})
                    run.add(ERROR, registry.FELL_THROUGH, f"{p} fell through static geometry {gp} at t={t:.3f} s", p, at=at)
                    break


@dataclass
class _MateTrack:
    initial_separation: float
    initial_misalignment: float
    max_separation: float
    max_misalignment: float
    max_separation_time: float = 0.0
    max_misalignment_time: float = 0.0
    separation: float = 0.0  # at the last sample
    misalignment: float = 0.0


class MateSeparation(Monitor):
    """How far each mate's connectors drift apart, in position and axis (A103).

    All mates of a batch of samples are measured at once (`_MateArrays`: the same formulas as
    `_monitor_measure`, over arrays); the running maxima are arrays too."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        self.mons = [(m, (run.model.body(m.body0).id, run.model.body(m.body1).id)) for m in run.compiled.monitors]
        self.track: dict[str, _MateTrack] = {}
        for m, ids in self.mons:
            sep, mis = _monitor_measure(m, ids, run.data)
            mis = mis if mis is not None else 0.0
            self.track[m.path] = _MateTrack(sep, mis, sep, mis)
        self.arrays = _MateArrays([m for m, _ in self.mons], [ids for _, ids in self.mons])
        n = len(self.mons)
        self.max_sep = np.array([self.track[m.path].max_separation for m, _ in self.mons], dtype=float)
        self.max_mis = np.array([self.track[m.path].max_misalignment for m, _ in self.mons], dtype=float)
        self.max_sep_t = np.zeros(n)
        self.max_mis_t = np.zeros(n)
        self.last_sep: np.ndarray | None = None
        self.last_mis: np.ndarray | None = None

    def samples(self, run: SimRun, b: Samples) -> None:
        if not self.mons:
            return
        sep, mis = self.arrays.measure(b.xpos[:b.n], b.xmat[:b.n])  # (samples, mates)
        self.last_sep, self.last_mis = sep[-1].copy(), mis[-1].copy()
        t = b.t[:b.n]
        _running_max(self.max_sep, self.max_sep_t, sep, t)
        _running_max(self.max_mis, self.max_mis_t, mis, t)  # -inf where a mate has no axis to compare

    def finish(self, run: SimRun) -> None:
        for k, (m, _) in enumerate(self.mons):
            tr = self.track[m.path]
            tr.max_separation, tr.max_separation_time = float(self.max_sep[k]), float(self.max_sep_t[k])
            tr.max_misalignment, tr.max_misalignment_time = float(self.max_mis[k]), float(self.max_mis_t[k])
            if self.last_sep is not None:
                tr.separation = float(self.last_sep[k])
                tr.misalignment = max(float(self.last_mis[k]), 0.0)
        for m, _ in self.mons:
            tr = self.track[m.path]
            if m.role == "pulled":  # started apart (A016): did the equality close it?
                pulled = tr.separation > run.opt.mate_tol or tr.misalignment > run.opt.angle_tol
            else:
                pulled = tr.max_separation > run.opt.mate_tol or tr.max_misalignment > run.opt.angle_tol
            run.res.mates[m.path] = MateReport(
                m.path, m.kind, m.role, tr.initial_separation, tr.max_separation, tr.max_separation_time,
                tr.initial_misalignment, tr.max_misalignment, tr.max_misalignment_time, pulled,
                tr.separation, tr.misalignment)
            if pulled and m.role == "pulled":
                run.add(WARNING, registry.MATE_DRIFT, f"{m.path} started {tr.initial_separation:.4g} m apart and is still "
                        f"{tr.separation:.4g} m apart at the end (axes {math.degrees(tr.misalignment):.3g} deg)", m.path)
            elif pulled:
                run.add(WARNING, registry.MATE_DRIFT,
                        f"{m.path} came apart: max separation {tr.max_separation:.4g} m at t="
                        f"{tr.max_separation_time:.3f} s, max axis misalignment "
                        f"{math.degrees(tr.max_misalignment):.3g} deg at t={tr.max_misalignment_time:.3f} s", m.path)


class _MateArrays:
    """`_monitor_measure` for every mate at once: (separations, misalignments), the latter -inf
    for distance and ball mates (which have none). Both sides of every mate are one stack: one
    gather of the body frames and a stacked matrix-vector product per vector."""

    def __init__(self, mons: list[MateMonitor], ids: list[tuple[int, int]]) -> None:
        def col(name: str) -> np.ndarray:
            return np.array([np.asarray(getattr(m, name), dtype=float) for m in mons], dtype=float).reshape(-1, 3)

        self.n = len(mons)
        self.bodies = np.array([i for i, _ in ids] + [j for _, j in ids], dtype=int)
        # both sides stacked, as column vectors: each is rotated by its own matrix-vector product
        # (one 3x3 product of all three would round differently: matrix kernels fuse multiply-adds)
        self.pos = np.concatenate([col("pos0"), col("pos1")])[:, :, None]
        self.axis = np.concatenate([col("axis0"), col("axis1")])[:, :, None]
        self.normal = np.concatenate([col("normal0"), col("normal1")])[:, :, None]
        kinds = [m.kind for m in mons]
        self.distance = np.array([k == "distance" for k in kinds])
        self.target = np.array([m.target_distance for m in mons], dtype=float)
        self.perp = np.array([k in ("prismatic", "cylindrical") for k in kinds])
        self.no_axis = np.array([k in ("distance", "ball") for k in kinds])
        self.lock = np.array([k == "lock" for k in kinds])
        self.any_perp, self.any_lock, self.any_distance = self.perp.any(), self.lock.any(), self.distance.any()

    def measure(self, xpos: np.ndarray, xmat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Separations and misalignments (samples x mates) from ``xpos``, ``xmat`` (samples x
        bodies x 3 or 9)."""
        n, s = self.n, xpos.shape[0]
        rot = xmat[:, self.bodies].reshape(s, -1, 3, 3)
        p = xpos[:, self.bodies] + (rot @ self.pos)[..., 0]
        axes = (rot @ self.axis)[..., 0]
        # every (sample, mate) as one row, as the per-sample formulas had one row per mate
        a0, a1 = axes[:, :n].reshape(-1, 3), axes[:, n:].reshape(-1, 3)
        d = (p[:, n:] - p[:, :n]).reshape(-1, 3)
        perp, distance, lock = (np.tile(a, s) for a in (self.perp, self.distance, self.lock))
        if self.any_perp:
            along = (d * a0).sum(axis=1)
            d = np.where(perp[:, None], d - along[:, None] * a0, d)
        sep = np.sqrt((d * d).sum(axis=1))
        if self.any_distance:
            sep = np.where(distance, np.abs(sep - np.tile(self.target, s)), sep)
        mis = _angles(a0, a1)
        if self.any_lock:
            normals = (rot @ self.normal)[..., 0]
            mis = np.where(lock, np.maximum(mis, _angles(normals[:, :n].reshape(-1, 3),
                                                         normals[:, n:].reshape(-1, 3))), mis)
        mis[np.tile(self.no_axis, s)] = -np.inf
        return sep.reshape(s, n), mis.reshape(s, n)


def _units(v: np.ndarray) -> np.ndarray:
    """`unit` row by row (a zero row stays zero)."""
    n = np.sqrt((v * v).sum(axis=1))
    if n.all():
        return v / n[:, None]
    return np.where((n > 0)[:, None], v / np.where(n > 0, n, 1.0)[:, None], v * 0.0)


def _angles(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """`angle_between` row by row."""
    return np.arccos(np.clip((_units(a) * _units(b)).sum(axis=1), -1.0, 1.0))


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product, as `np.cross` (and MuJoCo's `mju_cross`) compute it, without
    np.cross's per-call axis handling."""
    a0, a1, a2 = a[:, 0], a[:, 1], a[:, 2]
    b0, b1, b2 = b[:, 0], b[:, 1], b[:, 2]
    out = np.empty_like(a)
    out[:, 0] = a1 * b2 - a2 * b1
    out[:, 1] = a2 * b0 - a0 * b2
    out[:, 2] = a0 * b1 - a1 * b0
    return out


class JointLimits(Monitor):
    """The largest excursion of each limited hinge / slide joint beyond its range (A105)."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        model = run.model
        self.limited = [j for j in range(model.njnt) if model.jnt_limited[j] and model.jnt_type[j] in (2, 3)]
        self.worst: dict[int, tuple[float, float]] = {}  # joint -> (violation, time), by first excursion
        self.adr = np.array([model.jnt_qposadr[j] for j in self.limited], dtype=int)
        self.lo = np.array([model.jnt_range[j][0] for j in self.limited], dtype=float)
        self.hi = np.array([model.jnt_range[j][1] for j in self.limited], dtype=float)
        self.best = np.zeros(len(self.limited))
        self.best_t = np.zeros(len(self.limited))

    def samples(self, run: SimRun, b: Samples) -> None:
        if not self.limited:
            return
        q = b.qpos[:b.n, self.adr]  # (samples, joints)
        v = np.maximum(np.maximum(self.lo - q, q - self.hi), 0.0)
        fresh = [c for c, j in enumerate(self.limited) if j not in self.worst]
        up = _running_max(self.best, self.best_t, v, b.t[:b.n])
        if not up.any():
            return
        # joints are listed in the order they first left their range (then joint order)
        first = {c: int(np.argmax(v[:, c] > 0.0)) for c in fresh if up[c]}
        for c in sorted(first, key=lambda c: (first[c], c)):
            self.worst[self.limited[c]] = (0.0, 0.0)
        for c in np.flatnonzero(up).tolist():
            self.worst[self.limited[c]] = (self.best[c], float(self.best_t[c]))

    def finish(self, run: SimRun) -> None:
        for j, (v, t) in self.worst.items():
            if v > run.opt.limit_tol:
                jp = run.compiled.names.path("joint", run.model.joint(j).name)
                run.res.joint_limit_violations.append({"mate": jp, "violation": v, "time": t})
                run.add(WARNING, registry.JOINT_LIMIT_EXCEEDED, f"{jp} exceeded its range by {v:.4g} at t={t:.3f} s", jp)


class MotorTracking(Monitor):
    """Mean speed and effort of every actuator over the last 20 % of the run (A106).  A motor run as
    a velocity constraint (mujoco.velocity_constraint) is read on its coordinate: its speed is the
    joint's times its gear, its effort the constraint's force."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        model = run.model
        self.acts = [(a, model.actuator(a.name).id) for a in run.compiled.actuators]
        self.aid = np.array([aid for _, aid in self.acts], dtype=int)
        self.constraint = [k for k, (a, _) in enumerate(self.acts) if a.reference is not None]
        self.c_dof = np.array([int(model.jnt_dofadr[model.joint(self.acts[k][0].joint).id]) for k in self.constraint],
                              dtype=int)
        self.c_gear = np.array([float(self.acts[k][0].gear) for k in self.constraint])
        self.c_ref = np.array([reference_dof(model, self.acts[k][0].reference) for k in self.constraint], dtype=int)
        self.c_offset = np.array([float(self.acts[k][0].offset) for k in self.constraint])
        self.speed_sum = np.zeros(len(self.acts))
        self.force_sum = np.zeros(len(self.acts))
        self.count = 0

    def samples(self, run: SimRun, b: Samples) -> None:
        if not self.acts:
            return
        rows = np.flatnonzero(~(b.t[:b.n] < MOTOR_WINDOW * run.duration))
        if not rows.size:
            return
        speed = b.actuator_velocity[rows][:, self.aid]
        force = b.actuator_force[rows][:, self.aid]
        if self.constraint:
            speed[:, self.constraint] = b.qvel[rows][:, self.c_dof] * self.c_gear
            force[:, self.constraint] = -b.qfrc_constraint[rows][:, self.c_ref] + self.c_offset
        self.speed_sum = _running_sum(self.speed_sum, speed)
        self.force_sum = _running_sum(self.force_sum, force)
        self.count += int(rows.size)

    def finish(self, run: SimRun) -> None:
        for k, (a, _) in enumerate(self.acts):
            n = max(self.count, 1)
            mean_v, mean_f = float(self.speed_sum[k]) / n, float(self.force_sum[k]) / n
            err = abs(mean_v - a.target_speed) if a.target_speed is not None else None
            run.res.motors[a.path] = MotorReport(
                a.path, a.kind, a.target_speed if a.target_speed is not None else a.ctrl, mean_v, mean_f, a.kv, err)
            if err is not None and self.count and err > TRACKING_TOL * abs(a.target_speed) + TRACKING_ABS:
                pct = f" ({100 * err / abs(a.target_speed):.3g} % off)" if a.target_speed else ""
                why = _tracking_why(a)
                run.add(WARNING, registry.MOTOR_OFF_TARGET, f"{a.path}: mean speed {mean_v:.4g} vs target {a.target_speed:g}{pct} over "
                        f"the last 20 % of the run, with a mean effort of {mean_f:.4g}{why}", a.path)


def _tracking_why(a: Any) -> str:
    """Why a velocity motor can be off its target, by how it runs (A106's message)."""
    if a.reference is not None and a.kv is None:
        return "; it runs as a rigid velocity constraint, which falls behind only when the load needs more than its effort range"
    if a.reference is not None:
        return (f"; it runs as a velocity constraint of gain {a.kv:.4g}, so under a load the speed sags by "
                "load / gain")
    if a.kv is not None:
        return f"; its gain is kv = {a.kv:.4g} (A111), so under a load the speed sags by load / kv"
    return ""


_ENERGY_ROWS = 1024  # steps Energy buffers at first (it grows when a batch of samples needs more)


class Energy(Monitor):
    """Total mechanical energy (gravity, springs, motion) against the work the actuators did (A134).

    Nothing but an actuator (or a kinematic body) adds energy to a scene: contacts, damping and
    friction only take it away.  So E(t) - E(0) - W_actuators(t) must stay <= 0 up to the
    integrator's error; a gain above ``energy_tol`` of the run's energy scale (its largest kinetic
    energy plus the actuators' work, at least lifting every body by a millimetre) is a finding."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        data, model = run.data, run.model
        # velocity constraints' references (mujoco.velocity_constraint): their motion is not the scene's
        # and the kinematic bodies' armature (mujoco.kinematic): only their own mass's motion counts
        self.ref_dofs = np.array([reference_dof(model, a.reference) for a in run.compiled.actuators
                                  if a.reference is not None] + kinematic_dofs(run.compiled, model), dtype=int)
        self.initial = self._total(run)
        self.max_kinetic = float(data.energy[1]) - reference_energy(model, data.qvel, self.ref_dofs)
        self.work = 0.0
        self.work_abs = 0.0
        self.gain, self.gain_time = 0.0, 0.0
        self.drift, self.drift_time = 0.0, 0.0  # largest |E - E0 - W|, either way
        # a conservative, contact-free scene must keep its energy, not only not gain any
        self.conservative = not_conservative(model) is None
        masses = [float(model.body_mass[i]) for _, i in run.dyn]
        self.floor = sum(masses) * float(np.linalg.norm(model.opt.gravity)) * 1e-3
        # a kinematic body pushing things, or a controller setting velocities, does work not counted here
        self.checked = not run.movers and not run.controlled
        # the actuators, as arrays: the work they do is summed over every step (see after_step)
        acts = [a for a in run.compiled.actuators]
        self.per_step = bool(acts)
        self.dof = np.array([int(model.jnt_dofadr[model.joint(a.joint).id]) for a in acts], dtype=int)
        self.gear = np.array([float(a.gear) for a in acts])
        self.kv = np.array([float(a.kv) if a.kv is not None else 0.0 for a in acts])
        # a velocity constraint's force is the constraint's (-qfrc_constraint of its reference), per step
        self.is_constraint = np.array([a.reference is not None for a in acts], dtype=bool)
        self.c_ref = np.array([reference_dof(model, a.reference) if a.reference is not None else 0 for a in acts],
                              dtype=int)
        self.c_offset = np.array([float(a.offset) for a in acts])  # a constraint motor's constant effort
        ids = [model.actuator(a.name).id for a in acts]
        self.aid = np.array(ids, dtype=int)
        self.limited = np.array([bool(model.actuator_forcelimited[i]) for i in ids], dtype=bool)
        self.lo = np.array([float(model.actuator_forcerange[i][0]) if model.actuator_forcelimited[i] else -np.inf
                            for i in ids])
        self.hi = np.array([float(model.actuator_forcerange[i][1]) if model.actuator_forcelimited[i] else np.inf
                            for i in ids])
        # per step only the raw readings are copied (whole qvel and ctrl rows); the work of all the
        # steps since the last batch is computed at once when the monitors see a batch of samples
        # (and at the end): the same arithmetic, element by element and summed step by step in the
        # same order.  The speed before a step is the speed after the one before it.
        self.h = float(model.opt.timestep)
        self._qvel, self._ctrl_now, self._qfrc_c = data.qvel, data.ctrl, data.qfrc_constraint
        self._last = data.qvel.copy()
        self._qv = np.zeros((_ENERGY_ROWS, model.nv))
        self._ct = np.zeros((_ENERGY_ROWS, model.nu))
        self._fc = np.zeros((_ENERGY_ROWS, len(acts))) if self.is_constraint.any() else None
        self._rows = 0
        self._base = 0  # steps before the first buffered row

    def _total(self, run: SimRun) -> float:
        return float(run.data.energy[0] + run.data.energy[1]) - reference_energy(run.model, run.data.qvel,
                                                                                 self.ref_dofs)

    def after_step(self, run: SimRun) -> None:
        k = self._rows
        if k == len(self._qv):
            self._qv = np.concatenate([self._qv, np.zeros_like(self._qv)])
            self._ct = np.concatenate([self._ct, np.zeros_like(self._ct)])
            if self._fc is not None:
                self._fc = np.concatenate([self._fc, np.zeros_like(self._fc)])
        self._qv[k] = self._qvel
        self._ct[k] = self._ctrl_now
        if self._fc is not None:
            self._fc[k] = -self._qfrc_c[self.c_ref] + self.c_offset
        self._rows = k + 1

    def _add_work(self) -> np.ndarray:
        """The work of the steps recorded since the last call, added to ``work``; returns the
        work done after each of them, the work before them first.  A velocity servo is integrated
        implicitly, so its force is kv (ctrl - v) at the velocity the step ends with, unless it
        saturates (then MuJoCo uses the clamped explicit force); a motor's force is its clamped
        control."""
        k = self._rows
        if not k:
            return np.array([self.work])
        # C order (indexing columns gives Fortran order): `sum(axis=1)` below then adds each row's
        # actuators in the same (pairwise) order as on the rows of one step
        q1 = np.ascontiguousarray(self._qv[:k][:, self.dof])
        q0 = np.concatenate([self._last[self.dof][None], q1[:-1]])
        self._last[:] = self._qv[k - 1]
        self._rows = 0
        self._base += k
        v_old = self.gear * q0
        v_new = self.gear * q1
        ctrl = np.ascontiguousarray(self._ct[:k][:, self.aid])
        explicit = np.where(self.kv > 0, self.kv * (ctrl - v_old), ctrl)
        clamped = np.clip(explicit, self.lo, self.hi)
        saturated = self.limited & (clamped != explicit)
        implicit = np.where(self.kv > 0, self.kv * (ctrl - v_new), ctrl)
        force = np.where(saturated, clamped, np.clip(implicit, self.lo, self.hi))
        if self._fc is not None:
            force = np.where(self.is_constraint, self._fc[:k], force)
        w = force * 0.5 * (v_old + v_new) * self.h
        cum = np.add.accumulate(np.concatenate([[self.work], w.sum(axis=1)]))
        self.work = float(cum[-1])
        self.work_abs = float(np.add.accumulate(np.concatenate([[self.work_abs], np.abs(w).sum(axis=1)]))[-1])
        return cum

    def samples(self, run: SimRun, b: Samples) -> None:
        n = b.n
        base = self._base
        cum = self._add_work()
        work = cum[b.step[:n] - base] if self.per_step else np.full(n, self.work)
        ke = b.energy[:n, 1] - reference_energy(run.model, b.qvel[:n], self.ref_dofs)
        top = np.where(ke > self.max_kinetic, ke, -np.inf).max()
        if top > self.max_kinetic:
            self.max_kinetic = float(top)
        g = b.energy[:n, 0] + ke - self.initial - work
        a = np.abs(g)
        k = int(a.argmax())
        if a[k] > self.drift:
            self.drift, self.drift_time = float(a[k]), float(b.t[k])
        cand = np.where(g > self.gain, g, -np.inf)
        i = int(cand.argmax())
        if cand[i] > self.gain:
            self.gain, self.gain_time = float(cand[i]), float(b.t[i])

    def finish(self, run: SimRun) -> None:
        self._add_work()
        scale = max(self.max_kinetic + self.work_abs, self.floor, 1e-12)
        run.res.energy = {"initial_total": self.initial, "final_total": self._total(run),
                          "max_kinetic": self.max_kinetic, "actuator_work": self.work,
                          "max_unexplained_gain": self.gain, "max_unexplained_gain_time": self.gain_time,
                          "max_drift": self.drift, "max_drift_time": self.drift_time,
                          "conservative": self.conservative, "checked": self.checked}
        if not self.checked:
            return
        if self.conservative and self.drift > run.opt.drift_tol * scale + self.floor:
            m = run.model
            name = {int(run.mujoco.mjtIntegrator.mjINT_RK4): "rk4", int(run.mujoco.mjtIntegrator.mjINT_EULER): "euler",
                    int(run.mujoco.mjtIntegrator.mjINT_IMPLICIT): "implicit"}.get(int(m.opt.integrator), "implicitfast")
            run.add(WARNING, registry.ENERGY_GAIN,
                    f"the energy of this conservative scene (no contacts, damping, friction, limits or motors) drifted "
                    f"by {self.drift:.4g} J ({100 * self.drift / scale:.3g} % of its energy scale {scale:.4g} J; "
                    f"tolerance {100 * run.opt.drift_tol:g} %), largest at t={self.drift_time:.3f} s with the "
                    f"{name} integrator at a {float(m.opt.timestep):g} s step: use --integrator rk4 or a shorter "
                    f"--timestep", None)
            return
        if self.gain <= run.opt.energy_tol * scale + self.floor:
            return
        worst = None
        bodies = run.res.bodies
        if bodies:
            worst = max(bodies, key=lambda b: bodies[b].max_kinetic_energy if bodies[b].dynamic else -1.0)
        run.add(WARNING, registry.ENERGY_GAIN,
                f"the scene gained {self.gain:.4g} J of energy that no motor supplied "
                f"({100 * self.gain / scale:.3g} % of its energy scale {scale:.4g} J), largest at "
                f"t={self.gain_time:.3f} s" + (f"; the most energetic body is {worst}" if worst else "")
                + ": the motion is not physical (too stiff a spring or mate, an overlap pushed apart, a mate that "
                "started apart pulled together, or a gap in the MuJoCo mapping)", worst)


class Plausibility(Monitor):
    """A body faster than anything in the scene explains (A135): its start speed, free fall over
    the whole run, the motors' target speeds over the scene's size, and the springs' initial energy,
    with a margin of 2."""

    batched = True

    def __init__(self, run: SimRun) -> None:
        model, data = run.model, run.data
        dyn = run.dyn
        self.reported: set[str] = set()
        if not dyn:
            self.bound = math.inf
            return
        g = float(np.linalg.norm(model.opt.gravity))
        v0 = max((run.speed.get(p, 0.0) for p, _ in dyn), default=0.0)
        centre = np.mean([data.xipos[i] for _, i in dyn], axis=0)
        radius = max(float(np.linalg.norm(data.xipos[i] - centre)) for _, i in dyn)
        radius += max((float(model.geom_rbound[k]) for k in range(model.ngeom)
                       if model.geom_bodyid[k] in {i for _, i in dyn}), default=0.0)
        motors = 0.0
        for a in run.compiled.actuators:
            if a.kind == "velocity_motor":
                jid = model.joint(a.joint).id
                rot = model.jnt_type[jid] == 3
                motors = max(motors, abs(a.target_speed) * (radius if rot else 1.0))
        gpe = sum(-float(model.body_mass[i]) * float(np.asarray(model.opt.gravity) @ data.xipos[i])
                  for _, i, _d in run.bodies)
        spring_pe = max(float(data.energy[0]) - gpe, 0.0)
        m_min = min(float(model.body_mass[i]) for _, i in dyn) or 1e-9
        springs = math.sqrt(2.0 * spring_pe / m_min) if spring_pe > 0 else 0.0
        self.explained = v0 + g * run.duration + motors + springs
        self.parts = (v0, g * run.duration, motors, springs)
        self.bound = 2.0 * self.explained + 1.0

    def samples(self, run: SimRun, b: Samples) -> None:
        sp = run.batch_speed  # (samples, moving bodies), from BodyMotion
        if sp is None or not run.dyn or len(self.reported) == len(run.dyn):
            return
        cols = [run.moving_col[p] for p, _ in run.dyn]
        over = sp[:, cols] > self.bound
        if not over.any():
            return
        for k in np.flatnonzero(over.any(axis=1)).tolist():
            for c in np.flatnonzero(over[k]).tolist():
                p = run.dyn[c][0]
                if p in self.reported:
                    continue
                self.reported.add(p)
                v, t = float(sp[k, cols[c]]), float(b.t[k])
                v0, ff, mot, spr = self.parts
                run.res.implausible_speeds.append({"body": p, "time": t, "speed": v, "bound": self.bound})
                run.add(WARNING, registry.IMPLAUSIBLE_SPEED,
                        f"{p} reached {v:.4g} m/s at t={t:.3f} s, more than the scene explains "
                        f"({self.explained:.3g} m/s: start {v0:.3g} + free fall over the run {ff:.3g} + motors "
                        f"{mot:.3g} + springs {spr:.3g}; twice that plus 1 m/s is tolerated)", p, at=k)


# Everything watched during a run, in the order their findings are reported.  A new check of the
# motion is a Monitor subclass added here.
MONITORS: tuple[type[Monitor], ...] = (BadControl, Trace, BodyMotion, FallThrough, MateSeparation, JointLimits,
                                       MotorTracking, Plausibility, Energy)


def simulate_compiled(compiled: CompiledScene, duration: float = 5.0, controller: Any = None,
                      **options: Any) -> SimulationResult:
    """Run ``compiled`` for ``duration`` seconds, sampling every ``sample_dt`` with the monitors;
    ``options`` are the fields of :class:`SimOptions`.

    ``controller(t, model, data)``, when given, is called before every step with the state at time
    ``t`` (between ``mj_step1`` and ``mj_step2``, so positions and velocities are current) and once
    more after the last step; what it writes (``data.ctrl``, ...) acts from that step on."""
    import mujoco

    opt = SimOptions(**options)
    t_wall = time.perf_counter()
    # the limit covers everything from here (and, given a deadline, the file's checks before it)
    deadline = opt.deadline if opt.deadline is not None else (
        t_wall + opt.timeout if opt.timeout is not None else None)
    scene = compiled.scene
    res = SimulationResult(False, scene.name, float(duration), 0.0, 0, float(scene.timestep), 0.0,
                           compiled.compile_ms, notes=list(compiled.notes))
    if not compiled.ok:
        return res
    run, stepper = _set_up(mujoco, compiled, res, opt, float(duration), controller)
    if not initial_penetrations(run, deadline):
        res.wall_time_s = time.perf_counter() - t_wall
        return res
    loop = _Loop(run, stepper, controller, deadline)
    loop.step_to_end()
    if controller is not None and res.blowup is None:
        controller(loop.done * loop.h, run.model, run.data)  # the final state (mj_forward ran after the last chunk)
    res.wall_time_s = time.perf_counter() - t_wall
    loop.finish()
    return res


def _set_up(mujoco: Any, compiled: CompiledScene, res: SimulationResult, opt: SimOptions, duration: float,
            controller: Any) -> tuple[SimRun, Stepper]:
    """The MuJoCo data at the scene's initial keyframe, the bodies watched, and how a step is taken."""
    model, names = compiled.model, compiled.names
    res.timestep = float(model.opt.timestep)
    res.integrator = compiled.integrator
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("initial").id)
    mujoco.mj_forward(model, data)
    bodies: list[tuple[str, int, bool]] = []
    for b in compiled.scene.bodies:
        n = names.name("body", b.path)
        if n is not None and n not in [x[0] for x in bodies]:
            bodies.append((b.path, model.body(n).id, b.is_dynamic))
    run = SimRun(mujoco, compiled, model, data, res, opt, duration, bodies)
    stepper = Stepper(mujoco, compiled, model, data)
    run.movers = stepper.movers
    attach = getattr(getattr(controller, "runtime", None), "attach_movers", None)
    if attach is not None:  # a scenario's inputs may drive kinematic bodies
        attach(stepper.movers, stepper.engagements, stepper.lag)
    run.controlled = controller is not None
    return run, stepper


class _Loop:
    """The monitored stepping of one run: chunks of steps, each ended by a sample the monitors see.

    Without a controller or moving kinematic bodies, the state at a sample is computed by the next
    step's first half (mj_step1: positions and velocities, exactly what mj_forward would compute for
    them), instead of an extra mj_forward per sample; the step is then finished with mj_step2
    (``split``; the step is then ``primed``).  A controller reads acceleration-stage data (actuator
    forces) and a kinematic body is placed before each step, so those runs use mj_forward.  RK4:
    mj_step2 would integrate with Euler, so an RK4 run takes whole mj_steps."""

    def __init__(self, run: SimRun, stepper: Stepper, controller: Any, deadline: float | None) -> None:
        mujoco, model = run.mujoco, run.model
        self.run, self.stepper, self.controller, self.deadline = run, stepper, controller, deadline
        self.monitors: list[Monitor] = [m(run) for m in MONITORS if m is not Trace or run.opt.record]
        self.blowup = BlowUp(run)
        self.per_step = [m for m in self.monitors if m.per_step]
        self.batched = [m for m in self.monitors if m.batched]
        self.plain = [m for m in self.monitors if not m.batched and type(m).sample is not Monitor.sample]
        self.batch = Samples(run.data)
        self.h = h = float(model.opt.timestep)
        self.n_steps = max(1, int(round(run.duration / h)))
        self.chunk = max(1, int(round(run.opt.sample_dt / h)))
        # a motor with an effort offset is corrected after each step (velocity_constraint.Lag): the stepper's path
        self.own_steps = stepper.lag.active
        self.split = (controller is None and not run.movers and not self.own_steps
                      and int(model.opt.integrator) != int(mujoco.mjtIntegrator.mjINT_RK4))
        # MotorTracking reads actuator_force
        self.forces_from = MOTOR_WINDOW * run.duration if model.nu else math.inf
        self.primed = False  # mj_step1 of the next step has run
        self.fast_after = None  # the usual run: only one monitor (Energy) records something per step
        if (controller is None and not run.movers and not self.own_steps and len(self.per_step) == 1
                and type(self.per_step[0]).before_step is Monitor.before_step):
            self.fast_after = self.per_step[0].after_step
        self.done = 0

    def step_to_end(self) -> None:
        """Step to the end, the time limit or a blow-up, sampling after every chunk."""
        run, batch = self.run, self.batch
        while self.done < self.n_steps:
            if self.deadline is not None and time.perf_counter() > self.deadline:
                self._stop_at_deadline()
                break
            self._steps(min(self.chunk, self.n_steps - self.done))
            t = self.done * self.h
            if self._blew_up(t):
                break
            self._state_at_sample(t)
            for m in self.plain:
                m.sample(run, t)
            if batch.record(t, self.done):
                batch.flush(run, self.batched)
        batch.flush(run, self.batched)

    def _steps(self, k: int) -> None:
        """Advance ``k`` steps (the first one finishes a primed step), with the per-step monitors."""
        run, mujoco, model, data = self.run, self.run.mujoco, self.run.model, self.run.data
        per_step = self.per_step
        if self.primed:
            mujoco.mj_step2(model, data)
            self.done += 1
            k -= 1
            self.primed = False
            for m in per_step:
                m.after_step(run)
        fast_after = self.fast_after
        if fast_after is not None:
            for _ in range(k):
                mujoco.mj_step(model, data)
                fast_after(run)
            self.done += k
        elif run.movers or per_step or self.controller is not None or self.own_steps:
            stepper, controller, done = self.stepper, self.controller, self.done
            for _ in range(k):
                for m in per_step:
                    m.before_step(run)
                stepper.step(done, controller)
                done += 1
                for m in per_step:
                    m.after_step(run)
            self.done = done
        elif k:
            mujoco.mj_step(model, data, nstep=k)
            self.done += k

    def _state_at_sample(self, t: float) -> None:
        """The position- and velocity-dependent data of the state at ``t``, for the monitors: by the
        next step's mj_step1 when the run is ``split`` (and MuJoCo's own checks will not reset),
        otherwise by mj_forward (mj_step leaves it one step behind)."""
        run, mujoco = self.run, self.run.mujoco
        if self.split and self.done < self.n_steps and self.blowup.bounded:
            for m in self.per_step:
                m.before_step(run)
            mujoco.mj_step1(run.model, run.data)
            self.primed = True
            if t >= self.forces_from:
                mujoco.mj_fwdActuation(run.model, run.data)
        else:
            mujoco.mj_forward(run.model, run.data)

    def _blew_up(self, t: float) -> bool:
        run = self.run
        reason = self.blowup.check(run)
        if reason is None:
            return False
        run.mujoco.mj_forward(run.model, run.data)  # what the report reads of the final state
        self.batch.flush(run, self.batched)  # the speeds before the blow-up
        self.blowup.report(run, t, self.done, reason)
        return True

    def _stop_at_deadline(self) -> None:
        run = self.run
        if self.primed:
            run.mujoco.mj_forward(run.model, run.data)
        self.batch.flush(run, self.batched)
        run.add(ERROR, registry.SIMULATION_TIMEOUT, f"the simulation was stopped by the time limit ({_limit(run.opt)}) "
                f"at t={self.done * self.h:.3f} s of {run.duration:g} s; the motion after that is not checked", None)

    def finish(self) -> None:
        """The result's totals, every monitor's part of it, and whether the run ended early."""
        run, res, h = self.run, self.run.res, self.h
        res.steps = self.done
        res.simulated_time = self.done * h
        for m in self.monitors:
            m.finish(run)
        timed_out = any(n.code == registry.SIMULATION_TIMEOUT for n in res.notes)
        if res.blowup is None and not timed_out and res.simulated_time < run.duration - h / 2:
            run.add(INFO, registry.SIMULATION_INCOMPLETE, f"simulated {res.simulated_time:.3f} of {run.duration:g} s", None)
        res.ok = not any(n.severity == ERROR for n in res.notes)
