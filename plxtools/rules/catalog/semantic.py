"""Semantic rules: names (N), types (T), model structure (M), bundles (B), conventions (C)."""

from plxtools.rules.catalog.pages import doc


doc("UNREADABLE_FILE",
    "A file given on the command line or found in a folder cannot be read.",
    "Permissions or a broken link stop plxtools from reading it; nothing in it is checked.")

# ---------------------------------------------------------------- names
doc("UNRESOLVED_TYPE",
    "A type name after `is`, `becomes`, `with`, in a parameter or a return type does not resolve.",
    "Names are looked up from the current namespace outwards and then from the bundles (spec C.2). "
    "A misspelt or missing type leaves the attribute untyped, so nothing about it can be checked.",
    example="geometry is Physics3D.Geometries.Bx",
    use_instead="geometry is Physics3D.Geometries.Box")
doc("UNKNOWN_ATTRIBUTE",
    "An assignment or a dotted path names an attribute that the object being configured does not have.",
    "A misspelt attribute would otherwise be silently ignored or rejected at load time; the message "
    "names the model that was searched and suggests the closest attribute.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mas: 10",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10")
doc("UNRESOLVED_NAME",
    "A name in an expression is neither an attribute of the model being defined nor a global name "
    "(const model, global attribute, type or namespace).",
    "In OpenPLX the scope of a right-hand side is the outermost model where it is written, then the "
    "global names; a name outside both cannot be evaluated.",
    example="Chassis is Physics3D.Bodies.RigidBody:\n    inertia.mass: chassis_mass",
    use_instead="Chassis is Physics3D.Bodies.RigidBody:\n    chassis_mass is Real: 1000\n    inertia.mass: chassis_mass")
doc("UNKNOWN_MEMBER",
    "`.name` is used on a value whose type has no attribute or method of that name.",
    "Member access is checked against the declared types, through bases and traits.",
    example="x is Real: Math.Vec3.Z_AXIS().lenght()",
    use_instead="x is Real: Math.Vec3.Z_AXIS().length()")
doc("WRONG_KIND_OF_TYPE",
    "A model is used where a trait is needed (after `with`) or a trait is inherited with `is`.",
    "Models inherit from one model; traits are applied with `with`. Mixing them up changes what the "
    "object is.",
    example="Wheel is Physics3D.Bodies.RigidBody with Physics3D.Geometries.Box",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Box")
doc("IMPORT_FILE_NOT_FOUND",
    "The file an `import` names does not exist: `import @\"wheel.obj\" as WheelMesh` where there is no "
    "wheel.obj next to the .openplx file. An empty path and a path that names a folder are reported too.",
    "An `@\"...\"` path is relative to the folder of the importing file; a `$\"...\"` path is read after "
    "its `{VAR}` parts are taken from the environment (an unset variable is reported by `plx check`, "
    "A007). The runtime fails to load a model whose import is missing. The name is still bound, so the "
    "rest of the file is checked without follow-on errors.",
    example='import @"whel.obj" as WheelMesh',
    use_instead='import @"wheel.obj" as WheelMesh')
doc("IMPORT_NEEDS_ALIAS",
    "An `import` without `as` names a file whose stem is not a valid OpenPLX name (`my-robot.urdf`, "
    "`2wheels.obj`), so it binds no name.",
    "Without an alias the imported name is the file's stem; a stem with a dash, a space or a leading digit "
    "cannot be written as a name, so nothing in the file can use the import.",
    example='import @"my-robot.urdf"',
    use_instead='import @"my-robot.urdf" as MyRobot')
doc("NAME_FROM_OPAQUE_IMPORT",
    "A one-part type name that no file plx reads defines, in a file that imports a file plx cannot read "
    "(an `.agx` archive, a URDF): `ExtendedRod is PendulumScene_rod` after `import @\"pendulum.agx\"`.",
    "An AGX archive's bodies and systems keep their AGX names, which only the runtime can read from the "
    "archive. plx takes the name as an opaque model (no N001, no missing-attribute errors) and says so "
    "here; `plx check` lists what is built on it as not analysed (A042). A name close to one in scope "
    "is still reported as N001 with the suggestion (a typo).",
    example='import @"pendulum.agx"\n\nExtendedRod is PendulumScene_rod')

# ---------------------------------------------------------------- types
doc("TYPE_MISMATCH",
    "A value does not fit the declared type: a String where a Real is expected, a number where a Bool "
    "is expected, an object of the wrong model, an array where a single value is expected.",
    "OpenPLX is strictly typed; the value would be rejected when the model is loaded.",
    example="Ground is Physics3D.Bodies.RigidBody:\n    is_dynamic: 0",
    use_instead="Ground is Physics3D.Bodies.RigidBody:\n    is_dynamic: false")
doc("REAL_FOR_INT",
    "A Real is given where an Int is declared.",
    "The documentation accepts it, but whether the value is truncated or rounded is not specified.",
    example="count is Int: 2.5",
    use_instead="count is Int: 2")
doc("BRACE_LITERAL_LENGTH",
    "A `{...}` literal has a different number of values than the model it builds (Vec3 takes 3, "
    "Quat 4, Vec2 2, Matrix3x3 9).",
    "Brace literals are positional; a missing or extra value would shift every component.",
    example="main_axis: {0, 1}",
    use_instead="main_axis: {0, 1, 0}")
doc("WRONG_ARITY",
    "A function is called with a different number of arguments than its `fn` declaration, or an "
    "operator is declared with the wrong number of parameters.",
    "The bundles declare every function's signature; the call cannot match it.",
    example="x is Math.Vec3: Math.Vec3.from_xyz(1, 2)",
    use_instead="x is Math.Vec3: Math.Vec3.from_xyz(1, 2, 0)")
doc("ARGUMENT_TYPE",
    "A function argument does not fit the parameter's declared type.",
    "Arguments are checked against the `fn` declaration in the bundle.",
    example='x is Real: Math.Functions.sin("0.5")',
    use_instead="x is Real: Math.Functions.sin(0.5)")
doc("NO_OPERATOR",
    "An operator is used on types for which no `operator` is declared (for example `Quat * Vec3`).",
    "Only + - * / on numbers and the operators the bundles declare exist.",
    example="v is Math.Vec3: q * Math.Vec3.X_AXIS()",
    use_instead="v is Math.Vec3: q.rotate(Math.Vec3.X_AXIS())")
doc("VOID_IN_EXPRESSION",
    "A method declared without a return type is used in an expression.",
    "A method with no `->` cannot be called from OpenPLX (it is a runtime hook such as `on_init`).",
    example="x is Real: this.on_init()")
doc("BAD_CALL",
    "Something that is not a function is called, an instance method is called on a type, or (warning) "
    "a static function is called through an instance.",
    "Static functions belong to the type (`Math.Vec3.from_xyz`), instance methods to a value "
    "(`v.length()`); a const model is its own instance, so both work on it.",
    example="x is Real: Math.Vec3.length()",
    use_instead="x is Real: Math.Vec3.X_AXIS().length()")
doc("BAD_INDEX",
    "Something that is not an array is indexed, or the index is not an Int.",
    "Only arrays (`T[]`) can be indexed, and only with whole numbers.",
    example="x is Real: geometry.radius[0]",
    use_instead="x is Real: geometry.radius")

# ---------------------------------------------------------------- model structure
doc("REDECLARED_ATTRIBUTE",
    "`is` declares an attribute that the model already inherits.",
    "Redeclaring would create a second attribute with the same name. To give it a value use `:`; to "
    "narrow its type use `becomes`.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n    is_dynamic is Bool: false",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    is_dynamic: false")
doc("BECOMES_NOT_INHERITED",
    "`becomes` names an attribute that is not inherited.",
    "`becomes` specialises an existing attribute's type; there is nothing to specialise.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n    shape becomes Physics3D.Geometries.Box",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    shape is Physics3D.Geometries.Box")
doc("BECOMES_INCOMPATIBLE",
    "`becomes` gives an attribute a type that is not a subtype of its declared type (or of one "
    "alternative of a union).",
    "Code written against the base model must still work with the specialised attribute.",
    example="Contact is Physics.Interactions.SurfaceContact.Model:\n    friction becomes Physics.Geometries.Material")
doc("DUPLICATE_DEFINITION",
    "A name is defined twice: two top-level definitions in one namespace (across all files of a "
    "bundle), or two attributes with the same name in one model.",
    "Only one of them can be used; which one is undefined.")
doc("INHERITANCE_CYCLE",
    "A model or trait inherits from itself, directly or through others.",
    "The model would have no base to stop at; nothing about it can be resolved.",
    example="A is B\nB is A")
doc("REFERENCE_WITH_BLOCK",
    "A `reference` attribute is given a block.",
    "A block creates and configures a new object, which contradicts `reference`.")

# ---------------------------------------------------------------- bundles
doc("BUNDLES_UNAVAILABLE",
    "The language server could not load any OpenPLX bundles (shown once per file, instead of the "
    "model's diagnostics).",
    "Without the bundles no name can be resolved, so the editor shows only syntax errors until the "
    "setup is fixed: install `openplx-bundles`, or point `bundlePath` / `bundle-path` at a folder "
    "of bundles. The message says what failed.")
doc("BUNDLE_CONFIG_NAME",
    "A bundle's config.openplx has no `config is BundleConfig:` or no name.",
    "The name is how other bundles depend on this one.",
    example='config is BundleConfig:\n    version: "0.1.0"',
    use_instead='config is BundleConfig:\n    name: "MyBundle"\n    version: "0.1.0"')
doc("BAD_DEPENDENCY_STRING",
    "A dependency is not a string that starts with a bundle name.",
    "A dependency names the bundle it needs; plx cannot tell which bundle is meant.",
    example='dependencies: ["0.19.0"]',
    use_instead='dependencies: ["Physics==0.19.0"]')
doc("UNREAD_DEPENDENCY_FORM",
    "A dependency names a bundle but is not written as `Name`, `Name==1.2.3` or `Name@1.2.3`.",
    "These are the forms OpenPLX reads: `==` is what every official bundle's own config uses, `@` is "
    "the form in openplx.org's documentation, and a bare name takes whatever version is loaded. plx "
    "reads the string as the bare name, so it selects no official bundle version (see Bundle versions).",
    example='dependencies: ["Physics>=0.19"]',
    use_instead='dependencies: ["Physics==0.19.0"]')
doc("UNKNOWN_DEPENDENCY",
    "A bundle depends on a bundle that is not loaded, or two bundles share a name.",
    "Names from a missing dependency cannot resolve. Add its folder with `--bundle-path` or the "
    "`bundle-path` config key.")
doc("DEPENDENCY_CYCLE",
    "Bundles depend on each other in a cycle.",
    "A bundle must be loadable after its dependencies.")
doc("OUTSIDE_DEPENDENCIES",
    "A file in a bundle names something from a bundle that is not among its (transitive) dependencies.",
    "A bundle sees only the bundles it depends on; the name would not resolve for users of the bundle.")

# ---------------------------------------------------------------- conventions and hygiene
doc("NAMING_CONVENTION",
    "A definition does not follow the naming conventions: models and traits PascalCase, attributes "
    "snake_case, globals snake_case or UPPER_CASE (const instances may be lowercase).",
    "Consistent names make models easier to read and match the official bundles.",
    example="Scene is Physics3D.System:\n    boxTruck is BoxTruck",
    use_instead="Scene is Physics3D.System:\n    box_truck is BoxTruck")
doc("DEPRECATED_MEMBER",
    "An attribute that its bundle marks as deprecated (in its model's documentation or a comment) is used.",
    "Deprecated attributes are removed in later bundle versions.",
    example="Scene is Physics3D.System:\n    kinematically_controlled: [ground]",
    use_instead="Ground is Physics3D.Bodies.RigidBody:\n    is_dynamic: false")
doc("UNKNOWN_ANNOTATION",
    "An annotation name is not used by the official bundles and is not an `agx_` runtime setting.",
    "Annotations are free-form metadata, so any name is allowed; an unfamiliar one may be a typo.",
    example=".dco: \"A wheel\"",
    use_instead=".doc: \"A wheel\"")
doc("MISALIGNED_INDENTATION",
    "Lines of one block are indented differently.",
    "OpenPLX accepts it (some official files do it), but it is easy to misread, and it is also what a "
    "missing `:` on the line above looks like. `plx fmt` aligns siblings.")
