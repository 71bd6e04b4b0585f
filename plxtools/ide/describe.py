"""Markdown descriptions of symbols (hover, completion documentation) and where values come from."""

from __future__ import annotations

import os
import re

from plxtools.model.symbols import GlobalSym, MemberSym, MethodSym, ModelSym, Namespace, Ty
from plxtools.syntax import ast

MAX_DOC = 2500


def header_text(stmt: ast.Stmt, text: str) -> str:
    """The source of a statement's header, on one line (long values are cut)."""
    s = text[stmt.header.start.offset:stmt.header.end.offset]
    first, nl, _rest = s.partition("\n")
    first = first.strip()
    if nl:
        first += " …"
    if len(first) > 160:
        first = first[:157] + "…"
    return first


def expr_text(expr, unit) -> str:
    if expr is None or unit is None:
        return ""
    s = unit.tree.text[expr.span.start.offset:expr.span.end.offset]
    if "\n" in s:
        s = " ".join(part.strip() for part in s.splitlines())
    if len(s) > 120:
        s = s[:117] + "…"
    return s


def where(unit, stmt: ast.Stmt | None, official_root=None) -> str:
    if unit is None or stmt is None:
        return ""
    path = unit.path
    if official_root is not None:
        try:
            path = os.path.relpath(path, official_root)
        except ValueError:
            pass
    elif os.path.isabs(path):
        path = os.path.basename(path)
    return f"{path}:{stmt.header.start.line + 1}"


def trim_doc(doc: str | None) -> str:
    if not doc:
        return ""
    doc = doc.strip("\n")
    lines = doc.splitlines()
    # the bundles indent doc text inconsistently; remove the common indent
    indents = [len(ln) - len(ln.lstrip()) for ln in lines if ln.strip()]
    cut = min(indents) if indents else 0
    out = "\n".join(ln[cut:] for ln in lines).strip()
    if len(out) > MAX_DOC:
        out = out[:MAX_DOC].rstrip() + " …"
    return out


def attribute_note(owner_doc: str | None, name: str) -> str:
    """Bundle docs describe attributes inside the model's doc as `name - text` lines."""
    if not owner_doc:
        return ""
    lines = owner_doc.splitlines()
    pat = re.compile(rf"^\s*{re.escape(name)}\s*[-:–]\s+(.*)$")
    for i, ln in enumerate(lines):
        m = pat.match(ln)
        if m:
            out = [m.group(1).strip()]
            base = len(ln) - len(ln.lstrip())
            for nxt in lines[i + 1:]:
                if not nxt.strip() or len(nxt) - len(nxt.lstrip()) <= base or re.match(r"^\s*\w+\s*[-:–]\s", nxt):
                    break
                out.append(nxt.strip())
            return " ".join(out)
    return ""


def official_root_of(program, unit):
    if unit is None or not unit.official:
        return None
    ns = unit.namespace
    depth = len(ns.qname)
    path = os.path.dirname(unit.path)
    for _ in range(depth):
        path = os.path.dirname(path)
    return path


def model_kind(m: ModelSym) -> str:
    if m.kind == "import":
        return "import"
    if m.is_trait:
        return "trait"
    if m.const:
        return "const model"
    return "model"


def describe_model(program, m: ModelSym) -> str:
    m = program.concrete(m) if m.anonymous else m
    unit = m.unit
    head = m.qname
    if m.stmt is not None and unit is not None:
        # the qualified name with the definition's `is ...` part
        rest = ""
        if isinstance(m.stmt, ast.TraitDef):
            rest = f" is {m.stmt.base.text}" if m.stmt.base is not None else ""
            head = f"trait {m.qname}{rest}"
        else:
            base = program.base_of(m)
            rest = f" is {base.display()}" if base is not None else ""
            head = f"{'const ' if m.const else ''}{m.qname}{rest}"
    parts = [f"```openplx\n{head}\n```"]
    facts = [f"*{model_kind(m)}*"]
    if unit is not None:
        facts.append(f"bundle `{unit.bundle}`" if unit.bundle else "this file")
        loc = where(unit, m.stmt, official_root_of(program, unit))
        if loc:
            facts.append(f"`{loc}`")
    traits = program.traits_of(m)
    if traits:
        facts.append("with " + ", ".join(f"`{t.name}`" for t in traits))
    parts.append(" · ".join(facts))
    doc = trim_doc(m.doc)
    if doc:
        parts.append(doc)
    return "\n\n".join(parts)


def origin(program, mem: MemberSym, context: ModelSym | None) -> str:
    """Where an attribute comes from, seen from a model: own, inherited, or from a trait."""
    owner = mem.owner
    shown = program.concrete(owner) if owner.anonymous else owner
    if context is not None:
        if owner is context or (context.anonymous and owner is context):
            return "declared here"
    if owner.is_trait:
        return f"from trait `{shown.qname}`"
    if context is not None and owner is not context:
        return f"inherited from `{shown.qname}`"
    return f"declared in `{shown.qname}`"


def describe_member(program, mem: MemberSym, context: ModelSym | None = None,
                    path: tuple[str, ...] | None = None, skip_context: bool = False) -> str:
    ty = program.member_type(mem)
    unit = mem.owner.unit
    decl = header_text(mem.stmt, unit.tree.text) if unit is not None else mem.name
    parts = [f"```openplx\n{decl}\n```"]
    if context is not None and path:
        # the value in force first: the declaration's default below would otherwise read as it
        found = find_value(program, context, path, skip_self=skip_context)
        if found is not None:
            parts.insert(0, value_in_force(program, path[-1], found, mem, context))
    facts = [f"`{ty.display()}`"]
    flags = [w for w, on in (("optional", mem.optional), ("reference", mem.reference)) if on]
    if flags:
        facts.append(", ".join(flags))
    facts.append(origin(program, mem, context))
    if mem.value is not None:
        facts.append(f"default `{expr_text(mem.value, unit)}`")
    parts.append(" · ".join(facts))
    note = trim_doc(mem.doc) or attribute_note(mem.owner.doc, mem.name)
    if note:
        parts.append(note)
    elif ty.model is not None:
        tdoc = trim_doc(program.concrete(ty.model).doc)
        if tdoc:
            parts.append(f"`{program.concrete(ty.model).name}`: " + tdoc.split("\n\n", 1)[0])
    return "\n\n".join(parts)


def value_in_force(program, name: str, found, mem: MemberSym, context: ModelSym) -> str:
    """`mass: 1000` · set at line 3 in `Chassis` (or at file:line in another file; or the default)."""
    expr, setter, setter_unit = found
    shown = program.concrete(setter) if setter.anonymous else setter
    value = f"**`{name}: {expr_text(expr, setter_unit)}`**"
    if expr is mem.value:
        return f"{value} · the default, declared in `{shown.qname}`"
    line = expr.span.start.line + 1
    here = context.unit
    if setter_unit is not None and (here is None or setter_unit.path != here.path):
        where_ = f"`{os.path.basename(setter_unit.path)}:{line}`"
    else:
        where_ = f"line {line}"
    return f"{value} · set at {where_} in `{shown.qname}`"


def describe_global(program, g: GlobalSym) -> str:
    head = header_text(g.stmt, g.unit.tree.text)
    return f"```openplx\n{g.namespace.dotted + '.' if g.namespace.dotted else ''}{head}\n```\n\n*global value*"


def signature(meth: MethodSym) -> str:
    params = ", ".join(f"{p.name.name}: {p.type.name.text}{'[]' if p.type.array else ''}" for p in meth.stmt.params)
    ret = f" -> {meth.stmt.returns.name.text}{'[]' if meth.stmt.returns.array else ''}" if meth.stmt.returns else ""
    return f"{'static ' if meth.static else ''}fn {meth.name}({params}){ret}"


def describe_method(program, meth: MethodSym) -> str:
    owner = program.concrete(meth.owner) if meth.owner.anonymous else meth.owner
    parts = [f"```openplx\n{signature(meth)}\n```", f"*method of* `{owner.qname}`"]
    if meth.stmt.returns is None:
        parts[-1] += " · returns nothing (cannot be used in an expression)"
    note = attribute_note(meth.owner.doc, meth.name)
    if note:
        parts.append(note)
    return "\n\n".join(parts)


def describe_namespace(program, ns: Namespace) -> str:
    names = sorted(ns.symbols)
    subs = sorted(ns.children)
    parts = [f"```openplx\n{ns.dotted}\n```", f"*namespace* in bundle `{ns.bundle or ns.qname[0]}`"]
    if subs:
        parts.append("namespaces: " + ", ".join(f"`{s}`" for s in subs[:30]) + (" …" if len(subs) > 30 else ""))
    if names:
        parts.append("defines: " + ", ".join(f"`{s}`" for s in names[:40]) + (" …" if len(names) > 40 else ""))
    return "\n\n".join(parts)


PRIMITIVE_DOCS = {
    "Real": "a floating-point number (Int values convert to Real)",
    "Int": "a whole number",
    "Bool": "`true` or `false`",
    "String": 'text: `"..."`, or `"""..."""` over several lines',
    "Blob": "binary data (`{}`)",
    "BundleConfig": "a bundle's configuration: name, version, dependencies",
}


def describe(program, target, context: ModelSym | None = None, path: tuple[str, ...] | None = None,
             skip_context: bool = False) -> str:
    if isinstance(target, ModelSym):
        return describe_model(program, target)
    if isinstance(target, MemberSym):
        return describe_member(program, target, context, path, skip_context)
    if isinstance(target, GlobalSym):
        return describe_global(program, target)
    if isinstance(target, MethodSym):
        return describe_method(program, target)
    if isinstance(target, Namespace):
        return describe_namespace(program, target)
    if isinstance(target, str):
        return f"```openplx\n{target}\n```\n\n*primitive type*: {PRIMITIVE_DOCS.get(target, '')}"
    return ""


# ------------------------------------------------------------------ where a value comes from


def precedence(program, model: ModelSym) -> list[ModelSym]:
    """Models whose assignments apply to `model`, the strongest first: itself, its traits, its base...

    The reverse of the one class ordering (model/resolve.py)."""
    return program.ancestors(model)


def _in_body(body: list[ast.Stmt] | None, path: tuple[str, ...]):
    for s in body or ():
        if isinstance(s, (ast.Assignment, ast.Declaration)) and s.path.parts:
            names = tuple(p.name for p in s.path.parts)
            if names == path and s.value is not None:
                return s.value
            if path[: len(names)] == names and len(path) > len(names) and s.body:
                got = _in_body(s.body, path[len(names):])
                if got is not None:
                    return got
    return None


def find_value(program, model: ModelSym, path: tuple[str, ...], skip_self: bool = False, depth: int = 0):
    """The expression that gives `model.<path>` its value, the model that sets it, and its unit."""
    if depth > 30 or not path:
        return None
    for m in precedence(program, model):
        if skip_self and m is model:
            continue
        body = getattr(m.stmt, "body", None) if m.stmt is not None else None
        got = _in_body(body, path)
        if got is not None:
            return got, m, m.unit
    mem = program.all_members(model).get(path[0])
    if mem is None:
        return None
    if len(path) == 1:
        return (mem.value, mem.owner, mem.owner.unit) if mem.value is not None else None
    ty: Ty = program.member_type(mem)
    if ty.model is None:
        return None
    return find_value(program, ty.model, path[1:], False, depth + 1)
