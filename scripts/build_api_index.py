#!/usr/bin/env python3
"""Build the API index of official OpenPLX versions from the real `openplx-bundles` wheels.

The index lets plx say what changed between versions (`plx migrate --explain`) and in which version
a name exists, without fetching anything at run time. Each version becomes one gzip'd JSON file in
plxtools/model/apiindex/data/, written deterministically (sorted keys, gzip mtime 0), so re-running
the script on the same wheels gives identical bytes.

Regenerate (all released versions; wheels are cached in --wheels):

    python scripts/build_api_index.py --all

or for some versions only:

    python scripts/build_api_index.py 0.17.26 0.19.0

The bundles are read with plxtools' own parser and program (the same Workspace that `plx lint`
uses), never with a second parser.
"""

from __future__ import annotations

import argparse
import gzip
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DATA = REPO / "plxtools" / "model" / "apiindex" / "data"
FORMAT = 1
_VERSION = re.compile(r"^\d+(\.\d+)*$")


def version_key(v: str) -> tuple[int, ...]:
    return tuple(int(p) for p in v.split("."))


def released_versions() -> list[str]:
    """Every released version of openplx-bundles, asked of pip (the ordinary client)."""
    out = subprocess.run([sys.executable, "-m", "pip", "index", "versions", "openplx-bundles"],
                         capture_output=True, text=True, check=True).stdout
    m = re.search(r"Available versions:\s*(.*)", out)
    if not m:
        raise SystemExit("build_api_index: pip did not list the versions of openplx-bundles")
    return sorted((v.strip() for v in m.group(1).split(",") if _VERSION.match(v.strip())), key=version_key)


def wheel_for(version: str, wheels: Path) -> Path:
    path = wheels / f"openplx_bundles-{version}-py3-none-any.whl"
    if not path.is_file():
        wheels.mkdir(parents=True, exist_ok=True)
        subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-deps",
                        f"openplx-bundles=={version}", "-d", str(wheels)], check=True)
    if not path.is_file():
        raise SystemExit(f"build_api_index: pip did not produce {path.name}")
    return path


def _short_hash(text: str | None) -> str | None:
    if not text:
        return None
    return hashlib.sha1(" ".join(text.split()).encode()).hexdigest()[:10]


def _type_text(program, texpr, unit) -> str:
    """A type as qualified names (relative names in the source are resolved), else its source text."""
    ty = program.resolve_type_expr(texpr, unit)
    if not ty.unknown:
        return ty.display()
    parts = [r.name.text + ("[]" if r.array else "") for r in texpr.alternatives]
    text = " or ".join(parts)
    if texpr.traits:
        text += " with " + ", ".join(q.text for q in texpr.traits)
    return "?" + text  # '?': did not resolve in this version


def _ref_text(program, ref, unit) -> str:
    ty = program.resolve_type_ref(ref, unit)
    return ty.display() if not ty.unknown else "?" + ref.name.text + ("[]" if ref.array else "")


def index_program(ws, root: Path) -> dict:
    """Every model, trait and global of the loaded bundles, as plain data."""
    from plxtools.model.symbols import GlobalSym, ModelSym

    program = ws.program
    out: dict[str, dict] = {}
    stack = [program.root]
    while stack:
        ns = stack.pop()
        stack.extend(ns.children.values())
        for sym in ns.symbols.values():
            rel = Path(sym.unit.path).resolve().relative_to(root).as_posix()
            if isinstance(sym, GlobalSym):
                out[sym.qname] = {"k": "g", "f": rel, "l": sym.stmt.header.start.line + 1,
                                  "t": _type_text(program, sym.stmt.type, sym.unit)}
                continue
            assert isinstance(sym, ModelSym)
            rec: dict = {"k": "t" if sym.is_trait else "m", "f": rel, "l": sym.stmt.header.start.line + 1}
            if sym.base_ref is not None:
                base = program.base_of(sym)
                rec["b"] = base.display() if base is not None else "?" + " or ".join(
                    r.name.text for r in sym.base_ref.alternatives)
            traits = sorted(t.qname for t in program.traits_of(sym))
            if traits:
                rec["w"] = traits
            attrs = {}
            for name, mem in sym.members.items():
                flags = ""
                if mem.value is not None or mem.stmt.body is not None:
                    flags += "d"
                if mem.optional:
                    flags += "o"
                if mem.reference:
                    flags += "r"
                if mem.keyword == "becomes":
                    flags += "b"
                attrs[name] = [_type_text(program, mem.stmt.type, sym.unit), flags,
                               mem.stmt.header.start.line + 1, _short_hash(mem.doc)]
            if attrs:
                rec["a"] = attrs
            fns = {}
            for name, meth in sym.methods.items():
                params = ", ".join(f"{p.name.name}: {_ref_text(program, p.type, sym.unit)}" for p in meth.stmt.params)
                ret = f" -> {_ref_text(program, meth.stmt.returns, sym.unit)}" if meth.stmt.returns else ""
                fns[name] = f"{'static ' if meth.static else ''}fn {name}({params}){ret}"
            if fns:
                rec["fn"] = fns
            if sym.deprecated:
                rec["dep"] = dict(sym.deprecated)
            if sym.doc:
                rec["doc"] = _short_hash(sym.doc)
                if "deprecated" in sym.doc.lower() and not sym.deprecated:
                    rec["dep"] = {"": next(line.strip() for line in sym.doc.splitlines()
                                           if "deprecated" in line.lower())}
            out[sym.qname] = rec
    return out


def index_folder(root: Path, version: str) -> dict:
    """The index record of one version from its bundle folder (the one holding Math/, Physics/, ...)."""
    from plxtools.model.workspace import Workspace

    root = root.resolve()
    ws = Workspace([root], use_cache=False)
    if ws.official_root != root:
        raise SystemExit(f"build_api_index: {version}: the bundles were not loaded from {root}")
    bundles = {b.name: b.version for b in ws.bundles.values()}
    return {"format": FORMAT, "version": version, "bundles": dict(sorted(bundles.items())),
            "models": index_program(ws, root)}


def build_version(version: str, wheels: Path) -> dict:
    wheel = wheel_for(version, wheels)
    with tempfile.TemporaryDirectory(prefix="plx-apiindex-") as tmp:
        with zipfile.ZipFile(wheel) as zf:
            zf.extractall(tmp)
        return index_folder(Path(tmp) / "openplxbundles", version)


def write_index(data: dict, folder: Path) -> Path:
    """Deterministic bytes: sorted keys, compact separators, gzip without a timestamp or name."""
    folder.mkdir(parents=True, exist_ok=True)
    raw = json.dumps(data, sort_keys=True, separators=(",", ":"), ensure_ascii=False).encode()
    return _write_gz(raw, folder / f"{data['version']}.json.gz")


def write_names() -> Path:
    """The name -> versions summary (`names.json.gz`) from the version files now in the package."""
    from plxtools.model import apiindex

    apiindex.versions.cache_clear()
    apiindex.load.cache_clear()
    raw = json.dumps(apiindex.build_names(), sort_keys=True, separators=(",", ":")).encode()
    return _write_gz(raw, apiindex.NAMES)


def _write_gz(raw: bytes, path: Path) -> Path:
    tmp = path.with_suffix(".tmp")
    with open(tmp, "wb") as fh:
        with gzip.GzipFile(filename="", mode="wb", fileobj=fh, mtime=0, compresslevel=9) as gz:
            gz.write(raw)
    os.replace(tmp, path)
    return path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("versions", nargs="*", help="versions to index (default with --all: every released one)")
    ap.add_argument("--all", action="store_true", help="index every released version (asks pip for the list)")
    ap.add_argument("--wheels", type=Path, default=Path(os.environ.get("PLX_CACHE_DIR", Path.home() / ".cache"))
                    / "apiindex-wheels", help="folder where the wheels are downloaded and kept")
    ap.add_argument("--names-only", action="store_true",
                    help="only rewrite names.json.gz (the name -> versions summary) from the stored version files")
    ap.add_argument("--out", type=Path, default=DATA, help=f"output folder (default {DATA.relative_to(REPO)})")
    args = ap.parse_args(argv)
    if args.names_only:
        print(f"wrote {write_names()}", file=sys.stderr)
        return 0
    versions = released_versions() if args.all else args.versions
    if not versions:
        ap.error("name versions or pass --all")
    for v in versions:
        if not _VERSION.match(v):
            ap.error(f"not a version: {v!r}")
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 20000))
    t0 = time.perf_counter()
    for v in sorted(versions, key=version_key):
        t = time.perf_counter()
        path = write_index(build_version(v, args.wheels), args.out)
        print(f"{v}: {path.stat().st_size} bytes in {time.perf_counter() - t:.2f} s", file=sys.stderr)
    if args.out == DATA:
        write_names()
    print(f"{len(versions)} versions in {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
