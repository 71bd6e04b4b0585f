"""The API index of every official OpenPLX version, stored in the package (nothing fetched at run time).

One gzip'd JSON file per `openplx-bundles` version under `data/`, generated from the real wheels by
`scripts/build_api_index.py` with plxtools' own parser and program. A version's record is
`{"version", "bundles": {name: version}, "models": {qname: record}}` where a record has
`k` (m model, t trait, g global), `f`/`l` (bundle file and 1-based line), `b` (base, qualified),
`w` (traits), `a` (attributes: name -> [type, flags, line, doc hash]; flags: d default, o optional,
r reference, b becomes), `fn` (signatures), `dep` (deprecation notes by attribute, "" for the model)
and `doc` (a hash of the doc text). Types that did not resolve in that version start with `?`.
"""

from __future__ import annotations

import gzip
import json
from functools import lru_cache
from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"


class UnknownVersion(ValueError):
    """A version that the index does not hold."""


def version_key(v: str) -> tuple[int, ...]:
    return tuple(int(p) for p in v.split("."))


def parse_version(text: str) -> tuple[int, ...] | None:
    parts = text.strip().split(".")
    if not parts or not all(p.isdigit() for p in parts):
        return None
    return tuple(int(p) for p in parts)


@lru_cache(maxsize=1)
def versions() -> tuple[str, ...]:
    """Every indexed version, oldest first."""
    names = [p.name[: -len(".json.gz")] for p in DATA.glob("*.json.gz")]
    return tuple(sorted((n for n in names if parse_version(n)), key=version_key))


def check_version(v: str) -> str:
    """The version as indexed, or UnknownVersion with the versions that are available."""
    if v in versions():
        return v
    known = versions()
    span = f"{known[0]} to {known[-1]}" if known else "none"
    raise UnknownVersion(f"OpenPLX version '{v}' is not in plx's API index (indexed: {span}; "
                         f"{len(known)} released openplx-bundles versions)")


class ApiIndex:
    """One version's models, with the inherited view the diff and the rules need."""

    def __init__(self, data: dict):
        self.version: str = data["version"]
        self.bundles: dict[str, str] = data.get("bundles", {})
        self.models: dict[str, dict] = data["models"]
        self._all: dict[str, dict[str, list]] = {}

    def __contains__(self, qname: str) -> bool:
        return qname in self.models

    def base(self, qname: str) -> str | None:
        b = self.models.get(qname, {}).get("b")
        if not b or b.startswith("?"):
            return None
        return b.split(" with ")[0].removesuffix("[]")

    def ancestors(self, qname: str) -> list[str]:
        """The model, its bases and their traits, nearest first (no duplicates, cycles cut)."""
        out: list[str] = []
        stack = [qname]
        while stack:
            q = stack.pop(0)
            if q in out or q not in self.models:
                continue
            out.append(q)
            b = self.base(q)
            if b:
                stack.append(b)
            stack.extend(self.models[q].get("w", []))
        return out

    def all_attrs(self, qname: str) -> dict[str, list]:
        """Every attribute of a model, inherited ones included; each item is [type, flags, line, doc, declaring model]."""
        cached = self._all.get(qname)
        if cached is not None:
            return cached
        out: dict[str, list] = {}
        for anc in reversed(self.ancestors(qname)):
            for name, rec in self.models[anc].get("a", {}).items():
                out[name] = [*rec, anc]
        self._all[qname] = out
        return out

    def declaring(self, qname: str, attr: str) -> str | None:
        rec = self.all_attrs(qname).get(attr)
        return rec[4] if rec else None

    def subtypes(self, qname: str) -> list[str]:
        return sorted(q for q in self.models if q != qname and qname in self.ancestors(q))


@lru_cache(maxsize=None)
def load(version: str) -> ApiIndex:
    """One version's index (cached per process)."""
    check_version(version)
    with gzip.open(DATA / f"{version}.json.gz", "rb") as fh:
        return ApiIndex(json.loads(fh.read()))


NAMES = DATA / "names.json.gz"


def build_names() -> dict:
    """Every qualified name (models, traits, globals, and `Model.attr` with inherited attributes) and
    the versions that have it, as runs of indices into the version list: the data of `names.json.gz`."""
    vs = versions()
    seen: dict[str, list[int]] = {}
    for i, v in enumerate(vs):
        idx = load(v)
        for q in idx.models:
            seen.setdefault(q, []).append(i)
            for a in idx.all_attrs(q):
                seen.setdefault(f"{q}.{a}", []).append(i)
    names = {}
    for q, idxs in seen.items():
        runs: list[list[int]] = []
        for i in idxs:
            if runs and i == runs[-1][1] + 1:
                runs[-1][1] = i
            else:
                runs.append([i, i])
        names[q] = ",".join(str(a) if a == b else f"{a}-{b}" for a, b in runs)
    return {"versions": list(vs), "names": dict(sorted(names.items()))}


@lru_cache(maxsize=1)
def _names() -> dict:
    with gzip.open(NAMES, "rb") as fh:
        data = json.loads(fh.read())
    if data.get("versions") != list(versions()):  # stale summary: fall back to the version files
        return build_names()
    return data


def where_defined(qname: str) -> list[str]:
    """The indexed versions in which a model, trait or global `qname` exists, or `Model.attr` is an
    attribute of that model (inherited ones count), oldest first. Reads one small summary file."""
    data = _names() if NAMES.is_file() else build_names()
    runs = data["names"].get(qname)
    if not runs:
        return []
    vs = data["versions"]
    out = []
    for run in runs.split(","):
        a, _, b = run.partition("-")
        out.extend(vs[int(a): int(b or a) + 1])
    return out


def spans(found: list[str]) -> str:
    """Versions as readable runs of consecutive indexed versions: '0.15.0-0.17.33, 0.19.0'."""
    allv = versions()
    pos = {v: i for i, v in enumerate(allv)}
    runs: list[list[str]] = []
    for v in found:
        if runs and pos[v] == pos[runs[-1][-1]] + 1:
            runs[-1].append(v)
        else:
            runs.append([v])
    return ", ".join(r[0] if len(r) == 1 else f"{r[0]}-{r[-1]}" for r in runs)
