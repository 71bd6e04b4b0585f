"""Run a compiled scene in MuJoCo and report what happened, in plain JSON-ready data."""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from plxtools.check.mj_compile import VISUAL_GROUP, CompiledScene, MateMonitor
from plxtools.check.mj_math import angle_between, yaw_of_mat
from plxtools.check.mj_notes import ERROR, INFO, WARNING, BackendNote


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
    max_speed: float  # m/s, body origin
    min_z: float
    fell_through_time: float | None = None


@dataclass(slots=True)
class MateReport:
    path: str
    kind: str
    role: str  # tree (a MuJoCo joint) | loop (equality) | distance | open (not enforced)
    initial_separation: (
        float  # m (perpendicular to the axis for prismatic/cylindrical; |d - target| for distance)
    )
    max_separation: float
    max_separation_time: float
    initial_misalignment: float  # rad between the main axes (and normals for a lock)
    max_misalignment: float
    max_misalignment_time: float
    pulled_apart: bool


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
    blowup: dict[str, Any] | None = None
    penetrations: list[dict[str, Any]] = field(default_factory=list)
    fall_through: list[dict[str, Any]] = field(default_factory=list)
    joint_limit_violations: list[dict[str, Any]] = field(default_factory=list)
    bodies: dict[str, BodyReport] = field(default_factory=dict)
    mates: dict[str, MateReport] = field(default_factory=dict)
    motors: dict[str, MotorReport] = field(default_factory=dict)
    energy: dict[str, float] = field(default_factory=dict)
    notes: list[BackendNote] = field(default_factory=list)
    trace: dict[str, Any] | None = None  # record=True: {"time": [...], "joints": {mate path: [q...]}}

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


def simulate_compiled(
    compiled: CompiledScene,
    duration: float = 5.0,
    *,
    sample_dt: float = 0.01,
    penetration_tol: float = 0.005,
    max_speed: float = 1e3,
    fall_margin: float = 0.01,
    mate_tol: float = 5e-3,
    angle_tol: float = 0.05,
    limit_tol: float = 0.02,
    record: bool = False,
) -> SimulationResult:
    import mujoco

    scene = compiled.scene
    notes = list(compiled.notes)
    h = float(scene.timestep)
    res = SimulationResult(
        False, scene.name, float(duration), 0.0, 0, h, 0.0, compiled.compile_ms, notes=notes
    )
    if not compiled.ok:
        return res
    model, names = compiled.model, compiled.names
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key("initial").id)
    mujoco.mj_forward(model, data)

    def src(path: str | None) -> Any:
        return names.sources.get(path) if path else None

    def add(sev: str, code: str, msg: str, path: str | None) -> None:
        notes.append(BackendNote(sev, code, msg, src(path), path))

    # bodies
    bodies: list[tuple[str, int, bool]] = []
    for b in scene.bodies:
        n = names.name("body", b.path)
        if n is not None and n not in [x[0] for x in bodies]:
            bodies.append((b.path, model.body(n).id, b.is_dynamic))
    init = {p: (data.xpos[i].copy(), data.xquat[i].copy()) for p, i, _ in bodies}
    dyn = [(p, i) for p, i, d in bodies if d]

    # initial penetration
    deepest: dict[tuple[int, int], tuple[float, int, list[float]]] = {}
    for k in range(data.ncon):
        c = data.contact[k]
        if c.dist < -penetration_tol:
            key = (int(c.geom[0]), int(c.geom[1]))
            depth, count, pos = deepest.get(key, (0.0, 0, []))
            deepest[key] = (max(depth, float(-c.dist)), count + 1, _vec(c.pos) if -c.dist > depth else pos)
    for (ga, gb), (depth, count, pos) in deepest.items():
        g1, g2 = (names.path("geom", model.geom(g).name) for g in (ga, gb))
        res.penetrations.append({"geom1": g1, "geom2": g2, "depth": depth, "contacts": count, "pos": pos})
        add(WARNING, "A104", f"{g1} and {g2} overlap by {depth:.4g} m at t=0", g1)

    supports = _Supports(model, data)
    below_of = {p: supports.above(data.xipos[i]) for p, i in dyn}  # by centre of mass
    fell: dict[str, float] = {}

    mons = []
    for m in compiled.monitors:
        mons.append((m, (model.body(m.body0).id, model.body(m.body1).id)))
    mate_state: dict[str, list[float]] = {}
    for m, ids in mons:
        sep, mis = _monitor_measure(m, ids, data)
        mate_state[m.path] = [
            sep,
            sep,
            0.0,
            mis if mis is not None else 0.0,
            mis if mis is not None else 0.0,
            0.0,
        ]

    limited = [j for j in range(model.njnt) if model.jnt_limited[j] and model.jnt_type[j] in (2, 3)]
    limit_max: dict[int, tuple[float, float]] = {}

    path_len = {p: 0.0 for p, _ in dyn}
    last_pos = {p: data.xpos[i].copy() for p, i in dyn}
    yaw_last = {p: yaw_of_mat(data.xmat[i].reshape(3, 3)) for p, i in dyn}
    yaw_total = {p: 0.0 for p, _ in dyn}
    vmax = {p: 0.0 for p, _ in dyn}
    zmin = {p: float(data.xpos[i][2]) for p, i in dyn}
    act_ids = [(a, model.actuator(a.name).id) for a in compiled.actuators]
    act_sum = {a.path: [0.0, 0.0, 0] for a, _ in act_ids}
    energy0 = float(data.energy[0] + data.energy[1])
    ke_max = float(data.energy[1])

    traced: list[tuple[str, int, int]] = []  # (key, qpos address, sign) in the OpenPLX coordinate
    if record:
        for mate_path, jnames in compiled.joints.items():
            for jn in jnames:
                j = model.joint(jn)
                if model.jnt_type[j.id] in (2, 3):
                    key = mate_path + (jn[jn.rfind(":") :] if len(jnames) > 1 else "")
                    traced.append((key, int(model.jnt_qposadr[j.id]), compiled.joint_sign[mate_path]))
        res.trace = {"time": [0.0], "joints": {k: [s * float(data.qpos[a])] for k, a, s in traced}}

    n_steps = max(1, int(round(duration / h)))
    chunk = max(1, int(round(sample_dt / h)))
    warn_ids = [
        mujoco.mjtWarning.mjWARN_BADQPOS,
        mujoco.mjtWarning.mjWARN_BADQVEL,
        mujoco.mjtWarning.mjWARN_BADQACC,
    ]
    warn0 = sum(int(data.warning[w].number) for w in warn_ids)
    badctrl0 = int(data.warning[mujoco.mjtWarning.mjWARN_BADCTRL].number)
    done = 0
    t_wall = time.perf_counter()
    last_good_speed: dict[str, float] = {}
    vel6 = np.zeros(6)
    while done < n_steps:
        k = min(chunk, n_steps - done)
        mujoco.mj_step(model, data, nstep=k)
        mujoco.mj_forward(model, data)  # mj_step leaves positions-derived data one step behind
        done += k
        t = done * h
        warns = sum(int(data.warning[w].number) for w in warn_ids)
        finite = bool(np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)))
        vel_max = float(np.max(np.abs(data.qvel))) if finite and model.nv else 0.0
        if warns > warn0 or not finite or vel_max > max_speed:
            reason = (
                "MuJoCo reported a NaN/Inf/huge state (mjWARN_BADQPOS/QVEL/QACC) and reset"
                if warns > warn0
                else (
                    "NaN or Inf in the state"
                    if not finite
                    else f"generalised velocity {vel_max:.3g} exceeds {max_speed:g}"
                )
            )
            worst = max(last_good_speed, key=lambda p: last_good_speed[p]) if last_good_speed else None
            res.blowup = {"time": t, "step": done, "reason": reason, "fastest_body": worst}
            add(
                ERROR,
                "A101",
                f"numerical blow-up at t={t:.3f} s: {reason}"
                + (f" (fastest body before: {worst})" if worst else ""),
                worst,
            )
            break
        # samples
        if res.trace is not None:
            res.trace["time"].append(t)
            for key, adr, sgn in traced:
                res.trace["joints"][key].append(sgn * float(data.qpos[adr]))
        for p, i in dyn:
            x = data.xpos[i]
            path_len[p] += float(np.linalg.norm(x - last_pos[p]))
            last_pos[p] = x.copy()
            y = yaw_of_mat(data.xmat[i].reshape(3, 3))
            dy = (y - yaw_last[p] + math.pi) % (2 * math.pi) - math.pi
            yaw_total[p] += dy
            yaw_last[p] = y
            mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, i, vel6, 0)
            sp = float(np.linalg.norm(vel6[3:]))
            vmax[p] = max(vmax[p], sp)
            last_good_speed[p] = sp
            zmin[p] = min(zmin[p], float(x[2]))
            if p not in fell:
                for g in below_of[p]:
                    if supports.below(g, data.xipos[i], fall_margin):
                        fell[p] = t
                        gp = names.path("geom", model.geom(g).name)
                        res.fall_through.append(
                            {"body": p, "time": t, "ground": gp, "com": _vec(data.xipos[i])}
                        )
                        add(
                            ERROR,
                            "A102",
                            f"{p} fell through static geometry {gp} at t={t:.3f} s",
                            p,
                        )
                        break
        for m, ids in mons:
            sep, mis = _monitor_measure(m, ids, data)
            st = mate_state[m.path]
            if sep > st[1]:
                st[1], st[2] = sep, t
            if mis is not None and mis > st[4]:
                st[4], st[5] = mis, t
        for j in limited:
            q = float(data.qpos[model.jnt_qposadr[j]])
            lo, hi = model.jnt_range[j]
            v = max(lo - q, q - hi, 0.0)
            if v > limit_max.get(j, (0.0, 0.0))[0]:
                limit_max[j] = (v, t)
        if t >= 0.8 * duration:
            for a, aid in act_ids:
                s = act_sum[a.path]
                s[0] += float(data.actuator_velocity[aid])
                s[1] += float(data.actuator_force[aid])
                s[2] += 1
        ke_max = max(ke_max, float(data.energy[1]))
    res.wall_time_s = time.perf_counter() - t_wall
    if int(data.warning[mujoco.mjtWarning.mjWARN_BADCTRL].number) > badctrl0:
        add(
            ERROR,
            "A107",
            "MuJoCo rejected a NaN/huge actuator control (> 1e10) and zeroed the controls",
            None,
        )
    res.steps = done
    res.simulated_time = done * h

    for p, i, d in bodies:
        p0, q0 = init[p]
        p1, q1 = data.xpos[i].copy(), data.xquat[i].copy()
        disp = p1 - p0
        res.bodies[p] = BodyReport(
            p,
            d,
            _vec(p0),
            _vec(q0),
            _vec(p1),
            _vec(q1),
            _vec(disp),
            float(np.linalg.norm(disp)),
            float(np.linalg.norm(disp[:2])),
            path_len.get(p, 0.0),
            yaw_total.get(p, 0.0),
            vmax.get(p, 0.0),
            zmin.get(p, float(p0[2])),
            fell.get(p),
        )
    for m, _ in mons:
        st = mate_state[m.path]
        pulled = st[1] > mate_tol or st[4] > angle_tol
        res.mates[m.path] = MateReport(
            m.path, m.kind, m.role, st[0], st[1], st[2], st[3], st[4], st[5], pulled
        )
        if pulled:
            add(
                WARNING,
                "A103",
                f"{m.path} came apart: max separation {st[1]:.4g} m at t={st[2]:.3f} s, "
                f"max axis misalignment {math.degrees(st[4]):.3g} deg at t={st[5]:.3f} s",
                m.path,
            )
    for j, (v, t) in limit_max.items():
        if v > limit_tol:
            jp = names.path("joint", model.joint(j).name)
            res.joint_limit_violations.append({"mate": jp, "violation": v, "time": t})
            add(WARNING, "A105", f"{jp} exceeded its range by {v:.4g} at t={t:.3f} s", jp)
    for a, _ in act_ids:
        s = act_sum[a.path]
        n = max(s[2], 1)
        mean_v, mean_f = s[0] / n, s[1] / n
        err = abs(mean_v - a.target_speed) if a.target_speed is not None else None
        res.motors[a.path] = MotorReport(
            a.path,
            a.kind,
            a.target_speed if a.target_speed is not None else a.ctrl,
            mean_v,
            mean_f,
            a.kv,
            err,
        )
        if err is not None and s[2] and err > 0.1 * abs(a.target_speed) + 0.05:
            add(
                WARNING,
                "A106",
                f"{a.path}: mean speed {mean_v:.4g} vs target {a.target_speed:g} over the last 20 % of the run",
                a.path,
            )
    res.energy = {
        "initial_total": energy0,
        "final_total": float(data.energy[0] + data.energy[1]),
        "max_kinetic": ke_max,
    }
    if res.blowup is None and res.simulated_time < duration - h / 2:
        add(INFO, "A108", f"simulated {res.simulated_time:.3f} of {duration:g} s", None)
    res.ok = not any(n.severity == ERROR for n in notes)
    return res
