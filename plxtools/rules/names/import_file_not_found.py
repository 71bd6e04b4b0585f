"""The file an `import` names does not exist: `import @"wheel.obj" as WheelMesh` where there is no
wheel.obj next to the .openplx file. An empty path and a path that names a folder are reported too.

## Why it matters

An `@"..."` path is relative to the folder of the importing file; a `$"..."` path is read after its
`{VAR}` parts are taken from the environment (an unset variable is reported by `plx check`, A007).
The runtime fails to load a model whose import is missing. The name is still bound, so the rest of
the file is checked without follow-on errors.

## Example

```openplx
import @"whel.obj" as WheelMesh
```

## Use instead

```openplx
import @"wheel.obj" as WheelMesh
```
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.ImportNamesNoFile, found.ImportFileMissing)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if isinstance(f, found.ImportNamesNoFile):
            report("the import names no file (an empty path)", f.span,
                   help="write the file's path between the quotes: import @\"mesh.obj\" as Mesh")
            continue
        what = "is a folder, not a file" if f.is_folder else "does not exist"
        report(f"imported file {f.shown} {what}", f.span,
               help="a $\"...\" path takes each {VAR} from the environment" if f.from_environment
               else "an @\"...\" path is relative to the folder of the .openplx file that imports it")
