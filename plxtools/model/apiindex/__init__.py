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

from plxtools.model.resolve import replaces

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


def _keyword(flags: str) -> str:
    return "becomes" if "b" in flags else "is"


class ApiIndex:
    """One version's models, with the inherited view the diff and the rules need."""

    def __init__(self, data: dict):
        self.version: str = data["version"]
        self.bundles: dict[str, str] = data.get("bundles", {})
        self.models: dict[str, dict] = data["models"]
        self._all: dict[str, dict[str, list]] = {}
        self._lin: dict[str, list[str]] = {}

    def __contains__(self, qname: str) -> bool:
        return qname in self.models

    def base(self, qname: str) -> str | None:
        b = self.models.get(qname, {}).get("b")
        if not b or b.startswith("?"):
            return None
        return b.split(" with ")[0].removesuffix("[]")

    def linearize(self, qname: str) -> list[str]:
        """The layers of a model, lowest priority first, by the class ordering of model/resolve.py:
        the base's layers, then each trait's layers (a layer already present is skipped), then the
        model itself. The index stores a model's traits sorted by name (`w`), so two traits that
        declare the same attribute are ordered by name here, not by source order. Cycles are cut."""
        cached = self._lin.get(qname)
        if cached is not None:
            return cached
        if qname not in self.models:
            return []
        in_progress: set[str] = set()
        stack = [qname]
        while stack:
            q = stack[-1]
            if q in self._lin:
                stack.pop()
                continue
            parents = [x for x in [self.base(q), *self.models[q].get("w", [])] if x and x in self.models]
            if q not in in_progress:
                in_progress.add(q)
                pending = [x for x in parents if x not in self._lin and x not in in_progress]
                if pending:
                    stack.extend(reversed(pending))
                    continue
            lin: list[str] = []
            seen: set[str] = set()
            for par in parents:
                for layer in self._lin.get(par, ()):  # a parent still in progress is part of a cycle
                    if layer not in seen:
                        seen.add(layer)
                        lin.append(layer)
            lin.append(q)
            self._lin[q] = lin
            in_progress.discard(q)
            stack.pop()
        return self._lin[qname]

    def ancestors(self, qname: str) -> list[str]:
        """The model, its bases and their traits, highest priority first (the reverse of `linearize`)."""
        return self.linearize(qname)[::-1]

    def all_attrs(self, qname: str) -> dict[str, list]:
        """Every attribute of a model, inherited ones included; each item is [type, flags, line, doc, declaring model].

        The same answer as `Program.all_members` (model/resolve.py): a later layer replaces an earlier
        one, traits win over the base, and a plain `is` never undoes a `becomes` (flag `b`)."""
        cached = self._all.get(qname)
        if cached is not None:
            return cached
        out: dict[str, list] = {}
        for anc in self.linearize(qname):
            for name, rec in self.models[anc].get("a", {}).items():
                old = out.get(name)
                if old is None or replaces(_keyword(old[1]), _keyword(rec[1])):
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
