"""Plugin imports (`import @"wheel.obj" as WheelMesh`, newer than OpenPLX 0.19): the name an import
binds and what plx knows about the file behind it.

An import binds one name in the file's scope (spec B.1 item 6, C.2): the alias (`as Mesh`, or
`as robots.arm`, where `robots` is a namespace of this file only) or, without one, the file's stem
(`import @"inverted_pendulum.agx"` binds `inverted_pendulum`). The name is a model, usable as a type
or a base, built here as an ordinary model definition whose header is the import line, so lint,
check and the editor read it like any other model (definition and hover land on the import line):

* a mesh (`.obj`, `.stl`) is a `Visuals.Geometries.ExternalTriMeshGeometry` with `path` set to the
  file: placed in a System it is a visual mesh, as the AGXUnity importer makes it;
* an image is a `const` `Visuals.Materials.TextureMaterial` with that `path`: one shared texture,
  usable where a material is expected;
* anything else (an `.agx` archive, a URDF, ...) is *opaque*: plx cannot read it, so the model has
  no known base and its attributes are unknown rather than missing (no N002/N004/M002/M007
  cascades; `resolve.is_open`), and `plx check` says once what it could not analyse.

Nothing here reads the file system except `resolve_file` and `read_obj`, which the checker and
`plx check` call.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass

from plxtools import envpath
from plxtools.diagnostics import Span
from plxtools.model.symbols import ModelSym, Namespace
from plxtools.pickling import fast_pickling
from plxtools.syntax import ast

MESH_SUFFIXES = frozenset({".obj", ".stl"})
IMAGE_SUFFIXES = frozenset({".png", ".jpg", ".jpeg", ".bmp", ".tga", ".gif", ".tif", ".tiff", ".exr", ".hdr"})
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
_URI_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]+:")  # a scheme of 2+ letters: not a drive letter


def is_editor_buffer(path: str) -> bool:
    """An editor's buffer name (`untitled:Untitled-1`), not a file: it has no folder of its own."""
    return _URI_NAME.match(path) is not None

MESH_BASE = ("Visuals", "Geometries", "ExternalTriMeshGeometry")
IMAGE_BASE = ("Visuals", "Materials", "TextureMaterial")


@dataclass(slots=True, eq=False)
class ImportSym(ModelSym):
    """The model an import binds (kind "import"). `stmt` is a Declaration made from the import line."""

    import_stmt: ast.Import | None = None
    file_kind: str = "opaque"  # "mesh" | "image" | "opaque"
    suffix: str = ""

    @property
    def opaque(self) -> bool:
        return self.file_kind == "opaque"

    @property
    def written(self) -> str:
        return self.import_stmt.source.raw if self.import_stmt is not None else self.name


fast_pickling(ImportSym)


def file_kind(path_text: str) -> tuple[str, str]:
    """("mesh" | "image" | "opaque", suffix) for the file an import names."""
    suffix = os.path.splitext(path_text)[1].lower()
    if suffix in MESH_SUFFIXES:
        return "mesh", suffix
    if suffix in IMAGE_SUFFIXES:
        return "image", suffix
    return "opaque", suffix


def bound_name(stmt: ast.Import) -> tuple[list[str], Span]:
    """The dotted name an import binds and the span that names it (the alias, else the string).

    Without an alias the name is the file's stem, which may not be a valid name (the checker says so)."""
    if stmt.alias is not None and stmt.alias.parts:
        return [p.name for p in stmt.alias.parts], stmt.alias.parts[-1].span
    value = stmt.source.value
    stem = os.path.splitext(os.path.basename(value.replace("\\", "/").rstrip("/")))[0]
    return [stem], stmt.source.span


def valid_name(name: str) -> bool:
    return bool(_NAME.match(name))


def name_hint(stem: str) -> str:
    """A valid PascalCase name made from a file stem (`my-robot` -> `MyRobot`)."""
    words = [w for w in re.split(r"[^A-Za-z0-9]+", stem) if w]
    out = "".join(w[:1].upper() + w[1:] for w in words)
    return out if out and not out[0].isdigit() else "Imported" + out


def _qname(parts: list[str], span: Span) -> ast.QName:
    return ast.QName(span, [ast.Ident(span, p) for p in parts])


def import_symbol(stmt: ast.Import, unit, namespace: Namespace) -> tuple[list[str], ImportSym] | None:
    """The model an import binds, or None when it binds no usable name (a stem such as `my-robot`)."""
    parts, name_span = bound_name(stmt)
    if not parts or not all(valid_name(p) for p in parts):
        return None
    kind, suffix = file_kind(stmt.source.value)
    span = stmt.source.span
    texpr = None
    body = None
    if kind in ("mesh", "image"):
        base = MESH_BASE if kind == "mesh" else IMAGE_BASE
        texpr = ast.TypeExpr(span, [ast.TypeRef(span, _qname(list(base), span))])
        body = [ast.Assignment(span, span, _qname(["path"], span), stmt.source)]
    path = ast.QName(name_span, [ast.Ident(name_span, parts[-1])])
    decl = ast.Declaration(stmt.span, stmt.header, path, "is" if texpr is not None else None, texpr,
                           const=kind == "image", body=body, colon=body is not None)
    qname = ".".join(parts)
    sym = ImportSym(parts[-1], qname, "import", decl, unit, namespace, const=kind == "image", base_ref=texpr,
                    import_stmt=stmt, file_kind=kind, suffix=suffix)
    sym.doc = f"imported from {stmt.source.raw}: " + {
        "mesh": "a mesh file, read as a visual mesh (placed in a System it is rendered, it is no rigid body)",
        "image": "an image, read as a texture material",
        "opaque": "plx cannot read this kind of file, so its contents are not checked",
    }[kind]
    return parts, sym


def resolve_file(stmt: ast.Import, file_path: str | None) -> tuple[str | None, list[str]]:
    """(the full path the import names, the environment variables it needs that are not set).

    `@"..."` is relative to the importing file's folder; `$"..."` expands `{VAR}` from the environment
    first. The path is None when a variable is unset or the importing file has no folder."""
    s = stmt.source
    value = s.value
    if s.kind == "interp":
        value, unset = envpath.expand(value)
        if unset:
            return None, unset
    if not value:
        return None, []
    if os.path.isabs(value):
        return os.path.normpath(value), []
    if not file_path or is_editor_buffer(file_path):
        base = os.getcwd()
    else:
        base = os.path.dirname(os.path.abspath(file_path))
    return os.path.normpath(os.path.join(base, value)), []


@dataclass(slots=True)
class MeshInfo:
    vertices: int = 0
    faces: int = 0
    lo: tuple[float, float, float] | None = None
    hi: tuple[float, float, float] | None = None
    problem: str | None = None

    @property
    def extents(self) -> tuple[float, float, float] | None:
        if self.lo is None or self.hi is None:
            return None
        return tuple(h - lo for lo, h in zip(self.lo, self.hi))  # type: ignore[return-value]


def read_obj(path: str, limit: int = 64 << 20) -> MeshInfo:
    """Vertex and face counts and the axis-aligned bounds of a Wavefront OBJ file (`v` and `f` lines)."""
    info = MeshInfo()
    lo = [float("inf")] * 3
    hi = [float("-inf")] * 3
    from plxtools.cache.reads import open_regular

    try:
        fd, st = open_regular(path)  # a FIFO or a device (also behind a link) is refused, never read
        if st.st_size > limit:
            os.close(fd)
            info.problem = f"larger than {limit >> 20} MB: not read"
            return info
        with os.fdopen(fd, "rb") as fh:
            for n, raw in enumerate(fh, 1):
                if raw.startswith(b"v "):
                    try:
                        xyz = [float(t) for t in raw.split()[1:4]]
                    except ValueError:
                        info.problem = f"line {n}: a vertex with a value that is not a number"
                        return info
                    if len(xyz) < 3:
                        info.problem = f"line {n}: a vertex with fewer than 3 coordinates"
                        return info
                    info.vertices += 1
                    for i in range(3):
                        if xyz[i] < lo[i]:
                            lo[i] = xyz[i]
                        if xyz[i] > hi[i]:
                            hi[i] = xyz[i]
                elif raw.startswith(b"f "):
                    info.faces += 1
    except OSError as exc:
        info.problem = exc.strerror or str(exc)
        return info
    if info.vertices:
        info.lo, info.hi = tuple(lo), tuple(hi)  # type: ignore[assignment]
    else:
        info.problem = "no vertices ('v x y z' lines)"
    return info
