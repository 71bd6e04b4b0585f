"""The state shared by the steps that build a MuJoCo model from a scene (:mod:`mujoco.compile`,
:mod:`mujoco.geoms`, :mod:`mujoco.controllers`): one object with named fields, passed to plain functions.

It is the one home of the two notes every step may make: A129 (an element is disabled,
:meth:`BuildContext.disabled`) and A131 (the scene breaks what the static checks guarantee,
:meth:`BuildContext.inconsistent` and :meth:`BuildContext.invariant`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from plxtools.check.mujoco.notes import ERROR, INFO, BackendNote, NameMap, note_from_compile_error
from plxtools.check.mujoco.results import CompiledScene
from plxtools.check.scene import Body, Scene
from plxtools.rules import registry




class CompileFailed(Exception):
    """MuJoCo refused the spec; the reason is already a note (A110)."""


@dataclass(eq=False)
class BuildContext:
    mj: Any  # the mujoco module
    scene: Scene
    out: CompiledScene
    spec: Any  # mujoco.MjSpec
    bodies: dict[str, Body] = field(default_factory=dict)  # body path -> scene body
    body_index: dict[str, int] = field(default_factory=dict)  # body path -> index in scene.bodies
    mj_bodies: dict[str, Any] = field(default_factory=dict)  # body path -> MjsBody
    excluded: set[frozenset[str]] = field(default_factory=set)  # body pairs that do not collide
    mated: set[frozenset[str]] = field(default_factory=set)  # body pairs joined by a mate
    geoms_by_material: dict[str, list[tuple[str, str]]] = field(default_factory=dict)  # -> [(geom, body path)]
    joint_limits: dict[str, list[float]] = field(default_factory=dict)  # joint name -> [lo, hi]
    spring_count: dict[str, int] = field(default_factory=dict)  # joint name -> springs on it
    violated: set[str] = field(default_factory=set)  # mates that start apart (pulled together by equalities)
    # joint -> (carrier is a shaft, [(shaft, factor)]): the shafts each drive-train joint carries
    shaft_trains: dict[str, tuple[bool, list[tuple[Any, float]]]] = field(default_factory=dict)
    bouncy_pairs: list[tuple[Any, float]] = field(default_factory=list)  # (MjsPair, normal restitution)
    bouncy_models: list[Any] = field(default_factory=list)  # contact models with a mapped restitution (A137)
    carrier_pairs: list[Any] = field(default_factory=list)  # MjsPairs touching a kinematic body (geoms.set_restitution)

    @classmethod
    def for_scene(cls, scene: Scene) -> "BuildContext":
        import mujoco

        _keep_mujoco_warnings_in_process(mujoco)
        out = CompiledScene(scene=scene)
        out.spec = mujoco.MjSpec()
        return cls(mujoco, scene, out, out.spec)

    @property
    def notes(self) -> list[BackendNote]:
        return self.out.notes

    @property
    def names(self) -> NameMap:
        return self.out.names

    def note(self, severity: str, code: str, message: str, item: Any = None, path: str | None = None) -> None:
        """A backend finding (an A1xx rule code), placed at ``item``'s source."""
        src = getattr(item, "source", None) if item is not None else None
        if path is None and item is not None:
            path = getattr(item, "path", None)
        if src is None and path is not None:
            src = self.names.sources.get(path)
        self.notes.append(BackendNote(severity, code, message, src, path))

    def invariant(self, owner: str, message: str, item: Any = None) -> None:
        """A condition the static checks own (rule ``owner``) met in the scene: the checks reject such
        a scene before it reaches the backend, so meeting it here is an inconsistency (A131).  The
        backend still copes (skips or replaces the element) so that a hand-built scene compiles."""
        self.inconsistent(f"{message} (the static check {owner} should have rejected this scene)", item)

    def inconsistent(self, message: str, item: Any = None, path: str | None = None) -> None:
        """A131: the scene contradicts itself (a duplicate path, a reference to an unknown body)."""
        self.note(ERROR, registry.SCENE_INCONSISTENT, message, item, path)

    def disabled(self, message: str, item: Any) -> None:
        """A129: an element the model disables (``enabled: false``) is left out of the MuJoCo model."""
        self.note(INFO, registry.DISABLED_ELEMENT, message, item)

    def compile(self, stage: str) -> Any:
        try:
            return self.spec.compile()
        except Exception as err:  # ValueError (compile) or mujoco.FatalError
            self.notes.append(note_from_compile_error(err, self.names))
            self.out.model = None
            raise CompileFailed(stage) from err


MUJOCO_WARNINGS: list[str] = []  # MuJoCo's own warnings of this process (the last 100)


def _keep_mujoco_warnings_in_process(mujoco) -> None:
    """MuJoCo's default warning handler appends to MUJOCO_LOG.TXT in the current folder, which is
    the user's project: keep its warnings in memory (and the debug log) instead. The blow-ups they
    announce are reported by the simulation monitors."""
    if mujoco.get_mju_user_warning() is not None:
        return

    def on_warning(text: str) -> None:
        import logging

        logging.getLogger("plxtools.check").debug("MuJoCo warning: %s", text)
        MUJOCO_WARNINGS.append(text)
        del MUJOCO_WARNINGS[:-100]

    mujoco.set_mju_user_warning(on_warning)
