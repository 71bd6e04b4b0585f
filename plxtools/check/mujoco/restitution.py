"""Normal restitution as a velocity target of MuJoCo's contact, the same for every impact speed.

An impact law says the normal speed after the impact is ``e`` times the speed before it, whatever
that speed, the masses or the step.  MuJoCo's soft contact is solved at the velocity level: in the
step it is active it accelerates the contact towards ``aref = -B v - K r`` (``v`` the normal speed,
``r`` the penetration, ``solref = (-K, -B)`` in the direct form, divided by the impedance ``d``),
and reaches ``d aref + (1 - d) a0`` (``a0`` the acceleration without the contact).  With
``B = (1 + e) / h`` and ``d`` at MuJoCo's largest, 0.9999, one step takes the normal speed from
``-v`` to ``+e v``: the impact law itself, solved together with every other contact, joint and
motor (two bodies of any mass ratio, a box landing on four corners).  In the next step the contact
would have to pull to reverse the speed again, and a contact cannot, so the body flies off; with
``e = 0`` it stays (a plastic impact).  The impact law holds for any speed by construction; the
spring-damper it replaces (a contact of 10 steps with a damping ratio for ``e``) lost a share of the
rebound to gravity acting during the contact, a share that grew as the impact speed fell.

``K`` pushes a body out of what it sank into by an impact (the step that finds a contact finds it
already penetrating, by up to ``v h``): ``K h^2 = STIFFNESS_H2 max(e, 0.1)`` recovers it in tens of
steps and adds at most 1 % of ``e v`` to a rebound.  What is left is where the impact happens: at the
depth the step found, not at the surface, so a body that sank ``x`` rebounds ``(1 - e^2) x`` lower
than ``e^2`` times its drop (exact for ``e = 1``); :func:`slowest_exact_impact` is the impact speed
below which that can take more than 3 % off the rebound speed ratio (docs/physics.md, A137)."""

from __future__ import annotations

STIFFNESS_H2 = 0.01  # K h^2: the push out of a penetration, per step, for e >= 1 (scaled by e, at least 0.1 of it)
IMPEDANCE = 0.9999  # MuJoCo's largest: the contact reaches its velocity target to 0.01 %
# e = 0 needs no exact speed: 1 % of an impact left for the next step is still no rebound, and a
# softer contact leaves stiff motors on wheels their 0.1 % (a BoxTruck turning on the spot: 0.995 at 0.9999)
PLASTIC_IMPEDANCE = 0.99
RATIO_TOLERANCE = 0.03  # the rebound speed ratio promised within 3 % of e
# the share of the bound (1 - e^2) g h / (e^2 v) that A137 quotes: the bound itself. Drops of 0.05-5 m,
# e 0.2-1 and steps 0.5-5 ms (bench/restitution.py) reached 0.66 of it, held-out scenes 0.74 (e 0.2
# from 0.5 m): a quoted share below 1 was a measurement, and a scene can exceed it
MEASURED_SHARE = 1.0


def restitution_solref(e: float, timestep: float) -> tuple[list[float], list[float]]:
    """(solref, solimp) of a contact pair with normal restitution ``e`` (0 <= e <= 1) at ``timestep``."""
    h = float(timestep)
    k = STIFFNESS_H2 * max(float(e), 0.1) / (h * h)  # adds at most 1 % of e v (0.1 % of v below e = 0.1)
    d = IMPEDANCE if e > 0.0 else PLASTIC_IMPEDANCE
    return [-k, -(1.0 + float(e)) / h], [d, d, 0.001, 0.5, 2.0]


def slowest_exact_impact(e: float, timestep: float, gravity: float) -> float:
    """The impact speed (m/s) below which a rebound against ``gravity`` may be more than 3 % short
    of ``e`` in speed ratio: the impact is resolved up to ``v h`` deep, which takes up to
    ``(1 - e^2) v h`` off a rebound height of ``e^2 v^2 / 2g``, a speed-ratio error of at most
    ``(1 - e^2) g h / (e^2 v)`` (MEASURED_SHARE: the bound itself).  0 for e = 1 and for no gravity, and for e = 0 (a plastic impact
    has no rebound to be short of: it stops the body, which the step does exactly)."""
    if e >= 1.0 or e <= 0.0 or gravity <= 0.0:
        return 0.0
    return speed_ratio_error(e, timestep, gravity, 1.0) / RATIO_TOLERANCE


def speed_ratio_error(e: float, timestep: float, gravity: float, speed: float) -> float:
    """The largest rebound speed-ratio error (a share of e) expected for an impact at ``speed``."""
    if e >= 1.0 or e <= 0.0 or gravity <= 0.0:
        return 0.0
    return MEASURED_SHARE * (1.0 - e * e) * gravity * timestep / (e * e * speed)
