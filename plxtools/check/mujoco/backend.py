"""MuJoCo backend of ``plx check --simulate``: compile an assembled scene, simulate, export, render.

Public API (mujoco is imported lazily, only inside these functions)::

    compiled = compile_scene(scene)            # -> CompiledScene (.ok, .model, .spec, .notes, ...)
    result = simulate(scene_or_compiled, 5.0)  # -> SimulationResult (.to_dict() is JSON-ready)
    export_mjcf(compiled, "scene.xml")         # spec.to_xml(), with an "initial" keyframe (ctrl too)
    render_png(scene_or_compiled, "scene.png") # offscreen EGL/OSMesa; RenderUnavailable if impossible

Approximations (each one also produces a ``BackendNote`` when it applies):

* Velocity motors -> ``<velocity>`` actuators, ctrl = target_speed, ``kv = min(gain,
  10 * I_eff / timestep)`` where ``I_eff = 1 / dof_invweight0`` of the driven DOF.  With the
  ``implicitfast`` integrator this removes ~10/11 of the speed error per step (nearly rigid, like
  AGX's gain 1e8) without the ill-conditioning of kv = 1e8.
* Springs -> joint stiffness, capped so that sqrt(k / I_eff) * timestep <= 0.2 (stiffness is not
  integrated implicitly); springref = sign * rest.
* Ranges -> hard joint limits (range effort limits are not modelled).
* Mass > 0 without a tensor: the geometry's inertia is scaled to the given mass (centre of mass
  from the geometry unless ``cm_pos`` is set).  Mass 0: MuJoCo computes mass and inertia from
  geom densities (material density).
* Contact models -> one ``<pair>`` per colliding geom pair with those materials (friction
  ``mu mu 0.005 1e-4 1e-4``, condim 3), skipping excluded / mated / same-body pairs; other pairs
  use MuJoCo's default friction 1 (or ``Scene.default_friction``).  Restitution is not supported.
* Loop closures: ball -> connect, lock -> weld, hinge -> two connects on the axis; prismatic /
  cylindrical loops are not enforced.  Distance mates -> tendon-length equality.
"""

from __future__ import annotations

from typing import Any

from plxtools.check.mujoco.compile import ActuatorInfo, CompiledScene, MateMonitor, compile_scene
from plxtools.check.mujoco.notes import BackendNote
from plxtools.check.mujoco.render import RenderUnavailable, render_compiled, write_png
from plxtools.check.mujoco.simulate import (
    BodyReport,
    MateReport,
    MotorReport,
    SimulationResult,
    simulate_compiled,
)
from plxtools.check.scene import Scene
from plxtools.rules import registry
from plxtools.check.mujoco.notes import note_from_compile_error
from plxtools.fileio import write_output

__all__ = [
    "ActuatorInfo",
    "BackendNote",
    "BodyReport",
    "CompiledScene",
    "ExportError",
    "MateMonitor",
    "MateReport",
    "MotorReport",
    "RenderUnavailable",
    "SimulationResult",
    "compile_scene",
    "export_mjcf",
    "render_png",
    "simulate",
    "write_png",
]


def _compiled(scene_or_compiled: Scene | CompiledScene) -> CompiledScene:
    if isinstance(scene_or_compiled, CompiledScene):
        return scene_or_compiled
    return compile_scene(scene_or_compiled)


def simulate(
    scene_or_compiled: Scene | CompiledScene, duration: float = 5.0, **options: Any
) -> SimulationResult:
    """Compile (if needed) and run for ``duration`` seconds.  Options: ``sample_dt`` (0.01 s),
    ``penetration_tol`` (0.005 m), ``max_speed`` (1e3), ``fall_margin`` (0.01 m), ``mate_tol``
    (5e-3 m), ``angle_tol`` (0.05 rad), ``limit_tol`` (0.02)."""
    return simulate_compiled(_compiled(scene_or_compiled), duration, **options)


class ExportError(Exception):
    """The MJCF text MuJoCo wrote for the scene does not load back; ``note`` says where and why."""

    def __init__(self, note: BackendNote):
        super().__init__(note.message)
        self.note = note


def export_mjcf(compiled: CompiledScene, path: str | None = None) -> str:
    """MJCF text of the compiled scene (written to ``path`` when given).

    MuJoCo's XML writer rounds numbers, so a scene it simulates can still give a file it refuses
    (a size of 0.25 next to 1e30 is written as 0).  The text is therefore loaded back first, and
    the file is written (atomically, next to its final place) only when that succeeds; otherwise
    :class:`ExportError` names the element and its OpenPLX source."""
    import mujoco

    if compiled.spec is None:
        raise ValueError("nothing to export: the scene has no MjSpec")
    xml = compiled.spec.to_xml()
    if path is None:
        return xml

    def loads_back(tmp: str) -> None:
        try:
            mujoco.MjModel.from_xml_path(tmp)
        except ValueError as exc:
            note = note_from_compile_error(exc, compiled.names)
            note.code = registry.MJCF_EXPORT_UNLOADABLE
            note.message = note.message.replace("MuJoCo rejected the model", "MuJoCo cannot load the exported MJCF", 1)
            raise ExportError(note) from None

    write_output(path, xml, check=loads_back)  # through symlinks; devices refused; nothing half-written
    return xml


def render_png(
    scene_or_compiled: Scene | CompiledScene,
    path: str,
    width: int = 640,
    height: int = 480,
    *,
    at_time: float = 0.0,
) -> dict[str, Any]:
    """Render the scene (initial state, or after ``at_time`` seconds of simulation) to a PNG.

    Raises :class:`RenderUnavailable` with the reason when no headless GL context can be made,
    and ``ValueError`` when the scene does not compile."""
    return render_compiled(_compiled(scene_or_compiled), path, width, height, at_time)
