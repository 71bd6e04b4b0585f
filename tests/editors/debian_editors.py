"""Real Neovim, Helix and Emacs builds for the editor tests, taken from Debian's archive.

The CI machine runs Debian 12, whose Neovim (0.7) is older than the 0.10 our set-ups need, which
has no Helix and whose Emacs is 28. Debian 13 (trixie) ships Neovim 0.10, Helix 25.01 and Emacs 30,
unstable (sid) Neovim 0.12 and Helix 25.07: the versions users run. Their packages need a newer C library than the machine's, so
each suite's package and everything it depends on is unpacked into a folder of its own, and the
editor is started through that folder's dynamic loader (`ld.so --library-path`), never installed
into the system. The editor's children (`plx lsp`) start with the machine's own loader as usual.

    python tests/editors/debian_editors.py trixie neovim hx    # prints the launchers it made
"""

from __future__ import annotations

import lzma
import os
import re
import shutil
import subprocess
import sys
import tempfile
import urllib.request
from pathlib import Path

MIRROR = os.environ.get("PLX_DEBIAN_MIRROR", "http://deb.debian.org/debian")
SUITES = ("trixie", "sid")


def cache_root() -> Path:
    base = os.environ.get("PLX_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "editors"


def _fetch(url: str, dest: Path) -> None:
    tmp = dest.with_name(dest.name + ".part")
    with urllib.request.urlopen(url, timeout=120) as resp, open(tmp, "wb") as out:
        shutil.copyfileobj(resp, out)
    tmp.replace(dest)


def _index(suite: str, where: Path) -> dict[str, dict[str, str]]:
    """Package name -> fields of the suite's amd64 index, with virtual names mapped to a provider."""
    path = where / "Packages.xz"
    if not path.exists():
        _fetch(f"{MIRROR}/dists/{suite}/main/binary-amd64/Packages.xz", path)
    packages: dict[str, dict[str, str]] = {}
    providers: dict[str, dict[str, str]] = {}
    for stanza in lzma.open(path, "rt", encoding="utf-8").read().split("\n\n"):
        fields = dict(m.groups() for m in re.finditer(r"^([A-Za-z-]+): (.*)$", stanza, re.M))
        if "Package" not in fields:
            continue
        packages.setdefault(fields["Package"], fields)
        for provided in fields.get("Provides", "").split(","):
            name = provided.strip().split(" ")[0]
            if name:
                providers.setdefault(name, fields)
    for name, fields in providers.items():
        packages.setdefault(name, fields)
    return packages


def _closure(index: dict[str, dict[str, str]], wanted: list[str]) -> list[dict[str, str]]:
    """Every package `wanted` needs (Depends and Pre-Depends; the first of alternatives)."""
    seen: dict[str, dict[str, str]] = {}
    todo = list(wanted)
    while todo:
        name = todo.pop()
        fields = index.get(name)
        if fields is None:
            raise RuntimeError(f"package {name!r} is not in the index")
        if fields["Package"] in seen:
            continue
        seen[fields["Package"]] = fields
        for dep in f"{fields.get('Depends', '')},{fields.get('Pre-Depends', '')}".split(","):
            first = dep.split("|")[0].strip()
            if first:
                todo.append(re.split(r"[ (:]", first)[0])
    return list(seen.values())


def unpack(suite: str, packages: list[str]) -> Path:
    """The root folder holding `packages` of `suite` and all they depend on (made once, then reused)."""
    root = cache_root() / suite
    stamp = root / ("ready-" + "-".join(sorted(packages)))
    if stamp.exists():
        return root / "root"
    root.mkdir(parents=True, exist_ok=True)
    debs = root / "debs"
    debs.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory(dir=root) as tmp:
        for fields in _closure(_index(suite, Path(tmp)), packages):
            deb = debs / Path(fields["Filename"]).name
            if not deb.exists():
                _fetch(f"{MIRROR}/{fields['Filename']}", deb)
            subprocess.run(["dpkg-deb", "-x", str(deb), str(root / "root")], check=True)
    stamp.write_text("\n".join(packages) + "\n", encoding="utf-8")
    return root / "root"


def launcher(suite: str, package: str) -> Path:
    """A shell script that starts the suite's editor (`nvim` or `hx`) from its unpacked root."""
    root = unpack(suite, [package])
    libs = root / "usr/lib/x86_64-linux-gnu"
    loader = libs / "ld-linux-x86-64.so.2"
    if package == "neovim":
        # the runtime and the tree-sitter parsers (markdown, for hover) live where Debian's build put
        # them under /usr; point Neovim at them under the unpacked root instead
        env = f"VIMRUNTIME={root}/usr/share/nvim/runtime"
        exe, extra = root / "usr/bin/nvim", f'--cmd "set rtp+={root}/usr/lib/nvim"'
    elif package == "hx":
        env = f"HELIX_RUNTIME={root}/usr/lib/hx/runtime"
        exe, extra = root / "usr/bin/hx", ""
    elif package == "emacs-nox":
        # Emacs finds its Lisp, data, helpers, natively compiled Lisp and dump file by compiled-in
        # paths under /usr; each has a variable or option that points it elsewhere
        share = next((root / "usr/share/emacs").glob("[0-9]*"))
        env = (f"EMACSLOADPATH={share}/lisp EMACSDATA={share}/etc "
               f"EMACSPATH={next((root / 'usr/libexec/emacs').glob('*/x86_64-linux-gnu'))} "
               f"EMACSNATIVELOADPATH={root}/usr/lib/emacs/{share.name}/native-lisp")
        dump = next((root / "usr/libexec/emacs").glob("*/x86_64-linux-gnu/emacs-*.pdmp"))
        exe, extra = root / "usr/bin/emacs-nox", f'--dump-file="{dump}"'
    else:
        raise ValueError(package)
    script = root.parent / f"{package}.sh"
    script.write_text(f'#!/bin/sh\n{env} exec "{loader}" --library-path "{libs}" "{exe}" {extra} "$@"\n',
                      encoding="utf-8")
    script.chmod(0o755)
    return script


def main(argv: list[str]) -> int:
    if len(argv) < 2 or argv[0] not in SUITES:
        print(f"usage: debian_editors.py {{{'|'.join(SUITES)}}} PACKAGE...", file=sys.stderr)
        return 2
    for package in argv[1:]:
        print(launcher(argv[0], package))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
