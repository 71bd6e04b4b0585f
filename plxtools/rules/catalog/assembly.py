"""Assembly and simulation rules (A...): reported by `plx check`.

A0xx: instantiation, evaluation and static assembly checks (stage "check").
A1xx: findings of the MuJoCo backend and of the simulation (stage "simulate", only with --simulate).

Each problem has one owner: the static checks own assembly problems; the MuJoCo backend emits only
A1xx codes, for what is specific to it, and treats what the static checks guarantee as invariants
(A131 when one is broken).
"""

from plxtools.rules.catalog.pages import doc


# ---------------------------------------------------------------- instantiation and evaluation

doc("ROOT_MODEL_NOT_FOUND",
    "The model named with `--model` does not exist in the file (or the file defines no model).",
    "`plx check` instantiates one root model per file: the last model of the file, or the one named with "
    "`--model`. With no such model nothing can be assembled.")
doc("ROOT_IS_TRAIT",
    "The model chosen as the root is a trait.",
    "A trait only adds attributes to the models that use it; it cannot be instantiated on its own "
    "(AGXUnity: \"Cannot directly import a trait\").")
doc("EVALUATION_ERROR",
    "A value cannot be computed: a function called outside its domain (normalising a zero vector, "
    "`arccos(2)`), a division by zero, an unknown name, a value of the wrong kind.",
    "`plx check` evaluates the expressions of every object the root model creates, the way the OpenPLX "
    "runtime does, on the final object (defaults late). A value that cannot be computed makes the "
    "object unusable.",
    example="normal: main_axis.normal() / 0",
    use_instead="normal: main_axis.normal()")
doc("MISSING_VALUE",
    "A value the assembly needs has no assignment and no default.",
    "Usually reported by M007 already; this catches values that only the evaluation needs (a field of "
    "a Matrix4x4, a value read through a reference).")
doc("EVALUATED_UNBOUND_REFERENCE",
    "An attribute that must refer to an existing object is not bound, or is given something that is "
    "not an object.",
    "References (`connectors: [...]`, `group1: parts`, `material: Steel`) are followed during "
    "assembly; an unbound one leaves the mate, group or geometry without its target.")
doc("VALUE_CYCLE",
    "Values depend on each other in a ring, found while evaluating (`a: b + 1`, `b: a`).",
    "Such values can never be computed. The message lists the ring; break it by giving one of them a "
    "value that does not depend on the others.",
    example="a is Real: b\nb is Real: a",
    use_instead="a is Real: 1.0\nb is Real: a")
doc("ENVIRONMENT_VARIABLE_UNSET",
    "A `$\"...{VAR}...\"` string names an environment variable that is not set.",
    "Interpolated strings take `{NAME}` from the environment (the BoxTruck tutorial uses "
    "`$\"{AGX_DATA_DIR}/...\"`). Where the variable is unset the path cannot be resolved, so the file it "
    "names is missing at run time.",
    example='path: $"{AGX_DATA_DIR}/models/wheel.obj"',
    use_instead='path: @"wheel.obj"')
doc("UNSUPPORTED_FUNCTION",
    "An expression calls a function that the plxtools evaluator does not implement "
    "(`Physics3D.System.resnap`, signal factories, `on_init`...).",
    "Such functions need the AGX runtime. The value is left unknown and whatever depends on it is "
    "skipped.")
doc("INSTANTIATION_TOO_DEEP",
    "A model contains itself, directly or through others (owned objects more than 48 levels deep, "
    "a model met again among its owners), or distinct models nest more than 500 levels deep.",
    "Instantiating a model that contains itself would never end; the objects below that depth are not "
    "created. The message says which it is: the chain of models that repeats, or plx check's nesting limit.",
    example="Link is Physics3D.System:\n    next is Link")

# ---------------------------------------------------------------- connectors and mates

doc("ZERO_MAIN_AXIS",
    "A MateConnector's `main_axis` is the zero vector.",
    "The main axis is the axis a hinge turns about and a prismatic slides along; a zero vector defines "
    "no frame (AGXUnity `InvalidMateConnectorAxis`).",
    example="main_axis: {0, 0, 0}",
    use_instead="main_axis: {0, 0, 1}")
doc("DEGENERATE_NORMAL",
    "A MateConnector's `normal` is zero, or parallel or antiparallel to its `main_axis`.",
    "The connector frame is x = normal (orthogonalised), z = main_axis; a normal along the main axis "
    "leaves the rotation about the axis undefined, so SNAP cannot orient the parts.",
    example="main_axis: {0, 1, 0}\nnormal: {0, -1, 0}",
    use_instead="main_axis: {0, 1, 0}\nnormal: {1, 0, 0}")
doc("NORMAL_NOT_ORTHOGONAL",
    "A MateConnector's `normal` is not orthogonal to its `main_axis`; only its orthogonal part counts.",
    "This is allowed (the frame is Gram-Schmidt orthogonalised), but it usually means the axes were "
    "mixed up. The message shows the normal that is actually used.")
doc("CONNECTOR_COUNT",
    "A mate or a 1-DOF controller does not have exactly two MateConnectors.",
    "A mate joins two parts: `connectors[0]` and `connectors[1]`. With fewer there is nothing to join; "
    "extra connectors are ignored by the runtime.",
    example="connectors: [chassis.hub]",
    use_instead="connectors: [chassis.hub, wheel.connector]")
doc("MATE_SAME_CONNECTOR",
    "A mate lists the same connector twice.",
    "A mate must join two different parts.")
doc("MATE_SAME_BODY",
    "Both connectors of a mate belong to the same body (or both to the world / a system), so it joins "
    "nothing (AGXUnity `MissingConnectedBody`).",
    "A mate constrains one body relative to another; within one body it has no effect and SNAP cannot "
    "use it.")
doc("MATE_NOT_COINCIDENT",
    "After assembly the two connector frames of a mate do not coincide: the message gives the distance "
    "and the angle, and how each side was placed.",
    "SNAP moves only bodies and systems without a declared transform. When both sides of a mate are "
    "placed by declared transforms (or by other mates) and their connectors do not meet, the simulation "
    "starts with a violated joint and the solver yanks the parts together.",
    example="front_left_wheel is Wheel:\n    kinematics.local_transform.position.z: 2.0",
    use_instead="front_left_wheel is Wheel")
doc("MATE_WITHOUT_DYNAMIC_BODY",
    "A mate joins two parts that cannot move (static bodies, `is_dynamic: false`, or the world).",
    "Such a mate has no effect; usually one side was meant to be dynamic.")
doc("HINGE_AXIS_OFF_CYLINDER_AXIS",
    "A hinge (or cylindrical mate) turns a body about an axis that is not the axis of the cylinder or "
    "capsule it passes through. OpenPLX cylinders lie along their local Y axis.",
    "The classic wheel mistake: a wheel connector with `main_axis: {0, 0, 1}` makes SNAP turn the "
    "wheel so that its local Z lies on the hub's axis, and the wheel then tumbles about a diameter "
    "instead of rolling.",
    example="connector is Physics3D.Interactions.MateConnector:\n    main_axis: {0, 0, 1}",
    use_instead="connector is Physics3D.Interactions.MateConnector:\n    main_axis: {0, -1, 0}")

# ---------------------------------------------------------------- controllers

doc("CONTROLLER_WITHOUT_MATE",
    "A motor, range or spring has a connector pair that no mate uses, so it drives nothing.",
    "Controllers attach to the mate with the same two connectors (`connectors: hinge.connectors`). "
    "With any other pair the runtime cannot find the degree of freedom to drive.",
    example="connectors: [chassis.front_left_hub, front_right_wheel.connector]",
    use_instead="connectors: front_left_hinge.connectors")
doc("CONTROLLER_DOF_MISMATCH",
    "A controller's type does not fit its mate: a rotational motor, range or spring on a Prismatic, a "
    "linear one on a Hinge, or any controller on a Lock, Ball or Distance.",
    "Rotational controllers need a Hinge or Cylindrical mate; linear ones a Prismatic or Cylindrical.")
doc("ANGLE_PROBABLY_DEGREES",
    "An angle or angular speed (`initial_angle`, `target_speed` of a rotational motor, a rotational "
    "range) is larger than 2 pi.",
    "OpenPLX angles are radians. A value such as 90 is likely meant in degrees; "
    "`Math.Functions.deg_to_rad(90)` converts it.",
    example="initial_angle: 90",
    use_instead="initial_angle: Math.Functions.deg_to_rad(90)")
doc("MIRRORED_DRIVE_MOTORS",
    "Two velocity motors with the same target speed drive hinges whose axes point in opposite directions "
    "(the left and right hubs of a vehicle).",
    "The BoxTruck trap: left hubs look along -Y and right hubs along +Y, so equal target speeds turn the "
    "two wheels in opposite directions and the vehicle does not drive straight. Where nothing resists it "
    "turns on the spot; where other wheels on the ground resist the turn (the tutorial's four-wheeled "
    "truck) the driven wheels scrub against each other, the truck hardly moves, and with `--simulate` "
    "both motors miss their target speed (A106, whose help then names the other motor of the pair). Give one side the opposite sign to "
    "drive straight. This is information only: opposite speeds may be intended.",
    example="front_left_motor ...:\n    target_speed: 1\nfront_right_motor ...:\n    target_speed: 1",
    use_instead="front_left_motor ...:\n    target_speed: 1\nfront_right_motor ...:\n    target_speed: -1")
doc("INVERTED_LIMITS",
    "A range has `start > end`, or a controller has `min_effort > max_effort`.",
    "The allowed interval is empty; the runtime cannot satisfy it.")

# ---------------------------------------------------------------- geometry, mass, contacts

doc("NON_POSITIVE_SIZE",
    "A geometry has a size that is not positive: a Box `size` component <= 0 (the default is 0, 0, 0!), a "
    "radius or cylinder height <= 0, a capsule height < 0, a mesh scale <= 0, or a mesh without vertices.",
    "Such a geometry has no volume: it cannot collide and gives no mass. The MuJoCo backend skips it."
    " `plx lint` (and so the editor, while you type) reports it when the value is written as a number; `plx check` also finds computed ones.",
    example="geometry is Physics3D.Geometries.Box",
    use_instead="geometry is Physics3D.Geometries.Box:\n"
    "    size: {1, 0.5, 0.2}")
doc("MISSING_FILE",
    "A file named with `@\"...\"` (relative to the .openplx file's folder), or a mesh file, does not exist. "
    "Missing visual meshes and files behind `$\"...\"` are warnings.",
    "The runtime fails to load the model, or the geometry is missing from the simulation.",
    example='path: @"whel.obj"',
    use_instead='path: @"wheel.obj"')
doc("NEGATIVE_MASS",
    "A body has a negative `inertia.mass` (AGXUnity `NegativeMass`).",
    "Mass must be positive; 0 means \"compute it from the geometries\"."
    " `plx lint` (and so the editor, while you type) reports it when the value is written as a number; `plx check` also finds computed ones.")
doc("ZERO_MASS_DYNAMIC_BODY",
    "A dynamic body has `inertia.mass` 0 and no contact geometry that gives it mass.",
    "Mass 0 means \"compute from the geometries\" (density x volume); with no geometry that counts the "
    "body would have zero mass, which no solver can integrate.")
doc("INVALID_INERTIA",
    "An explicit inertia tensor is not symmetric, not positive definite, or breaks the triangle "
    "inequality of principal moments.",
    "The tensor counts as set when any diagonal element is not 0, and is then used as given. A physical "
    "tensor has positive principal moments a, b, c with a + b >= c.")
doc("DUPLICATE_CONTACT_MODEL",
    "Two SurfaceContact.Models are given for the same (unordered) pair of materials.",
    "The runtime rejects this (AGXUnity `DuplicateMaterialPairForSurfaceContactModelDefinitionError`): it "
    "cannot know which friction to use.")
doc("INVALID_CONTACT_PARAMETER",
    "A contact model has a negative friction coefficient, or a restitution outside [0, 1]; or a mate's "
    "joint friction (ConstantLimitFriction.limit, ConstantViscousSurfaceFriction.viscosity) is negative or "
    "not finite.",
    "Friction coefficients are >= 0 and restitution is a fraction of the normal speed kept after impact."
    " `plx lint` (and so the editor, while you type) reports it when the value is written as a number; `plx check` also finds computed ones.")
doc("UNPLACED_BODY_OVERLAPS",
    "A body with no declared transform that no mate places stays at its system's origin, where it "
    "overlaps another body.",
    "Bodies that SNAP cannot place keep the identity transform. Several of them pile up at the origin "
    "and the simulation starts by pushing them apart.")
doc("NON_POSITIVE_DENSITY",
    "A material used by a mass-giving geometry has density <= 0.",
    "The geometry then adds no mass."
    " `plx lint` (and so the editor, while you type) reports it when the value is written as a number; `plx check` also finds computed ones.")
doc("BODY_NOT_IN_SYSTEM",
    "A RigidBody is owned by an object that is not a Physics3D.System (AGXUnity "
    "`RigidBodyOwnerNotSystemError`).",
    "Bodies belong directly to systems; to attach one body to another use a mate (a Lock).")
doc("NOT_SIMULATED",
    "Something that the MuJoCo backend of `plx check --simulate` cannot represent: Physics1D and DriveTrain "
    "objects other than shafts, gears, hinge actuators, 1D motors on one shaft, brakes, clutches and open "
    "differentials (engines, gear boxes, torque converters, limited-slip differentials, flexible and viscous "
    "gears, prismatic actuators, motors between two shafts), Terrain, Sensors, Vehicles and Robotics objects, signals it does not map (see docs/testing.md), KinematicLock, tangential restitution, non-dry "
    "friction models, oriented (anisotropic) friction and surface viscosity traits, any attribute a bundle "
    "trait adds to a mapped object that the backend does not simulate (named with the trait, on the line "
    "that gives it), PointGravitationalField, unknown mate or interaction types.",
    "It is named, never dropped silently: the simulation runs without it, so its results may differ "
    "from AGX's.")
doc("RANGE_STARTS_VIOLATED",
    "A mate starts outside the range on it: its `initial_angle` (or `initial_position`) lies outside the "
    "range's [start, end].",
    "The joint limit then pushes the bodies back at the first step, a kick the model does not describe "
    "(hundreds of joules and metres per second in a stiff limit); found before any simulation.")
doc("IMPORTED_FILE_NOT_ANALYSED",
    "The scene uses a model imported from a file plx cannot read (an `.agx` archive, a URDF, any "
    "format other than `.obj`/`.stl` meshes and images): said once per import, listing the objects built "
    "from it.",
    "What such a file holds (bodies, mates, masses) is unknown to plx, so the objects built from it are "
    "not instantiated, analysed or simulated, and nothing inside them is reported as missing or wrong "
    "(no \"mass 0\" or \"not owned by a system\" for an imported body specialised with `becomes`). "
    "Members reached through the import are not errors in lint either.",
    example='import @"pendulum.agx"\n\nScene is Physics3D.System:\n    pendulum is pendulum')
doc("NON_FINITE_VALUE",
    "A number that assembly reads is NaN or infinite: a mass, size, connector position or axis, initial "
    "velocity, motor gain... (`1e308 * 10` overflows to infinity, `inf - inf` is NaN), or an integer "
    "too large for a number (beyond 1.8e308).",
    "Such a value cannot be simulated and would silently turn the scene into NaN. It is reported at the "
    "line that gives it and the value is treated as unknown. Infinity is allowed only where it means "
    "\"no limit\": `min_effort`, `max_effort` and a range's `start` / `end`.",
    example="inertia.mass: 1e308 * 10",
    use_instead="inertia.mass: 1e3")

# ---------------------------------------------------------------- simulation (MuJoCo backend)

# A043 connector-used-by-two-mates: plxtools/rules/assembly/shared_connector.py
doc("COLLISION_PAIR_WITHOUT_EFFECT",
    "A `DisableCollisionPair` whose body pairs are all either joined by a mate or apart at the start: "
    "it changes nothing at the start of the simulation.",
    "Bodies joined by a mate never collide with each other (MuJoCo excludes their contacts, as AGX "
    "does), so a collision group around a truck's chassis and its wheels, as in the BoxTruck tutorial's "
    "step 8, has no visible effect: the wheels are mated to the chassis and apart from each other. It "
    "is information only: the pair still matters if those bodies come to touch as they move.")
doc("SIMULATION_BLOWUP",
    "The simulation became numerically unstable: NaN/Inf, MuJoCo's bad-state warnings, or a velocity "
    "above 1000 (m or rad)/s. The time and the fastest body are named.",
    "The model is usually wrong: masses many orders of magnitude apart, huge stiffness, violated mates "
    "or deep initial penetration.")
doc("FELL_THROUGH",
    "A dynamic body that started above static geometry ended up below it (its centre of mass more than "
    "1 cm below the top, inside the footprint), or a body fell out of the world: it ended more than 5 m "
    "below every body it started near (within 20 m) while one of those stayed.",
    "Collisions are off for that pair (collision groups, `enable_collisions: false`) or the body tunnelled. "
    "A body that falls out of the world had nothing under it and nothing holding it: a wheel whose hinge "
    "names another wheel's connector, a part placed past the edge of the ground. A scene that falls as a "
    "whole (a free-fall test without ground) is not reported.")
doc("MATE_DRIFT",
    "During the simulation a mate's connectors separated by more than 5 mm, or its axes by more than "
    "0.05 rad; the maximum and its time are given.",
    "Stiff mates hold within millimetres. Larger separations mean a violated start (see A016), a loop "
    "that MuJoCo cannot close exactly, or forces far beyond what the model can carry.")
doc("OVERLAP_AT_START",
    "Two geometries overlap by more than 5 mm at t = 0.",
    "The solver pushes them apart in the first steps, which shows up as a jump or a blow-up.")
doc("JOINT_LIMIT_EXCEEDED",
    "A joint went more than 0.02 beyond its range during the run.",
    "The range is enforced by a soft limit in MuJoCo; large excursions mean large forces.")
doc("MOTOR_OFF_TARGET",
    "A velocity motor's mean speed over the last 20 % of the run is off its target by more than 2 % "
    "(+ 0.005); the message gives the measured error, the mean effort and the gain MuJoCo runs with.",
    "The motor is blocked, its effort range is too small, or it fights another motor.")
doc("BAD_CONTROL",
    "MuJoCo rejected a NaN or huge actuator control and zeroed the controls.",
    "A target speed or effort evaluated to an unusable number.")
doc("SIMULATION_INCOMPLETE",
    "The simulation stopped before the requested duration.",
    "Usually after a blow-up (A101).")
doc("SIMULATION_TIMEOUT",
    "The simulation took longer than the wall-clock limit (`--timeout`, 300 s by default) and was stopped.",
    "The motion after that time is not checked, so the file does not pass. Shorten `--duration`, raise "
    "`--timeout`, or look for what makes the scene slow (very stiff springs shorten the time step, A133).")
doc("MUJOCO_COMPILE_ERROR",
    "MuJoCo rejected the compiled model; the message names the OpenPLX element when it can.",
    "This is a model MuJoCo cannot represent (or a gap in the backend).")
doc("VELOCITY_MOTOR_GAIN_CLAMPED",
     "A velocity motor runs as a velocity constraint of its gain, solved together with contacts and "
     "limits as AGX's is (rigid with the bundle's default `gain`, 1e8), whatever its effort range "
     "(symmetric, asymmetric, one-sided or none: a constant offset plus a friction bound around it). "
     "One with an inverted effort range (min above max) cannot: it runs as a MuJoCo velocity servo whose "
     "gain is clamped to 10 x the joint's effective inertia / timestep (1 x with an effort limit, or on a "
     "drive train). An info for the bundle's default gain; a warning naming your value and the one used "
     "when your files set the gain.",
     "The clamped servo gets close to its target speed in a few steps and sags by load / kv under a load "
     "(A106 says by how much); fix the effort range to have it run as a constraint.")
doc("SPRING_STIFFNESS_CLAMPED",
    "A spring is so stiff that even the shortest time step plxtools uses (1e-4 s) cannot integrate it; "
    "the message names your stiffness and the lower one simulated.",
    "Joint stiffness is integrated explicitly and needs sqrt(k / I) * timestep <= 0.2. Springs up to that "
    "limit shorten the time step instead (A133).")
doc("FRICTION_MODEL_APPROXIMATED",
    "A dry friction model (box, scaled box, constant normal force...) is approximated by MuJoCo's "
    "Coulomb cone with the same coefficient.",
    "Friction magnitudes can differ from AGX's model.")
doc("LOOP_CLOSURE",
    "A mate closes a kinematic loop and becomes a MuJoCo equality constraint (weld, connect, or two "
    "connects on a hinge axis).",
    "Equality constraints are soft; they hold within millimetres.")
doc("LOOP_CLOSURE_UNSUPPORTED",
    "A prismatic or cylindrical mate closes a kinematic loop; MuJoCo cannot express it and it is not "
    "enforced.",
    "The parts it should hold together can drift apart in the simulation.")
doc("DISTANCE_MATE_APPROXIMATED",
    "A Distance mate is approximated by a tendon-length equality (or a connect when the distance is 0).",
    "MuJoCo has no distance constraint; the approximation is soft.")
doc("CONCAVE_MESH_HULL",
    "MuJoCo collides with the convex hull of a (possibly concave) mesh.",
    "Contacts inside concavities are lost.")
doc("MESH_FORMAT_UNSUPPORTED",
    "MuJoCo cannot read this mesh file format; the geometry is skipped.",
    "MuJoCo reads .obj and .stl meshes (and a few others).")
doc("RANGE_EFFORT_IGNORED",
    "A range's effort limits are not modelled: MuJoCo limits are hard.",
    "Ranges become joint limits in MuJoCo.")
doc("INITIAL_VELOCITY_IGNORED",
    "Part of the initial velocity of a body attached by a mate is ignored: the body starts with the joint "
    "speed its velocity gives (the rotation about a hinge axis, the translation along a slide), relative to "
    "its parent; the components the mate does not allow are left out, and named.",
    "Free bodies (the roots of the MuJoCo tree) take their whole initial velocity.")
doc("KINEMATIC_BODY",
     "A kinematic body (`is_dynamic: false`, or listed in a system's `kinematically_controlled`) with a "
     "velocity moves at that velocity, whatever hits it: a free MuJoCo body of effectively infinite inertia "
     "set to its prescribed pose and velocity every step. Its velocity inputs set a new velocity.",
     "Contacts see how fast it moves, so friction carries what rests on it (a conveyor belt, a turntable, a "
     "lifting platform: within 0.1 % of the closed form after the slip, docs/physics.md).")
doc("CONTROLLER_REVERSED",
    "A controller lists its mate's connectors in the opposite order, so its coordinate is the negated "
    "mate coordinate.",
    "A positive target speed then turns the other way; usually unintended.")
doc("CONTROLLER_ON_DISABLED_MATE",
    "A controller drives a mate that is disabled.",
    "It has nothing to drive.")
doc("CONTROLLER_ON_LOOP_MATE",
    "A controller drives a mate that closes a kinematic loop (an equality constraint in MuJoCo); this is "
    "not supported.",
    "The controller is ignored in the simulation.")
doc("STACKED_CONTROLLERS",
    "Several ranges or springs act on one degree of freedom: ranges are intersected; springs act as one "
    "spring with their summed stiffness and damping, at the stiffness-weighted mean of their rests (the same "
    "force as the separate springs).",
    "Check that this is what the model means.")
doc("MASS_WITHOUT_GEOMETRY",
    "A body has a mass but no geometry to shape its inertia; a 0.1 m solid sphere is assumed.",
    "Give the body a geometry or an inertia tensor.")
doc("PLANE_ON_DYNAMIC_BODY",
    "MuJoCo planes can only be static; the geometry is skipped.",
    "Use a thin box for a moving plate.")
doc("CONTACT_MODEL_UNUSED",
    "A SurfaceContact.Model names a material that no colliding geometry uses.",
    "The model has no effect; often the geometry's `material` was not set.")
doc("DISABLED_ELEMENT",
    "A mate, controller or contact model is disabled (`enabled: false`).",
    "It is left out of the simulation.")
doc("INVALID_CONTROLLER_PARAMETER",
    "A controller parameter is unusable: a non-positive gain or stiffness, a negative damping, a range "
    "without start or end.",
    "The controller is ignored in the simulation.")
doc("SCENE_INCONSISTENT",
    "The scene handed to the MuJoCo backend names an unknown or duplicate body, or breaks a condition "
    "that a static check (named in the message) guarantees.",
    "The backend runs only on scenes without errors, so this points at a plxtools bug; please report it "
    "with the model.")
doc("TIMESTEP_SHORTENED",
    "A stiff spring would be unstable at the default time step of 0.002 s, so the whole scene is "
    "simulated with a shorter one (a whole fraction of 0.002 s, at least 1e-4 s).",
    "The spring then acts with the stiffness the model gives it; the run takes proportionally longer.")
doc("ENERGY_GAIN",
    "The scene's mechanical energy (motion, gravity, springs) grew by more than 5 % of its energy scale "
    "beyond the work its motors did.",
    "Contacts, damping and friction only remove energy, so a gain means motion the model does not "
    "describe: a spring or mate too stiff for the integrator, an initial overlap pushed apart, or a gap in "
    "the MuJoCo mapping. The message gives the gain, the time and the most energetic body. Not checked "
    "when kinematic bodies move (they do work on what they push) or when signal inputs drive the run "
    "(`plx test`, the Python API).")
doc("IMPLAUSIBLE_SPEED",
    "A body moved faster than anything in the scene explains: its start speed plus free fall over the "
    "whole run plus the motors' target speeds (rotational ones times the scene's size) plus the speed the "
    "springs' initial energy could give, with a margin of 2 and 1 m/s.",
    "The message lists the parts of the bound. A runaway usually comes before a blow-up (A101).")
doc("RESTITUTION_APPROXIMATED",
     "A contact model's `normal_restitution` e is simulated per material pair as a velocity target of "
     "MuJoCo's contact: in the step an impact begins, the normal speed goes from -v to e v (MuJoCo `solref` "
     "in its direct form, damping (1 + e) / h), solved with every other contact and joint. An info; a "
     "warning when impacts slower than 1 m/s may rebound more than 3 % short of e at the scene's time step.",
     "The impact law holds for every speed and mass ratio, but a step finds an impact up to v h deep, and "
     "the rebound starts from there: (1 - e^2) times that depth comes off the rebound height, which matters "
     "for slow impacts with a low e. The warning names the impact speed below which that can exceed 3 %; "
     "a shorter `--timestep` lowers it (see docs/physics.md).")
doc("VISUAL_MESH_SKIPPED",
    "A visual-only mesh (`Visuals.Geometries...`) that MuJoCo cannot load (fewer than 4 vertices, a "
    "degenerate file) is left out of the MuJoCo scene.",
    "Visuals never change the physics: they are compiled without mass or collisions (a flat mesh as a "
    "shell), and one that cannot be drawn is only missing from renders.")
doc("MJCF_EXPORT_UNLOADABLE",
    "`--export-mjcf`: the MJCF that MuJoCo writes for the scene does not load back into MuJoCo (its XML "
    "writer rounds numbers, so a box of 0.25 m next to one of 1e30 m is written with size 0).",
    "The file is not written (the command exits with 2); the message names the MuJoCo element and "
    "the line of the OpenPLX object it comes from. Bring the sizes or masses of the scene into a "
    "physical range.")

# ---------------------------------------------------------------- plx test (scenario files)
T = "test"
doc("EXPECTATION_FAILED",
    "An expectation of a scenario file does not hold: the value measured in the simulation is outside "
    "what the `[[expect]]` table states (`below`, `above`, `abs_below`, `between`, `equals` with a "
    "`tolerance`).",
    "The message names the scenario line, the expected and the measured value and the time of the "
    "measurement (for `during`, the first failing sample and the worst one). A wrong motor sign or hub "
    "axis shows up here as a truck that does not move the way the scenario drives it.",
    example='[[expect]]\nat = 2.0\nof = "box_truck.chassis.x"\nbelow = -1.0')
doc("INVALID_SCENARIO",
    "A scenario file cannot be run as written: invalid TOML, an unknown key, an unknown signal or body "
    "path (with a did-you-mean), a geometry, contact model or connector the scene does not hold, a "
    "value of the wrong kind for an input, a time before 0 or after the run's `duration`, a `root` "
    "model that is not in the model file, or a `[[place]]` that cannot be carried out (an unknown "
    "path, or an object with a body hanging by a mate from something outside it).",
    "`plx test` reports it at the line of the scenario and exits 2, like a pytest collection error: "
    "the scenario says nothing about the model until it is fixed.")
doc("SCENARIO_MODEL_NOT_SIMULATED",
    "The model a scenario names cannot be simulated: it has errors that make its scene unreliable, or "
    "MuJoCo cannot compile it.",
    "The scenario fails (exit 1) with the model's first errors; `plx check --simulate` on the model "
    "shows all of them.")
