"""The OpenPLX types the MuJoCo mapping takes, per family, and what each becomes in the scene
(:mod:`plxtools.check.scene`): one row per type, the one table of each family.

The assembler reads the mates and controllers, the collector the geometries, the scene its lists
of kinds, the backend the degrees of freedom a mate leaves free and the signals their source
kinds: each derives what it needs from these rows, so a new type is added here once and a motor
has one name (the scene's kind and degree of freedom, and the name signals and scene counts use)."""

from __future__ import annotations

# mate type -> scene kind
MATES = {
    "Physics3D.Interactions.Hinge": "hinge",
    "Physics3D.Interactions.Prismatic": "prismatic",
    "Physics3D.Interactions.Cylindrical": "cylindrical",
    "Physics3D.Interactions.Ball": "ball",
    "Physics3D.Interactions.Lock": "lock",
    "Physics3D.Interactions.Distance": "distance",
}

# mate kind -> the degrees of freedom it leaves free, which a controller on it may drive
FREE_DOFS: dict[str, tuple[str, ...]] = {
    "hinge": ("rotational",),
    "prismatic": ("linear",),
    "cylindrical": ("rotational", "linear"),
    "ball": (),
    "lock": (),
    "distance": (),
}

# controller type -> (scene kind, degree of freedom, its own name: a signal's source kind and the
# key of scene counts)
CONTROLLERS = {
    "Physics3D.Interactions.RotationalVelocityMotor": ("velocity_motor", "rotational", "rotational_velocity_motor"),
    "Physics3D.Interactions.LinearVelocityMotor": ("velocity_motor", "linear", "linear_velocity_motor"),
    "Physics3D.Interactions.TorqueMotor": ("torque_motor", "rotational", "torque_motor"),
    "Physics3D.Interactions.ForceMotor": ("force_motor", "linear", "force_motor"),
    "Physics3D.Interactions.RotationalRange": ("range", "rotational", "rotational_range"),
    "Physics3D.Interactions.LinearRange": ("range", "linear", "linear_range"),
    "Physics3D.Interactions.TorsionSpring": ("spring", "rotational", "torsion_spring"),
    "Physics3D.Interactions.LinearSpring": ("spring", "linear", "linear_spring"),
}

# geometry type -> its shape as the collector reads it; every *mesh shape is the scene's "mesh"
GEOMS = {
    "Physics3D.Geometries.Box": "box",
    "Physics3D.Geometries.Sphere": "sphere",
    "Physics3D.Geometries.Cylinder": "cylinder",
    "Physics3D.Geometries.Capsule": "capsule",
    "Physics3D.Geometries.ConvexMesh": "convex_mesh",
    "Physics3D.Geometries.TriMesh": "trimesh",
    "Physics3D.Geometries.ExternalTriMeshGeometry": "external_mesh",
    "Visuals.Geometries.Box": "box",
    "Visuals.Geometries.Sphere": "sphere",
    "Visuals.Geometries.Cylinder": "cylinder",
    "Visuals.Geometries.ConvexMesh": "convex_mesh",
    "Visuals.Geometries.ExternalTriMeshGeometry": "external_mesh",
}
# scene geometry kinds no bundle type maps to: a scene built by hand (the Python API) may hold them
SCENE_ONLY_GEOMS = ("plane",)


def scene_geom_kind(shape: str) -> str:
    """The scene's geometry kind of a collector shape (the three mesh shapes are one kind)."""
    return "mesh" if shape.endswith("mesh") else shape


def controller_name(kind: str, dof: str) -> str | None:
    """A scene controller's own name (``rotational_velocity_motor``) from its kind and degree of freedom."""
    return _NAMES.get((kind, dof))


_NAMES = {(kind, dof): name for kind, dof, name in CONTROLLERS.values()}
