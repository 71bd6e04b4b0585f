"""What a simulation's end says beyond its own monitors (post-simulation rules): a body that fell
out of the world (A102) and a motor that misses its target because it is driven against its mirror
(A106 tied to A023).

Kept apart from the static checks (checks.py) so that the MuJoCo backend, which these read from,
and the static checks, which the backend reads, do not import each other.
"""

from __future__ import annotations

import numpy as np

from plxtools.check.mujoco.simulate import fell_out_of_world
from plxtools.check.report import Reporter
from plxtools.rules import registry

# A body that ends this far below everything it started near has left the scene (issue 32.4)
OUT_OF_WORLD_DROP = 5.0  # m
OUT_OF_WORLD_NEAR = 20.0  # m between starting positions


def bodies_out_of_world(sim, sources) -> list:
    """A102 for a dynamic body that ended far below every body it started near, while one of those
    stayed (a static ground, the chassis a loose wheel should have been mated to).

    The monitor of the simulation reports a body that sinks through static geometry it started
    above; a body that never had anything under it (the loose wheel of a mis-mated hinge beside
    the chassis, a part off the edge of the ground) falls out of the world without crossing any,
    so the start and end positions decide here. A scene that falls as a whole (a free-fall test
    with no ground) has nothing that stayed, and is not reported."""
    if sim is None:
        return []
    fell = {f["body"] for f in sim.fall_through}
    bodies = list(sim.bodies.values())
    out = []
    for b in bodies:
        if not b.dynamic or b.path in fell:
            continue
        start = np.asarray(b.initial_pos, dtype=float)
        near = [o for o in bodies if o is not b
                and float(np.linalg.norm(np.asarray(o.initial_pos, dtype=float) - start)) <= OUT_OF_WORLD_NEAR]
        stayed = [o for o in near if not o.dynamic or o.final_pos[2] > o.initial_pos[2] - OUT_OF_WORLD_DROP]
        if not stayed:
            continue
        floor = min([b.initial_pos[2]] + [o.initial_pos[2] for o in near])
        if b.final_pos[2] < floor - OUT_OF_WORLD_DROP:
            below = floor - b.final_pos[2]
            sim.fall_through.append({"body": b.path, "time": None, "ground": None, "com": list(b.final_pos),
                                     "drop": below})
            out.append(fell_out_of_world(
                b.path,
                f"{b.path} fell out of the world: it ended at z = {b.final_pos[2]:.1f} m, {below:.1f} m below "
                f"everything it started near (nothing held it: is it mated, and is there ground under it?)",
                sources.get(b.path)))
    return out


def tie_mirrored_motors(rep: Reporter) -> None:
    """A106 on a motor of an A023 pair says why it misses its target: the two motors drive the
    wheels against each other (issue 32.6); the two findings name each other."""
    if not rep.mirrored_motors:
        return

    partner = {}
    for a, b, d in rep.mirrored_motors:
        partner[a], partner[b] = (b, d), (a, d)
    for e in rep.entries:
        if e.diag.code == registry.MOTOR_OFF_TARGET and e.path in partner:
            other, a023 = partner[e.path]
            e.diag.help = (f"it is driven against {other} (A023, line {a023.span.start.line + 1}): give one of "
                           "the two the opposite target_speed to drive straight")
