"""Fake AGX installations for the tests: folders laid out like an installation, with OpenPLX
bundles copied from a real release (relabelled, or changed the way a newer OpenPLX might be)."""

from __future__ import annotations

import shutil
from pathlib import Path

from tests.conftest import bundle_root


def write(p: Path, text: str) -> Path:
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text, encoding="utf-8")
    return p


def fake_agx(root: Path, openplx: str = "0.20.1", layout: str = "data/openplx") -> Path:
    """An AGX installation folder whose bundles are newer than any PyPI release: the official
    Math/Physics/Physics3D relabelled, and a Vehicles bundle with a model 0.19.0 does not have."""
    bundles = root / layout
    for name in ("Math", "Physics", "Physics3D"):
        shutil.copytree(bundle_root() / name, bundles / name, ignore=shutil.ignore_patterns("__pycache__"))
        cfg = bundles / name / "config.openplx"
        cfg.write_text(cfg.read_text(encoding="utf-8").replace("0.19.0", openplx), encoding="utf-8")
    write(bundles / "Vehicles" / "config.openplx", f'config is BundleConfig:\n    name: "Vehicles"\n'
                                                   f'    version: "{openplx}"\n    dependencies: ["Physics3D=={openplx}"]\n')
    write(bundles / "Vehicles" / "TrackSystem.openplx", "TrackSystem is Physics3D.System\n")
    (root / "bin").mkdir(parents=True, exist_ok=True)
    return bundles


def agx_copy_of(release: Path, root: Path, layout: str = "data/openplx") -> Path:
    """An AGX installation whose bundles are a copy of a release's (every bundle, unchanged)."""
    bundles = root / layout
    shutil.copytree(release, bundles, ignore=shutil.ignore_patterns("__pycache__", "*.py"))
    (root / "bin").mkdir(parents=True, exist_ok=True)
    return bundles


def documented_agx(root: Path, openplx: str = "0.20.1") -> Path:
    """An installation laid out as Algoryx documents it (docs/bundles.md): the official bundles in
    `openplxbundles/`, AGX's own bundle in `data/openplx/agxBundle/`, plugins in `bin/plugins/`."""
    bundles = fake_agx(root, openplx, layout="openplxbundles")
    agx = root / "data" / "openplx" / "agxBundle"
    write(agx / "config.openplx", f'config is BundleConfig:\n    name: "AGX"\n    version: "{openplx}"\n'
                                  f'    dependencies: ["Physics3D"]\n')
    write(agx / "Cable.openplx", "Cable is Physics3D.System\n")
    (root / "bin" / "plugins").mkdir(parents=True, exist_ok=True)
    return bundles
