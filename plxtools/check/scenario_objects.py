"""Expectations of ``plx test`` on what the assembled scene holds besides signals, named as the
Python API names them (``plxtools.check.api_inspect``):

* ``<geometry path>.material.density``: a geometry's material as simulated (kg/m^3);
* ``contact_model(MAT1, MAT2).friction`` (``restitution``, ``tangential_restitution``): the contact
  model of two materials named by their ``unique_name``, either way round;
* ``<connector path>.position.x`` (``main_axis``, ``normal``; ``.x``/``.y``/``.z``): a mate
  connector's world frame at the time of the expectation, as ``sim.connector`` gives it.

A material or contact model does not change during a run: its value is read once, at bind time.
"""

from __future__ import annotations

import re
from typing import Any

from plxtools.check.signals import did_you_mean

CONTACT = re.compile(r"^contact_model\(\s*([^,()\s]+)\s*,\s*([^,()\s]+)\s*\)(?:\.(\w+))?$")
CONTACT_FIELDS = {"friction": "friction", "restitution": "restitution",
                  "tangential_restitution": "tangential_restitution"}
MATERIAL = ".material."
MATERIAL_FIELDS = ("density",)
CONNECTOR_VECTORS = ("position", "main_axis", "normal")
XYZ = ("x", "y", "z")
MATE_CONNECTOR = "Physics3D.Interactions.MateConnector"


class SceneObjects:
    """What a scenario's ``of`` may name in the scene: geometries, contact models, connectors."""

    def __init__(self, prep: Any, runtime: Any) -> None:
        self.prep, self.runtime = prep, runtime
        scene = prep.compiled.scene
        self.geoms = {g.path: g for b in scene.bodies for g in b.geoms}
        self.scene = scene
        kinds, owned = prep.fc.kinds, prep.fc.assembly.owned
        self.connectors = {o.display: o for o in owned if o.display and kinds.isa(o, MATE_CONNECTOR)}

    def unknown_place(self, path: str) -> str | None:
        return unknown_place(self.prep, path)

    def claims(self, of: str) -> bool:
        """Whether ``of`` names a material, a contact model or a connector (else: a signal or body)."""
        if of.startswith("contact_model(") or MATERIAL in of + ".":
            return True
        parts = of.split(".")  # <connector>.position[.x]: not its output signals (position_output.x)
        return any(".".join(parts[:n]) in self.connectors and parts[n] in CONNECTOR_VECTORS
                   for n in (len(parts) - 1, len(parts) - 2) if n > 0)

    def bind(self, e: Any) -> str | None:
        """Fill in what ``e`` reads (``e.fixed`` or ``e.connector``); the error text otherwise."""
        if e.of.startswith("contact_model("):
            return self._contact(e)
        if MATERIAL in e.of + ".":
            return self._material(e)
        return self._connector(e)

    def _contact(self, e: Any) -> str | None:
        m = CONTACT.match(e.of)
        if m is None:
            return f"write a contact model as contact_model(MATERIAL1, MATERIAL2).FIELD, not {e.of!r}"
        a, b, what = m.groups()
        fields = ", ".join(CONTACT_FIELDS)
        if what is None:
            return f"name a value of the contact model: {e.of}.friction (or {fields})"
        if what not in CONTACT_FIELDS:
            hint = did_you_mean(what, list(CONTACT_FIELDS))
            return f"a contact model has no value {what!r}; use one of {fields}" + \
                (f"; did you mean '{hint}'?" if hint else "")
        from plxtools.check.api_inspect import contact_model

        cm = contact_model(self.scene, a, b)
        if cm is None:
            names = sorted({n for c in self.scene.contact_models for n in (c.material1, c.material2) if n})
            return f"the scene has no contact model between {a} and {b}" + \
                (f" (materials with one: {', '.join(names)})" if names else " (it has none)")
        v = getattr(cm, CONTACT_FIELDS[what])
        if v is None:
            return f"{cm.path} sets no {what}: the simulation uses its default"
        return self._fixed(e, float(v))

    def _material(self, e: Any) -> str | None:
        geom, _, what = e.of.rpartition(MATERIAL)
        if geom not in self.geoms:
            hint = did_you_mean(geom, list(self.geoms))
            return f"the scene has no simulated geometry '{geom}'" + (f"; did you mean '{hint}'?" if hint else "")
        if what not in MATERIAL_FIELDS:
            return f"a material has no number {what!r}; use {geom}{MATERIAL}{MATERIAL_FIELDS[0]}"
        return self._fixed(e, float(self.geoms[geom].density))

    def _fixed(self, e: Any, value: float) -> str | None:
        e.fixed = value
        return None

    def _connector(self, e: Any) -> str | None:
        from plxtools.check.connector_frames import connector_frame
        from plxtools.check.connector_signals import _placed
        from plxtools.check.signals import Unbindable

        parts = e.of.split(".")
        n = next(n for n in (len(parts) - 1, len(parts) - 2) if ".".join(parts[:n]) in self.connectors)
        path, rest = ".".join(parts[:n]), parts[n:]
        if len(rest) != 2 or rest[0] not in CONNECTOR_VECTORS or rest[1] not in XYZ:
            return (f"name a vector and a component of the connector {path}: "
                    f"{', '.join(f'{path}.{v}.x' for v in CONNECTOR_VECTORS)} (or .y, .z)")
        p = self.prep
        frame = connector_frame(p.fc.assembly, p.fc.evaluator, p.fc.kinds, self.connectors[path])
        if frame is None:
            return f"{path} has a degenerate frame (see plx check's findings)"
        try:
            e.connector = (_placed(self.runtime, frame), CONNECTOR_VECTORS.index(rest[0]), XYZ.index(rest[1]))
        except Unbindable as exc:
            return f"{path}: {exc}"
        return None


def read_connector(d: Any, connector: tuple) -> float:
    """One component of a connector's origin, main axis or normal in the world now."""
    from plxtools.check.connector_signals import _world

    placed, vector, index = connector
    r, p = _world(d, placed)
    v = (p, r[:, 2], r[:, 0])[vector]
    return float(v[index])


class Placer:
    """What ``api_place.place`` moves (a ``sim``), over a scenario run's MuJoCo model and data: a
    ``[[place]]`` moves the object as ``sim.place`` would, then the state is computed again so that
    the step under way (and the expectations measured now) see the new pose."""

    def __init__(self, prep: Any, runtime: Any) -> None:
        self.prepared, self.runtime = prep, runtime
        self.frames: dict = {}  # systems moved so far: their frame now
        self.model = self.data = self._stepper = None
        self.time = 0.0

    def place(self, mujoco: Any, step: Any, t: float, m: Any, d: Any) -> str | None:
        """Carry out ``step`` at time ``t``; why it is refused otherwise."""
        from types import SimpleNamespace

        from plxtools.check.api_errors import NotSimulatedError
        from plxtools.check.api_place import place

        self.model, self.data, self.time = m, d, t
        self._stepper = SimpleNamespace(movers=list(getattr(self.runtime, "movers", {}).values()))
        try:
            place(self, step.path, step.position, step.rotation)
        except (NotSimulatedError, ValueError) as exc:
            return str(exc)
        mujoco.mj_forward(m, d)
        return None


def unknown_place(prep: Any, path: str) -> str | None:
    """Why ``path`` cannot be placed ("" is the root model), or None."""
    if path == "" or path in prep.objects:
        return None
    hint = did_you_mean(path, list(prep.objects))
    return f"the model has no object '{path}' to place" + (f"; did you mean '{hint}'?" if hint else "")
