"""Semantic rules: names (N), types (T), model structure (M), bundles (B), conventions (C)."""

from plxtools.rules.catalog.pages import doc


doc("UNREADABLE_FILE",
    "A file given on the command line or found in a folder cannot be read.",
    "Permissions or a broken link stop plxtools from reading it; nothing in it is checked.")

# ---------------------------------------------------------------- names
# ---------------------------------------------------------------- types
# ---------------------------------------------------------------- model structure
doc("DEFAULT_CYCLE",
    "Values of a model depend on each other in a ring (`a: b` and `b: a`).",
    "Defaults are evaluated late on the final object; a ring can never be evaluated.",
    example="Box is Physics3D.System:\n    a is Real: b\n    b is Real: a",
    use_instead="Box is Physics3D.System:\n    a is Real: 1\n    b is Real: a")
doc("MISSING_ASSIGNMENT",
    "An object that the file's root model creates has a non-optional Real, Int, Bool or String "
    "attribute with no value anywhere (base, model, trait or instance block).",
    "OpenPLX refuses to load an incomplete model (\"Missing assignment ..., owning model is not "
    "complete\"). Library models may stay incomplete; only what the root model instantiates is checked.",
    example="Scene is Physics3D.System:\n    ball is Physics3D.Bodies.RigidBody:\n        geometry is Physics3D.Geometries.Sphere",
    use_instead="Scene is Physics3D.System:\n    ball is Physics3D.Bodies.RigidBody:\n        geometry is Physics3D.Geometries.Sphere:\n            radius: 0.1")
doc("UNBOUND_REFERENCE",
    "A non-optional `reference` attribute of an instantiated object is never given an object.",
    "A reference never creates its own object; unbound, it points at nothing.")
# ---------------------------------------------------------------- bundles
doc("BUNDLES_UNAVAILABLE",
    "The language server could not load any OpenPLX bundles (shown once per file, instead of the "
    "model's diagnostics).",
    "Without the bundles no name can be resolved, so the editor shows only syntax errors until the "
    "setup is fixed: install `openplx-bundles`, or point `bundlePath` / `bundle-path` at a folder "
    "of bundles. The message says what failed.")
# ---------------------------------------------------------------- conventions and hygiene
doc("NAMING_CONVENTION",
    "A definition does not follow the naming conventions: models and traits PascalCase, attributes "
    "snake_case, globals snake_case or UPPER_CASE (const instances may be lowercase).",
    "Consistent names make models easier to read and match the official bundles.",
    example="Scene is Physics3D.System:\n    boxTruck is BoxTruck",
    use_instead="Scene is Physics3D.System:\n    box_truck is BoxTruck")
doc("UNUSED_MODEL",
    "A model or trait defined in a file outside any bundle is never used in that file and is not its "
    "root model.",
    "Dead definitions are often leftovers of a rename.")
doc("MISALIGNED_INDENTATION",
    "Lines of one block are indented differently.",
    "OpenPLX accepts it (some official files do it), but it is easy to misread, and it is also what a "
    "missing `:` on the line above looks like. `plx fmt` aligns siblings.")
doc("ROOT_NOT_SYSTEM",
    "The last model of a file outside any bundle (the model a runtime loads) is not a Physics3D.System, "
    "a rigid body or a material.",
    "agxViewer and other runtimes load the last model of a file: a System as a scene, a rigid body or a "
    "material (of the official bundles) as a library item. Reported when the last model is none of "
    "these, and when it is a body or material while a System above it is used by nothing (the scene "
    "was meant to be last).")
