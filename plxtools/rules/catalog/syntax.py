"""Syntax rules (S...): reported by the parser, always on, cannot be suppressed away from the file."""

from plxtools.rules.catalog.pages import doc


doc("BINARY_FILE",
    "The file contains NUL bytes, so it is not OpenPLX text.",
    "A binary file with an `.openplx` name is almost always a mistake (a mesh or archive saved with the "
    "wrong name). Nothing in it can be checked.")
doc("INVALID_UTF8",
    "The file has bytes that are not valid UTF-8. The position of the first bad byte is reported.",
    "OpenPLX source is UTF-8. The rest of the file is still checked with the bad bytes replaced, but "
    "`plx fmt` refuses to rewrite such a file so nothing is lost.")
doc("TAB_INDENTATION",
    "A tab character is used for indentation.",
    "Indentation decides which block a line belongs to. No official file uses tabs, and a tab's width "
    "is ambiguous; plxtools counts a tab as reaching the next multiple of 4 columns. When the block a "
    "line belongs to would differ with 8-wide tabs, it is an error (the cause of everything that would "
    "follow from the wrong block): the line is read as part of the deeper block, and `plx fmt` refuses "
    "the file.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n\tis_dynamic: true",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    is_dynamic: true")
doc("UNBALANCED_BRACKET",
    "A `(`, `[` or `{` is never closed, or a closing bracket has no matching opener.",
    "Brackets let an expression continue over several lines, so a missing closer would swallow the "
    "lines after it. Bracket depth decides: a line inside an open bracket continues the statement "
    "unless, at or left of the statement's indentation, it begins the way only a statement can "
    "(`x is`, `x becomes`, `.a:`, `const`, `fn`, ...); there the expression ends and the opener is "
    "reported. A continued `fn` parameter list (`b: Real`) is only cut when the end of the file shows "
    "the list never closes, at its first such line.",
    example="connectors: [a.connector, b.connector",
    use_instead="connectors: [a.connector, b.connector]")
doc("INVALID_NUMBER",
    "A number is malformed, for example `1.` or `2x`.",
    "OpenPLX numbers are digits with an optional fraction (`0.5`) and exponent (`1e-3`); a trailing dot "
    "or a letter glued to a number is not a number.",
    example="mass: 1.",
    use_instead="mass: 1.0")
doc("EMPTY_BACKTICK_NAME",
    "A backtick-quoted name has no characters.",
    "Backticks quote names that contain dots; an empty one names nothing.")
doc("NESTING_TOO_DEEP",
    "Brackets are nested more than 200 levels deep on one line, or an expression is more than 500 "
    "levels deep (20,000 unary minus signs, a sum of 1,000 terms).",
    "Such an expression is machine-generated or broken; refusing it with a located error keeps every "
    "later stage (checker, evaluator, formatter) safe. Give the parts names and combine those.")
doc("UNEXPECTED_CHARACTER",
    "A character that is not part of OpenPLX, such as `=`, `<` or `'`.",
    "OpenPLX gives values with `:` and its expressions use only `+ - * /` and unary minus; there are "
    "no comparisons, no logic operators and no single-quoted strings.",
    example="x is Real: 1 == 2",
    use_instead="x is Real: 1")
doc("UNTERMINATED_STRING",
    'A `"..."` string does not close on its line, or a `"""` string never closes.',
    "A plain string must end on the same line; a triple-quoted string that never closes would turn the "
    "rest of the file into text.",
    example='unique_name: "Wheel',
    use_instead='unique_name: "Wheel"')
doc("EXPECTED_INDENTED_BLOCK",
    "A line ends with `:` but no more-indented line follows it.",
    "A `:` at the end of a line opens a block. Without a block and without a value the line means "
    "nothing; usually the block was not indented or the value is missing.",
    example="size:\nx: 1",
    use_instead="size:\n    x: 1")
doc("INVALID_SYNTAX",
    "A line does not follow the OpenPLX grammar. The message names what was found and what could "
    "come there instead.",
    "The line is skipped; the lines around it are still checked.",
    example="mass: 10 20",
    use_instead="mass: 10")
doc("MISPLACED_STATEMENT",
    "A statement stands where the language does not allow it: an assignment or `becomes` at top level, "
    "a trait or operator inside a model, `const` on a nested attribute, a method outside a model.",
    "Top level holds models, traits, global attributes, operators and imports; members belong inside "
    "a model's block.",
    example="mass: 10",
    use_instead="Box is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10")
doc("INCOMPLETE_MEMBER",
    "A name stands alone on a line inside a block.",
    "Inside a model every line declares (`x is T`), specialises (`x becomes T`) or assigns (`x: 1`). "
    "A lone name is usually a half-written line.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n    radius",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    radius is Real: 0.3")
doc("NON_LITERAL_ANNOTATION",
    "An annotation (`.name: value`) has a value that is not a string, number, true or false.",
    "Annotations are metadata read by tools and runtimes; the language allows only literal values there.",
    example=".doc: description",
    use_instead='.doc: "A wheel with a rubber tyre"')
doc("INDENTATION_BETWEEN_LEVELS",
    "A line is indented less than the block it follows but more than the block around that one.",
    "Blocks are given by indentation, so a line between two levels has no meaning of its own: it could "
    "end the inner block or belong to it. plxtools reads it as part of the inner block (so the lines "
    "after it stay where they are) and reports it as an error; `plx fmt` refuses the file until it is "
    "fixed, rather than moving code out of its block.",
    example="Wheel is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Cylinder:\n"
            "        radius: 0.4\n      height: 0.3",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    geometry is Physics3D.Geometries.Cylinder:\n"
                "        radius: 0.4\n        height: 0.3")
doc("MISSING_COLON",
    "A header line (`x is T`, `x becomes T`, a lone name) has no `:` at its end, but the lines "
    "after it are indented under it.",
    "A block opens only with `:`. Without it the indented lines are read as siblings of the header, "
    "so everything in them seems misplaced (assignments at top level, attributes missing from the "
    "model). The missing `:` is the cause: it is reported on the header line with the fix, and the "
    "indented lines are read as the header's block, so nothing else is reported because of it.",
    example="Wheel is Physics3D.Bodies.RigidBody\n    inertia.mass: 10",
    use_instead="Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10")
