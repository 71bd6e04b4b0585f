"""The one table per family of mapped types (plxtools/check/mapped_types.py): every type it names
is a type of the loaded bundles, the assembler, the collector, the scene and the signals read the
same rows, and a controller is counted by the name signals give it."""

from __future__ import annotations

import pytest

from plxtools.check import assemble, convert, mapped_types, scene, signals
from plxtools.check.scenecounts import scene_counts

TYPES = sorted({*mapped_types.MATES, *mapped_types.CONTROLLERS, *mapped_types.GEOMS})


@pytest.mark.parametrize("qname", TYPES)
def test_each_mapped_type_is_a_bundle_type(ws, qname):
    assert ws.program.lookup_outside_visibility(qname.split(".")) is not None, qname


def test_the_readers_of_the_tables_agree_with_them():
    for qname, (kind, dof, name) in mapped_types.CONTROLLERS.items():
        assert assemble.CONTROLLER_KINDS[qname] == (kind, dof)
        assert signals.SOURCE_KINDS[qname] == name
        assert kind in scene.CONTROLLER_KINDS and dof in scene.DOF_KINDS
    for qname, kind in mapped_types.MATES.items():
        assert assemble.MATE_KINDS[qname] == kind == signals.SOURCE_KINDS[qname]
        assert kind in scene.MATE_KINDS
        assert assemble.DOF_OF_MATE[kind] == set(mapped_types.FREE_DOFS[kind])
    for qname, shape in mapped_types.GEOMS.items():
        assert convert.GEOM_KINDS[qname] == shape
        assert mapped_types.scene_geom_kind(shape) in scene.GEOM_KINDS
    # every source kind a signal row names is one the tables give some type
    used = {k for _t, kinds, _q in (*signals.INPUT_MAP, *signals.OUTPUT_MAP) for k in kinds}
    assert used <= set(signals.SOURCE_KINDS.values()), used - set(signals.SOURCE_KINDS.values())


RIG = """
Post is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    pivot is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}
    rail is Physics3D.Interactions.MateConnector:
        position: {0, 0, 1}
        main_axis: {1, 0, 0}
        normal: {0, 0, 1}

Disc is Physics3D.Bodies.RigidBody:
    inertia.mass: 2.0
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.3
        height: 0.05
    hub is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {1, 0, 0}

Carriage is Physics3D.Bodies.RigidBody:
    inertia.mass: 1.0
    geometry is Physics3D.Geometries.Box:
        size: {0.2, 0.2, 0.2}
    slot is Physics3D.Interactions.MateConnector:
        main_axis: {1, 0, 0}
        normal: {0, 0, 1}

Rig is Physics3D.System:
    post is Post
    disc is Disc
    carriage is Carriage
    spin is Physics3D.Interactions.Hinge:
        connectors: [post.pivot, disc.hub]
    slide is Physics3D.Interactions.Prismatic:
        connectors: [post.rail, carriage.slot]
    spinner is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: spin.connectors
        target_speed: 1.0
    pusher is Physics3D.Interactions.LinearVelocityMotor:
        connectors: slide.connectors
        target_speed: 0.5
    stop is Physics3D.Interactions.LinearRange:
        connectors: slide.connectors
        start: -1.0
        end: 1.0
"""


def test_scene_counts_name_each_controller_as_signals_do(check_text):
    fc = check_text(RIG)
    assert fc.scene is not None, [d.to_json() for d in fc.diagnostics]
    counts = scene_counts(fc.scene)
    assert counts["controllers"] == 3
    assert counts["controllers.rotational_velocity_motor"] == 1
    assert counts["controllers.linear_velocity_motor"] == 1
    assert counts["controllers.linear_range"] == 1
    assert "controllers.velocity_motor" not in counts
    assert counts["mates.hinge"] == 1 and counts["mates.prismatic"] == 1
