"""Which MuJoCo integrator a scene runs with.

``implicitfast`` (MuJoCo's recommendation) integrates joint damping and velocity servos
implicitly, which is what keeps stiff motors and dampers stable; but it is only first order, and a
conservative system drifts: a frictionless double pendulum loses or gains several percent of its
energy over ten seconds at the default 2 ms step.  RK4 is fourth order and keeps such a scene's
energy to a few parts per million, but it integrates damping and servos explicitly, and contacts,
joint limits and equality constraints are impulsive or soft-constraint forces that RK4's sub-steps
do not improve.  So ``auto`` picks RK4 exactly for the scenes where it pays: **conservative and
contact-free** (no velocity servo, no joint damping or friction, no joint limit, no equality
constraint, no tendon and no pair of geometries that could ever touch), and ``implicitfast``
otherwise.  ``plx check --integrator`` and the config key ``check.integrator`` choose one by name.
"""

from __future__ import annotations

from typing import Any

CHOICES = ("auto", "implicitfast", "implicit", "rk4", "euler")
_MAX_GEOM_PAIRS = 200_000  # above that, the contact-free test is not attempted (assume contacts)


def mujoco_integrator(mj: Any, name: str) -> Any:
    return {"implicitfast": mj.mjtIntegrator.mjINT_IMPLICITFAST, "implicit": mj.mjtIntegrator.mjINT_IMPLICIT,
            "rk4": mj.mjtIntegrator.mjINT_RK4, "euler": mj.mjtIntegrator.mjINT_EULER}[name]


def not_conservative(model: Any) -> str | None:
    """Why the compiled scene is not conservative and contact-free (the first reason), or None."""
    import numpy as np

    if model.nu and np.any(model.actuator_biasprm[:, 2] != 0.0):
        return "a velocity motor (a servo, integrated implicitly)"
    if np.any(model.dof_damping != 0.0):
        return "joint damping"
    if np.any(model.dof_frictionloss != 0.0):
        return "joint friction"
    if model.njnt and np.any(model.jnt_limited != 0):
        return "a joint limit"
    if model.neq:
        return "an equality constraint (a loop closure, a gear or a hinge actuator)"
    if model.ntendon:
        return "a tendon"
    if model.npair:
        return "contacts"
    if _contacts_possible(model):
        return "contacts"
    return None


def _contacts_possible(model: Any) -> bool:
    """Whether any two geometries can ever collide: both with matching contype / conaffinity, on
    different bodies, not both fixed to the world, not a parent and its child (MuJoCo filters
    those), and not excluded."""
    geoms = [g for g in range(model.ngeom) if model.geom_contype[g] or model.geom_conaffinity[g]]
    if len(geoms) * (len(geoms) - 1) // 2 > _MAX_GEOM_PAIRS:
        return True
    excluded = {int(s) for s in model.exclude_signature[: model.nexclude]} if model.nexclude else set()
    filter_parent = not (model.opt.disableflags & 1024)  # mjDSBL_FILTERPARENT
    for a_i, a in enumerate(geoms):
        ba = int(model.geom_bodyid[a])
        for b in geoms[a_i + 1:]:
            bb = int(model.geom_bodyid[b])
            if ba == bb:
                continue
            ta, tb = model.geom_contype, model.geom_conaffinity
            if not (ta[a] & tb[b] or ta[b] & tb[a]):
                continue
            wa, wb = int(model.body_weldid[ba]), int(model.body_weldid[bb])
            if wa == wb:
                continue  # welded together (both static: both welded to the world)
            if filter_parent and wa != 0 and wb != 0 and (
                    int(model.body_weldid[model.body_parentid[wa]]) == wb
                    or int(model.body_weldid[model.body_parentid[wb]]) == wa):
                continue
            lo, hi = min(ba, bb), max(ba, bb)
            if (lo << 16) + hi in excluded:
                continue
            return True
    return False


def choose(mj: Any, model: Any, requested: str) -> tuple[str, str]:
    """(integrator name, why) for the compiled model; sets ``model.opt.integrator``."""
    if requested != "auto":
        name, why = requested, "set by --integrator / check.integrator"
    else:
        reason = not_conservative(model)
        if reason is None:
            name, why = "rk4", "conservative and contact-free: fourth order keeps its energy"
        else:
            name, why = "implicitfast", f"chosen for {reason}"
    model.opt.integrator = mujoco_integrator(mj, name)
    return name, why
