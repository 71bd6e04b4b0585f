"""`plx migrate --explain FROM TO`: the API changes between two official versions, grouped and readable."""

from __future__ import annotations

import json
import sys

from plxtools.model.apichanges import AUTO, INFO, KIND_ORDER, KIND_TITLES, PERSON, TABLE, Change, between, changes, summary
from plxtools.migrate import endpoints
from plxtools.model.apichanges import RenameTableError
from plxtools.model.apichanges import changes_over
from plxtools.model.apiindex import UnknownVersion
from plxtools.model.apiindex import versions, version_key

HANDLING_TEXT = {AUTO: "automatic", TABLE: "reviewed table", PERSON: "needs a person", INFO: "nothing to migrate"}


def describe(c: Change) -> str:
    """One line for a change (without its group title)."""
    if c.kind in ("model-moved", "model-renamed"):
        text = f"{c.old} -> {c.new}"
    elif c.kind == "attr-renamed":
        text = f"{c.model}.{c.old} -> {c.new}"
    elif c.kind in ("attr-type-changed", "fn-changed", "base-changed"):
        text = f"{c.subject()}: {c.old} -> {c.new}"
    elif c.kind in ("attr-added", "attr-added-required", "attr-removed"):
        text = f"{c.subject()} ({c.new or c.old})"
    elif c.kind == "fn-removed":
        text = f"{c.model}: {c.old}"
    elif c.kind == "fn-added":
        text = f"{c.model}: {c.new}"
    elif c.kind == "deprecated":
        text = f"{c.subject()}: {c.detail}"
    else:
        text = c.subject()
    return f"{text}  [{c.since}]"


def render_text(from_v: str, to_v: str, cs: list[Change], apart: int | None = None) -> str:
    counts = summary(cs)
    apart = len(between(from_v, to_v)) - 1 if apart is None else apart
    lines = [f"OpenPLX API changes from {from_v} to {to_v} ({apart} indexed versions apart)",
             f"{counts[AUTO]} automatic, {counts[TABLE]} from the reviewed table, {counts[PERSON]} need a person, "
             f"{counts[INFO]} additions or notes. [V] is the first version with the change."]
    for kind in KIND_ORDER:
        group = [c for c in cs if c.kind == kind]
        if not group:
            continue
        handling = {c.handling for c in group}
        how = ", ".join(HANDLING_TEXT[h] for h in (AUTO, TABLE, PERSON, INFO) if h in handling)
        lines.append("")
        lines.append(f"{KIND_TITLES[kind]} ({len(group)}; {how}):")
        for c in group:
            mark = " (table)" if c.handling == TABLE else ""
            lines.append(f"  {describe(c)}{mark}")
    if not cs:
        lines.append("")
        lines.append("No API changes.")
    return "\n".join(lines) + "\n"


def render_json(from_v: str, to_v: str, cs: list[Change]) -> str:
    return json.dumps({"from": from_v, "to": to_v, "counts": summary(cs), "changes": [c.to_json() for c in cs]},
                      indent=2) + "\n"


def run_explain(from_v: str, to_v: str, output_format: str = "text") -> int:
    """Print the change list; exit 2 with one clear line for an unknown version or a backward range."""

    try:
        from_label, to_label, cs, apart = _changes(from_v, to_v)
        text = render_json(from_label, to_label, cs) if output_format == "json" else \
            render_text(from_label, to_label, cs, apart)
    except (UnknownVersion, RenameTableError, ValueError) as exc:
        print(f"plx migrate: {exc}", file=sys.stderr)
        return 2
    sys.stdout.write(text)
    return 0


def _changes(from_v: str, to_v: str) -> tuple[str, str, list[Change], int | None]:
    """The changes between two releases of the stored index, or, when either version is the one
    of the AGX installation found (its bundles indexed now), along the chain of indexes between."""

    if from_v in versions() and to_v in versions():
        return from_v, to_v, changes(from_v, to_v), None

    src = endpoints.source([], from_v, "FROM")
    dst = endpoints.target([], to_v, "TO")
    if version_key(src.version) > version_key(dst.version):
        raise ValueError(f"'{from_v}' is newer than '{to_v}': plx migrates forward only")
    chain = endpoints.chain(src, dst)
    return src.label, dst.label, changes_over(chain), len(chain) - 1
