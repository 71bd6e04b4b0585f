"""An API index record built from a folder of bundles with plxtools' own parser and program.

The stored index (`data/*.json.gz`) is built by `scripts/build_api_index.py` from the released
wheels; `plx migrate` builds the same record at run time for bundles that are in no release (an AGX
installation ships newer ones), so both come from this one function and diff alike.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

FORMAT = 1


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
            out[sym.qname] = _model_record(program, sym, rel)
    return out


def _model_record(program, sym, rel: str) -> dict:
    """A model's or trait's record: place, base, traits, attributes, functions, deprecation, doc."""
    rec: dict = {"k": "t" if sym.is_trait else "m", "f": rel, "l": sym.stmt.header.start.line + 1}
    if sym.base_ref is not None:
        base = program.base_of(sym)
        rec["b"] = base.display() if base is not None else "?" + " or ".join(
            r.name.text for r in sym.base_ref.alternatives)
    traits = sorted(t.qname for t in program.traits_of(sym))
    if traits:
        rec["w"] = traits
    attrs = {name: _attr_record(program, sym, mem) for name, mem in sym.members.items()}
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
    return rec


def _attr_record(program, sym, mem) -> list:
    """[type, flags (d default, o optional, r reference, b becomes), line, doc hash]."""
    flags = ""
    if mem.value is not None or mem.stmt.body is not None:
        flags += "d"
    if mem.optional:
        flags += "o"
    if mem.reference:
        flags += "r"
    if mem.keyword == "becomes":
        flags += "b"
    return [_type_text(program, mem.stmt.type, sym.unit), flags, mem.stmt.header.start.line + 1,
            _short_hash(mem.doc)]


def index_folder(root: Path, version: str, use_cache: bool = False) -> dict:
    """The index record of the bundles in `root` (the folder holding Math/, Physics/, ...), loaded
    alone: no configured folder, environment or installed package takes part."""
    from plxtools.model.versions import BundleSet
    from plxtools.model.workspace import Workspace

    root = root.resolve()
    ws = Workspace(use_cache=use_cache, bundle_set=BundleSet(root, version, "indexed"))
    bundles = {b.name: b.version for b in ws.bundles.values()}
    return {"format": FORMAT, "version": version, "bundles": dict(sorted(bundles.items())),
            "models": index_program(ws, root)}
