"""The words of what the workspace knows about an unknown name: a bundle that is not loaded,
newer bundles, the official versions that have it (the facts' `bundle`, `newer`, `versions`)."""

from __future__ import annotations

from plxtools.model.agx import AGX_BUNDLE, ENV_VARS


def bundle_help(bundle: tuple | None) -> str | None:
    """How to load the bundle an unknown `Name.X` names (facts.UnknownName.bundle)."""
    if bundle is None:
        return None
    kind, a, b = bundle
    if kind == "nearby":
        return (f"a bundle named '{a}' is in {b} but is not loaded: pass --bundle-path {b} or add it to "
                "bundle-path in plx.toml / [tool.plx]")
    if kind == "dependency":
        return (f"'{a}' is a dependency in {b} but no bundle of that name is loaded: add its folder with "
                "--bundle-path or bundle-path in plx.toml")
    if a is not None and b is not None:  # AGX's own bundle, in the installation found
        return (f"'AGX' is AGX Dynamics' own bundle; the installation plx found ({a}) has it at {b}, loaded only "
                f"when its bundles are in use: drop openplx-version or pass --bundle-path {b}")
    return (f"'AGX' is AGX Dynamics' own bundle: it ships with an AGX installation (<AGX_DIR>/{'/'.join(AGX_BUNDLE)}), "
            "not with openplx-bundles; plx loads it with that installation's bundles when it finds one (agx-dir in "
            f"plx.toml, {', '.join(ENV_VARS)}, the agx Python package, the usual install folders), or pass its "
            "folder with --bundle-path")


def version_note(f) -> str | None:
    """Newer bundles that have the name, or the official versions that do (UnknownType)."""
    if f.versions is not None:
        written, spans, last, using = f.versions
        return (f"'{written}' exists in OpenPLX {spans}, not in {using} (the version in use): `plx migrate "
                f"--explain {last} {using}` lists what changed; `openplx-version` in plx.toml chooses another version")
    if f.newer is None:
        return None
    if f.newer[0] == "agx":
        _, written, using, agx_version, openplx_version, bundles = f.newer
        return (f"'{written}' is not in OpenPLX {using} (in use); AGX {agx_version}'s bundles (OpenPLX "
                f"{openplx_version}, {bundles}) have it: set bundle-path to that folder, or AGX_DIR, instead of "
                f"what chooses {using} now").replace("AGX 's", "AGX's")
    _, written, newest = f.newer
    return (f"'{written}' is in no openplx-bundles release up to {newest}: it may need a newer OpenPLX; AGX ships "
            "newer bundles: set AGX_DIR to an AGX installation or bundle-path to its bundles folder")


def broken_help(line: int) -> str:
    return f"its declaration at line {line + 1} has a syntax error; fix that first"
