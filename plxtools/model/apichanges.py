"""What changed in the OpenPLX API between two official versions, computed from the API index.

A step compares two consecutive indexed versions. Models that vanish and reappear with the same
simple name elsewhere are *moved*; an attribute replaced by exactly one new attribute of the same
type (after moves), the same flags and the same documentation, or named by a deprecation note, is
*renamed*. Renames that OpenPLX itself declares (`apiindex/declared_renames.toml`, facts of the
official migration tool's list) are applied where the bundles show them; anything else the data
cannot prove comes from the reviewed table `apiindex/renames.toml` (each entry cites the bundle files
and lines in both versions) or is reported as needing a person.
`changes(a, b)` composes the steps between a and b (a rename followed by a move is one change).
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import asdict, dataclass, field, replace
from functools import lru_cache
from pathlib import Path

from plxtools.model.apiindex import ApiIndex, check_version, load, version_key, versions

RENAMES = Path(__file__).resolve().parent / "apiindex" / "renames.toml"
DECLARED_RENAMES = Path(__file__).resolve().parent / "apiindex" / "declared_renames.toml"

# how a change is handled when migrating a model
AUTO = "automatic"  # inferred from the index, one to one
TABLE = "table"  # from the reviewed table
DECLARED = "declared"  # declared by OpenPLX's own migration list
PERSON = "person"  # a person must decide
INFO = "info"  # nothing to migrate (an addition, a deprecation note)
MECHANICAL = (AUTO, TABLE, DECLARED)  # what `plx migrate` rewrites

KIND_TITLES = {
    "model-moved": "Moved models",
    "model-renamed": "Renamed models",
    "model-removed": "Removed models",
    "attr-renamed": "Renamed attributes",
    "attr-removed": "Removed attributes",
    "attr-type-changed": "Changed attribute types",
    "attr-now-required": "Attributes that lost their default",
    "attr-added-required": "New attributes without a default",
    "base-changed": "Changed bases",
    "fn-removed": "Removed functions",
    "fn-changed": "Changed function signatures",
    "deprecated": "New deprecation notes",
    "model-added": "Added models",
    "attr-added": "Added attributes (with a default)",
    "fn-added": "Added functions",
}
KIND_ORDER = list(KIND_TITLES)

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*")


@dataclass(slots=True)
class Change:
    kind: str
    since: str  # the first version that has the change
    model: str  # qualified name (the old one for moves, renames and removals)
    handling: str
    attr: str | None = None
    old: str | None = None  # old name / type / signature
    new: str | None = None
    detail: str | None = None
    where: list[str] = field(default_factory=list)  # "VERSION FILE:LINE" in the old and new version

    def subject(self) -> str:
        return f"{self.model}.{self.attr}" if self.attr else self.model

    def to_json(self) -> dict:
        return {k: v for k, v in asdict(self).items() if v not in (None, [])}


@dataclass(slots=True)
class TableEntry:
    kind: str  # "model" | "attribute"
    version: str
    old: str
    new: str
    model: str | None
    evidence: list[str]
    note: str
    handling: str = TABLE
    old_model: str | None = None  # a declared attribute: its model's name before the step


@dataclass(frozen=True, slots=True)
class DeclaredRename:
    """One rename or move of OpenPLX's own migration list (see declared_renames.toml)."""

    kind: str  # "model" | "attribute" | "method" | "extension"
    after: str  # the step it is declared for: from `after` ...
    to: str  # ... to `to`
    old: str
    new: str
    model: str | None  # attribute / method: the model that has it under the old name
    operation: str

    def source(self) -> str:
        fn = self.operation.partition(": ")[0]
        return f"declared by OpenPLX: openplx.migrations.{fn}, {self.after} -> {self.to}"


class RenameTableError(ValueError):
    pass


@lru_cache(maxsize=1)
def rename_table() -> tuple[TableEntry, ...]:
    """The reviewed renames; a malformed table is an error, never silently skipped."""
    try:
        data = tomllib.loads(RENAMES.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise RenameTableError(f"{RENAMES}: {exc}") from exc
    out = []
    for kind in ("model", "attribute"):
        for i, e in enumerate(data.get(kind, [])):
            missing = [k for k in ("version", "old", "new", "evidence", "note") if k not in e]
            if kind == "attribute" and "model" not in e:
                missing.append("model")
            if missing:
                raise RenameTableError(f"{RENAMES}: [[{kind}]] #{i + 1} lacks {', '.join(missing)}")
            out.append(TableEntry(kind, e["version"], e["old"], e["new"], e.get("model"), list(e["evidence"]),
                                  e["note"]))
    return tuple(out)


@lru_cache(maxsize=1)
def declared_renames() -> tuple[DeclaredRename, ...]:
    """OpenPLX's declared renames, oldest step first; a malformed file is an error, never skipped."""
    try:
        data = tomllib.loads(DECLARED_RENAMES.read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise RenameTableError(f"{DECLARED_RENAMES}: {exc}") from exc
    out = []
    for kind in ("model", "attribute", "method", "extension"):
        for i, e in enumerate(data.get(kind, [])):
            need = ("from", "to", "operation", "old", "new") + (("model",) if kind in ("attribute", "method") else ())
            missing = [k for k in need if k not in e]
            if missing:
                raise RenameTableError(f"{DECLARED_RENAMES}: [[{kind}]] #{i + 1} lacks {', '.join(missing)}")
            out.append(DeclaredRename(kind, e["from"], e["to"], e["old"], e["new"], e.get("model"), e["operation"]))
    return tuple(sorted(out, key=lambda d: version_key(d.after)))


def _declared_for(old_v: str) -> list[TableEntry]:
    """The declared model and attribute renames a step from `old_v` may show: every one declared at
    or before it (placed where the bundles show the old name gone and the new one there)."""
    lo = version_key(old_v)
    out = []
    for d in declared_renames():
        if d.kind not in ("model", "attribute") or version_key(d.after) > lo:
            continue
        out.append(TableEntry(d.kind, d.to, d.old, d.new, d.model if d.kind == "attribute" else None, [],
                              d.source(), DECLARED, d.model if d.kind == "attribute" else None))
    return out


def _where(idx: ApiIndex, qname: str, attr: str | None = None) -> str:
    rec = idx.models[qname]
    line = rec["l"]
    if attr is not None:
        line = idx.all_attrs(qname)[attr][2]
        rec = idx.models[idx.declaring(qname, attr)]
    return f"{idx.version} {rec['f']}:{line}"


def _map_type(text: str, mapping: dict[str, str]) -> str:
    return _NAME.sub(lambda m: mapping.get(m.group(0), m.group(0)), text)


def _table_for(old_v: str, new_v: str) -> list[TableEntry]:
    lo, hi = version_key(old_v), version_key(new_v)
    return [e for e in rename_table() if lo < version_key(e.version) <= hi]


def diff(old: ApiIndex, new: ApiIndex) -> list[Change]:
    """The changes from one version's index to another's (normally consecutive versions).

    Models first (renamed by the table, moved, removed, added), then per model that exists in both:
    its attribute renames (all models first, so a subtype can follow its base's rename), then what
    else changed in its attributes, base, functions and deprecation notes."""
    table = _table_for(old.version, new.version) + _declared_for(old.version)
    out, full_map = _model_changes(old, new, table)
    own, renames, pending = {}, {}, {}  # own: by old model; renames: by new model (several old may merge)
    for q, n in sorted(full_map.items()):
        own[q], pending[q] = _attr_renames(old, new, q, n, table, full_map)
        renames.setdefault(n, {}).update(own[q])
    for q, n in sorted(full_map.items()):
        rest_gone, rest_fresh = pending[q]
        _follow_base_renames(old, new, q, n, own[q], renames, rest_gone, rest_fresh, full_map)
        out += _attr_changes(old, new, q, n, own[q], renames, rest_gone, rest_fresh, full_map)
        out += _model_body_changes(old, new, q, n, full_map)
    return out


def _model_changes(old: ApiIndex, new: ApiIndex, table: list[TableEntry]) -> tuple[list[Change], dict[str, str]]:
    """The model-level changes, and every old model that lives on mapped to its name in `new`."""
    v = new.version
    out: list[Change] = []
    removed = sorted(set(old.models) - set(new.models))
    added = sorted(set(new.models) - set(old.models))
    mapping: dict[str, str] = {}
    for e in table:
        if e.kind == "model" and e.old in removed and e.new in new.models and e.old not in mapping:
            mapping[e.old] = e.new  # (the new one may already exist)
            simple = e.old.rsplit(".", 1)[-1] == e.new.rsplit(".", 1)[-1]
            out.append(Change("model-moved" if simple and e.handling == DECLARED else "model-renamed", v, e.old,
                              e.handling, old=e.old, new=e.new, detail=e.note,
                              where=[_where(old, e.old), _where(new, e.new)]))
    for o, n in _moved_models(old, new, removed, added, mapping):
        mapping[o] = n
        out.append(Change("model-moved", v, o, AUTO, old=o, new=n, where=[_where(old, o), _where(new, n)]))
    out += [Change("model-removed", v, q, PERSON, where=[_where(old, q)]) for q in removed if q not in mapping]
    mapped_new = set(mapping.values())
    out += [Change("model-added", v, q, INFO, where=[_where(new, q)]) for q in added if q not in mapped_new]
    return out, {q: mapping.get(q, q) for q in old.models if q in mapping or q in new.models}


def _moved_models(old: ApiIndex, new: ApiIndex, removed: list[str], added: list[str],
                  mapping: dict[str, str]) -> list[tuple[str, str]]:
    """(old, new) for a removed and an added model of the same short name and kind: one to one, or
    else paired within their bundle when that is one to one."""
    by_name_old: dict[tuple[str, str], list[str]] = {}
    by_name_new: dict[tuple[str, str], list[str]] = {}
    for q in removed:
        if q not in mapping:
            by_name_old.setdefault((q.rsplit(".", 1)[-1], old.models[q]["k"]), []).append(q)
    taken = set(mapping.values())
    for q in added:
        if q not in taken:
            by_name_new.setdefault((q.rsplit(".", 1)[-1], new.models[q]["k"]), []).append(q)
    pairs: list[tuple[str, str]] = []
    for key, olds in by_name_old.items():
        news = by_name_new.get(key, [])
        if len(olds) == 1 and len(news) == 1:
            pairs.append((olds[0], news[0]))
            continue
        for o in olds:
            bundle = o.split(".")[0]
            same = [n for n in news if n.split(".")[0] == bundle]
            if len(same) == 1 and sum(x.split(".")[0] == bundle for x in olds) == 1:
                pairs.append((o, same[0]))
    return pairs


def _attr_renames(old: ApiIndex, new: ApiIndex, q: str, n: str, table: list[TableEntry],
                  full_map: dict[str, str]) -> tuple[dict[str, tuple[str, str, str]], tuple[list[str], list[str]]]:
    """A model's renamed attributes (old attr -> (new attr, handling, why)), by the table, a
    deprecation note that names the new one, or a single gone/new pair that is alike in everything
    but its name; and the attributes left gone and fresh."""
    o_own, n_own = old.models[q].get("a", {}), new.models[n].get("a", {})
    o_all, n_all = old.all_attrs(q), new.all_attrs(n)
    gone = [a for a in o_own if a not in n_all]
    fresh = [a for a in n_own if a not in o_all]
    found = _listed_attr_renames(table, q, n, gone, n_all)
    rest_gone = [a for a in gone if a not in found]
    rest_fresh = [a for a in fresh if a not in {x[0] for x in found.values()}]
    dep = old.models[q].get("dep", {})
    for a in list(rest_gone):
        note = dep.get(a, "")
        named = [b for b in rest_fresh if re.search(rf"\b{re.escape(b)}\b", note)]
        if len(named) == 1:
            found[a] = (named[0], AUTO, f"deprecation note: {note}")
            rest_gone.remove(a)
            rest_fresh.remove(named[0])
    if len(rest_gone) == 1 and len(rest_fresh) == 1:
        a, b = rest_gone[0], rest_fresh[0]
        ra, rb = o_own[a], n_own[b]
        if _map_type(ra[0], full_map) == rb[0] and ra[1] == rb[1] and ra[3] and ra[3] == rb[3]:
            found[a] = (b, AUTO, "same type, flags and documentation")
            rest_gone, rest_fresh = [], []
    return found, (rest_gone, rest_fresh)


def _listed_attr_renames(table: list[TableEntry], q: str, n: str, gone: list[str],
                         n_all: dict) -> dict[str, tuple[str, str, str]]:
    """A model's attribute renames that a list names: the reviewed table (by the model's new name) or
    OpenPLX's declared list (by its old one)."""
    found: dict[str, tuple[str, str, str]] = {}
    for e in table:
        mine = e.old_model == q if e.old_model else e.model == n
        if e.kind == "attribute" and mine and e.old in gone and e.new in n_all and e.old not in found:
            found[e.old] = (e.new, e.handling, e.note)
    return found


def _follow_base_renames(old: ApiIndex, new: ApiIndex, q: str, n: str, found: dict, renames: dict,
                         rest_gone: list[str], rest_fresh: list[str], full_map: dict[str, str]) -> None:
    """A subtype redeclaring (`becomes`) an attribute its base renamed follows the base's rename:
    whether it redeclares the new name or drops the redeclaration (inherited under the new name).
    `found`: the model's own renames (added to); `renames`: every model's, by its new name."""
    n_all = new.all_attrs(n)
    for a in list(rest_gone):
        hit = _base_rename(old, new, q, n, a, full_map, renames)
        if hit is None:
            continue
        b, how, anc = hit
        if b in rest_fresh or ("b" in old.models[q]["a"][a][1] and b in n_all):
            found[a] = renames.setdefault(n, {})[a] = (b, how, f"follows {anc}.{a}")
            rest_gone.remove(a)
            if b in rest_fresh:
                rest_fresh.remove(b)


def _base_rename(old: ApiIndex, new: ApiIndex, q: str, n: str, a: str, full_map: dict[str, str],
                 renames: dict[str, dict[str, tuple[str, str, str]]]) -> tuple[str, str, str] | None:
    """The rename of attribute `a` in a base of `q` (old name) / `n` (new name): (new attr, handling,
    base). The bases are looked up in both versions (Physics1D.Interactions.Mate drops its
    redeclaration of `charges` in 0.18.11)."""
    bases = [full_map.get(x, x) for x in old.ancestors(q)[1:]] + new.ancestors(n)[1:]
    for anc in dict.fromkeys(bases):
        hit = renames.get(anc, {}).get(a)
        if hit:
            return hit[0], hit[1], anc
    return None


def _attr_changes(old: ApiIndex, new: ApiIndex, q: str, n: str, found: dict, renames: dict, rest_gone: list[str],
                  rest_fresh: list[str], full_map: dict[str, str]) -> list[Change]:
    """A model's attributes renamed, removed, added, retyped or newly required."""
    v = new.version
    out: list[Change] = []
    o_all, n_all = old.all_attrs(q), new.all_attrs(n)
    for a, (b, how, why) in sorted(found.items()):
        out.append(Change("attr-renamed", v, q, how, attr=a, old=a, new=b, detail=why,
                          where=[_where(old, q, a), _where(new, n, b)]))
    for a in rest_gone:
        inherited = any(a in old.models[anc].get("a", {}) and renames.get(full_map.get(anc, ""), {}).get(a)
                        for anc in old.ancestors(q)[1:])
        if not inherited:
            out.append(Change("attr-removed", v, q, PERSON, attr=a, old=o_all[a][0], where=[_where(old, q, a)]))
    for b in rest_fresh:
        rec = n_all[b]
        if "b" in rec[1]:
            continue  # a `becomes` of an attribute that is new in a base: reported there
        required = "d" not in rec[1] and "o" not in rec[1]
        out.append(Change("attr-added-required" if required else "attr-added", v, n,
                          PERSON if required else INFO, attr=b, new=rec[0], where=[_where(new, n, b)]))
    n_own = new.models[n].get("a", {})
    back = {b: a for a, (b, _h, _w) in found.items()}
    for b in sorted(set(old.models[q].get("a", {})) | set(n_own)):
        a = back.get(b, b)
        if a not in o_all or b not in n_all or b not in n_own:
            continue
        t_new = n_all[b][0]
        t_old = _map_type(o_all[a][0], full_map)
        if t_old != t_new and not (a != b and _widened(new, t_old, t_new)):
            out.append(Change("attr-type-changed", v, q, PERSON, attr=a, old=o_all[a][0], new=t_new,
                              where=[_where(old, q, a), _where(new, n, b)]))
        if "d" in o_all[a][1] and "d" not in n_all[b][1] and "o" not in n_all[b][1]:
            out.append(Change("attr-now-required", v, q, PERSON, attr=a, where=[_where(new, n, b)]))
    return out


def _widened(new: ApiIndex, t_old: str, t_new: str) -> bool:
    """A renamed attribute whose new type is a base or trait of its old one (Hinge's `hinge` became
    `source`, an AngularVelocity1DOutputTrait that Hinge has): every value it held still fits."""
    if t_old.endswith("[]") != t_new.endswith("[]") or " " in t_old or " " in t_new:
        return False
    return t_new.removesuffix("[]") in new.ancestors(t_old.removesuffix("[]"))


def _model_body_changes(old: ApiIndex, new: ApiIndex, q: str, n: str, full_map: dict[str, str]) -> list[Change]:
    """A model's base, its functions and its new deprecation notes."""
    v = new.version
    out: list[Change] = []
    ob, nb = old.base(q), new.base(n)
    mapped_base = ob and _map_type(ob, full_map)
    # (a model renamed into its own base, TorqueDriveTrain -> FlexibleJointDriveTrain, changed no base)
    if mapped_base != nb and mapped_base != n and old.models[q]["k"] != "g":
        out.append(Change("base-changed", v, q, PERSON, old=ob, new=nb))
    o_fn, n_fn = old.models[q].get("fn", {}), new.models[n].get("fn", {})
    for f in sorted(set(o_fn) | set(n_fn)):
        if f not in n_fn:
            out.append(Change("fn-removed", v, q, PERSON, attr=f, old=o_fn[f]))
        elif f not in o_fn:
            out.append(Change("fn-added", v, n, INFO, attr=f, new=n_fn[f]))
        elif _map_type(o_fn[f], full_map) != n_fn[f]:
            out.append(Change("fn-changed", v, q, PERSON, attr=f, old=o_fn[f], new=n_fn[f]))
    o_dep, n_dep = old.models[q].get("dep", {}), new.models[n].get("dep", {})
    for a in sorted(set(n_dep) - set(o_dep)):
        out.append(Change("deprecated", v, n, INFO, attr=a or None, detail=n_dep[a], where=[_where(new, n)]))
    return out


@lru_cache(maxsize=None)
def step(old_v: str, new_v: str) -> tuple[Change, ...]:
    return tuple(diff(load(old_v), load(new_v)))


def between(from_v: str, to_v: str) -> list[str]:
    """The indexed versions from `from_v` to `to_v` inclusive (either order is an error if equal)."""
    allv = versions()
    a, b = allv.index(check_version(from_v)), allv.index(check_version(to_v))
    if a > b:
        raise ValueError(f"'{from_v}' is newer than '{to_v}': plx migrates forward only")
    return list(allv[a:b + 1])


def steps(from_v: str, to_v: str) -> list[tuple[str, str, tuple[Change, ...]]]:
    chain = between(from_v, to_v)
    return [(a, b, step(a, b)) for a, b in zip(chain, chain[1:])]


def _joined(e: Change, c: Change, **kw) -> Change:
    """`e` then `c` as one change: from e's first place to c's last, a table's answer if either needs one."""
    hs = (e.handling, c.handling)
    handling = DECLARED if DECLARED in hs else TABLE if TABLE in hs else AUTO
    detail = c.detail if c.handling == DECLARED and e.handling != DECLARED else e.detail
    return replace(e, new=c.new, where=[e.where[0], c.where[-1]], handling=handling, detail=detail, **kw)


class _Composer:
    """Changes of consecutive steps composed into one list (see `changes`); `None` marks one that
    cancelled out. Each step names models as its older version does (`before`)."""

    def __init__(self) -> None:
        self.out: list[Change | None] = []
        self.model_at: dict[str, int] = {}  # current model name -> composed move/rename
        self.added_at: dict[str, int] = {}  # current name of a model added in the range
        self.orig: dict[str, str] = {}  # current model name -> its name in from_v
        self.attr_at: dict[tuple[str, str], int] = {}  # (orig model, current attr) -> composed attribute change
        self.type_at: dict[tuple[str, str], int] = {}

    def push(self, c: Change) -> int:
        self.out.append(c)
        return len(self.out) - 1

    def step(self, cs) -> None:
        before = dict(self.orig)
        for c in cs:
            m = before.get(c.model, c.model)
            handler = _COMPOSE.get(c.kind)
            if handler is None:
                self.push(replace(c, model=m))
            else:
                handler(self, c, m)

    def model_moved(self, c: Change, m: str) -> None:
        if c.old in self.model_at:
            i = self.model_at.pop(c.old)
            e = self.out[i]
            assert e is not None
            simple = e.old.rsplit(".", 1)[-1] == c.new.rsplit(".", 1)[-1]
            self.out[i] = _joined(e, c, kind="model-moved" if simple else "model-renamed")
            self.model_at[c.new] = i
        elif c.old in self.added_at:
            i = self.added_at.pop(c.old)
            self.out[i] = replace(self.out[i], model=c.new)
            self.added_at[c.new] = i
        else:
            self.model_at[c.new] = self.push(c)
        self.orig[c.new] = self.orig.pop(c.old, c.old)

    def model_removed(self, c: Change, m: str) -> None:
        if c.model in self.model_at:
            i = self.model_at.pop(c.model)
            self.out[i] = replace(c, model=self.out[i].old, where=self.out[i].where[:1])
        elif c.model in self.added_at:
            self.out[self.added_at.pop(c.model)] = None
        else:
            self.push(c)

    def model_added(self, c: Change, m: str) -> None:
        self.added_at[c.model] = self.push(c)

    def attribute(self, c: Change, m: str) -> None:
        key = (m, c.attr or "")
        if c.kind == "attr-renamed" and key in self.attr_at:
            i = self.attr_at.pop(key)
            e = self.out[i]
            self.out[i] = _joined(e, c) if e.kind == "attr-renamed" else replace(e, attr=c.new)
            self.attr_at[(m, c.new or "")] = i
        elif c.kind == "attr-removed" and key in self.attr_at:
            i = self.attr_at.pop(key)
            e = self.out[i]
            self.out[i] = None if e.kind != "attr-renamed" else replace(c, model=m, attr=e.old, where=e.where[:1])
        else:
            i = self.push(replace(c, model=m))
            self.attr_at[(m, c.new if c.kind == "attr-renamed" else c.attr or "")] = i

    def attr_type(self, c: Change, m: str) -> None:
        key = (m, c.attr or "")
        if key in self.type_at and self.out[self.type_at[key]] is not None:
            i = self.type_at[key]
            e = self.out[i]
            self.out[i] = None if e.old == c.new else replace(e, new=c.new, where=[e.where[0], c.where[-1]])
        else:
            self.type_at[key] = self.push(replace(c, model=m))


_COMPOSE = {
    "model-moved": _Composer.model_moved, "model-renamed": _Composer.model_moved,
    "model-removed": _Composer.model_removed, "model-added": _Composer.model_added,
    "attr-renamed": _Composer.attribute, "attr-added": _Composer.attribute,
    "attr-added-required": _Composer.attribute, "attr-removed": _Composer.attribute,
    "attr-type-changed": _Composer.attr_type,
}


def changes(from_v: str, to_v: str) -> list[Change]:
    """The changes from `from_v` to `to_v`, composed over the consecutive steps between them.

    A chain of renames and moves becomes one change from the first name to the last; something
    added and later removed in the range disappears; a type changed twice shows first and last.
    """
    return _compose(cs for _a, _b, cs in steps(from_v, to_v))


def changes_over(chain: list[ApiIndex]) -> list[Change]:
    """The changes along a chain of indexes, oldest first, composed as `changes` does: for bundles
    that are in no release (an AGX installation's, indexed at run time) between indexed versions."""
    return _compose(tuple(diff(a, b)) for a, b in zip(chain, chain[1:]))


def _compose(steps_changes) -> list[Change]:
    composer = _Composer()
    for cs in steps_changes:
        composer.step(cs)
    return [c for c in composer.out if c is not None]


def summary(cs: list[Change]) -> dict[str, int]:
    counts = {AUTO: 0, TABLE: 0, DECLARED: 0, PERSON: 0, INFO: 0}
    for c in cs:
        counts[c.handling] += 1
    return counts


def renamed_model(qname: str, old_v: str, new_v: str) -> Change | None:
    """The rename or move of model `qname` (its name in `old_v`) by `new_v`, one to one: from OpenPLX's
    declared list, the reviewed table or the index (`handling` and `detail` say which). The one
    lookup behind lint's U001 and a suggestion ranking: a declared target beats a look-alike name."""
    for c in changes(old_v, new_v):
        if c.kind in ("model-moved", "model-renamed") and c.old == qname and c.handling in MECHANICAL:
            return c
    return None
