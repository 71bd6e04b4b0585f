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


def index_folder(root: Path, version: str) -> dict:
    """The index record of one version from its bundle folder (the one holding Math/, Physics/, ...)."""
    from plxtools.model.apiindex.build import index_folder as build

    return build(root, version)


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
