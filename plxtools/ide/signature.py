"""Signature help for `fn` calls: `Math.Vec3.from_xyz(1, |` shows the parameters, the current one marked."""

from __future__ import annotations

from plxtools.ide.context import (
    MethodRef,
    block_context,
    chain_before,
    eval_chain,
    member_value,
    owners_for_line,
)
from plxtools.ide.describe import attribute_note, signature
from plxtools.ide.host import FileState
from plxtools.ide.types import ParameterInfo, SignatureHelpResult, SignatureInfo


def _open_call(text: str, offset: int, limit: int) -> tuple[int, int] | None:
    """The offset of the unclosed '(' around the cursor, and how many commas precede the cursor."""
    depth = 0
    commas = 0
    i = offset
    in_str = False
    while i > max(limit, 0):  # (limit -1: back to the start of the file, never past it)
        i -= 1
        ch = text[i]
        if ch == '"':
            in_str = not in_str
            continue
        if in_str:
            continue
        if ch in ")]}":
            depth += 1
        elif ch in "[{":
            if depth == 0:
                commas = 0  # a comma inside a literal argument is not an argument separator
                continue
            depth -= 1
        elif ch == "(":
            if depth == 0:
                return i, commas
            depth -= 1
        elif ch == "," and depth == 0:
            commas += 1
    return None


def signature_help(st: FileState, offset: int) -> SignatureHelpResult | None:
    if st.program is None or st.unit is None:
        return None
    idx = st.tree.index
    pos = idx.pos(offset)
    # a call may span lines inside brackets: look back a few lines at most
    limit = idx.offset(max(0, pos.line - 20), 0) - 1
    found = _open_call(st.text, offset, max(limit, -1))
    if found is None:
        return None
    paren, commas = found
    chain = chain_before(st.text, paren)
    if not chain or "." not in chain and not chain.isidentifier():
        return None
    # the scope of names is the outer model of the line the call starts on
    ppos = idx.pos(paren)
    line_text = idx.line_text(ppos.line)
    indent = len(line_text) - len(line_text.lstrip())
    owners = owners_for_line(st.tree, ppos.line, indent)
    ctx = block_context(st, owners) if owners else None
    outer = ctx.outer if ctx is not None else None
    head, dot, last = chain.rpartition(".")
    if not dot:
        return None
    base = eval_chain(st, outer, head)
    f = member_value(st, base, last) if base is not None else None
    if not isinstance(f, MethodRef):
        return None
    meth = f.method
    params = [ParameterInfo(f"{p.name.name}: {p.type.name.text}{'[]' if p.type.array else ''}")
              for p in meth.stmt.params]
    doc = attribute_note(meth.owner.doc, meth.name) or None
    sig = SignatureInfo(signature(meth), params, doc)
    active = min(commas, max(len(params) - 1, 0))
    return SignatureHelpResult([sig], 0, active)


def param_label_offsets(sig: SignatureInfo) -> list[tuple[int, int]]:
    """Where each parameter's label sits inside the signature label (for clients that want offsets)."""
    out = []
    start = sig.label.find("(") + 1
    for p in sig.parameters:
        i = sig.label.find(p.label, start)
        out.append((i, i + len(p.label)))
        start = i + len(p.label)
    return out
