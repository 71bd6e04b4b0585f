"""The files one load of a model read, to watch for live reload.

The cache layer keeps its own dependency record; this small function is the view's stand-in
until that record is public, and can be swapped for it: it returns the model file, the
configuration file that applied, every file of the user bundles in the workspace (imports resolve
to them) and the mesh files the scene names.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any


def files_read(prepared: Any) -> list[str]:
    """Absolute paths of the files behind ``prepared`` (a :class:`plxtools.check.api.Prepared`)."""
    fc = prepared.fc
    out: list[str] = [os.path.abspath(prepared.path)]
    src = getattr(fc.cfg, "source", None)
    if src:
        out.append(os.path.abspath(src))
    ws = prepared.workspace
    for b in getattr(ws, "bundles", {}).values() if ws is not None else ():
        if b.official:
            continue
        out.append(os.path.abspath(b.root / "config.openplx"))
        out.extend(os.path.abspath(f) for f in b.files())
    scene = getattr(fc, "scene", None)
    for body in getattr(scene, "bodies", ()):
        for g in body.geoms:
            if g.mesh_file:
                f = g.mesh_file
                if not os.path.isabs(f) and scene.base_dir:
                    f = os.path.join(scene.base_dir, f)
                out.append(os.path.abspath(f))
    return list(dict.fromkeys(out))


def config_candidates(path: str) -> list[str]:
    """plx.toml / pyproject.toml beside the model and in its parent folders: creating one changes
    the load even though this load read none."""
    out = []
    for d in [Path(path).resolve().parent, *Path(path).resolve().parents]:
        out += [str(d / "plx.toml"), str(d / "pyproject.toml")]
        if (d / ".git").exists():
            break
    return out


def stamp(path: str) -> tuple[int, int] | None:
    """What changes when a file is saved: (mtime_ns, size), None when it does not exist."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)
