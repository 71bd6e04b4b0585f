"""Scenario files (``*.scenario.toml``): inputs over time and expectations on outputs and body poses.

Format (docs/testing.md)::

    model = "boxtruck.openplx"   # the model file, relative to this file (required)
    root = "Scene"               # the model in that file (default: its last model)
    duration = 4.0               # seconds (default: the latest time below)
    name = "drive"               # default: the file name without .scenario.toml

    [[input]]                    # from `at` on, the input has `value`
    at = 0.0
    signal = "box_truck.front_left_motor.target_angular_velocity_input"
    value = 3.0

    [[expect]]                   # at `at` (or at every step of `during = [t0, t1]`)
    at = 2.0
    of = "box_truck.chassis.x"   # an output path (+ .x/.y/.z, .roll/.pitch/.yaw) or <body>.x|y|z|roll|...
                                 # or a count of the assembled scene: scene.bodies, scene.mates.hinge, ...
                                 # or <geometry>.material.density, contact_model(M1, M2).friction,
                                 # <connector>.position.x (check/scenario_objects.py)
    below = -1.0                 # and/or above, abs_below, between = [lo, hi], equals + tolerance
    unit = "deg"                 # optional: thresholds of angles in degrees (deg/s for angular speeds)

    [[place]]                    # at `at`, move a root/system/free body as sim.place does
    at = 1.0
    path = "box_truck"
    position = [0, 0, 2]         # and/or rotation = [w, x, y, z]

:func:`parse` checks the file on its own (TOML, keys, kinds of values); :func:`bind` checks it
against the loaded model (paths, value kinds, times).  Every problem is a :class:`ScenarioError`
with its line: nothing here raises anything else on bad input.
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plxtools.check.signals import KIND_TEXT, SignalInfo, SignalValueError, coerce, did_you_mean
from plxtools.check.api import ANGULAR_OUTPUTS, BODY_QUANTITIES, component_index
from plxtools.check.mapped_types import CONTROLLERS, MATES
from plxtools.check.scenecounts import PREFIX
from plxtools.check.signals import COMPONENTS, RPY_COMPONENTS, RPY_QUANTITIES
from plxtools.model import suggest

SUFFIX = ".scenario.toml"
TOP_KEYS = ("model", "root", "duration", "name", "description", "input", "expect", "place")
INPUT_KEYS = ("at", "signal", "value")
PLACE_KEYS = ("at", "path", "position", "rotation")
EXPECT_KEYS = ("at", "during", "of", "below", "above", "abs_below", "between", "equals", "tolerance", "unit")
COMPARATORS = ("below", "above", "abs_below", "between", "equals")
_STRICT = frozenset({"below", "above", "abs_below"})  # the comparisons that fail at equality
UNITS = {"rad": 1.0, "deg": math.pi / 180.0}


@dataclass(frozen=True, slots=True)
class Loc:
    file: str
    line: int  # 1-based
    column: int = 1

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class ScenarioError(Exception):
    """A located problem in a scenario file (rule A141)."""

    def __init__(self, message: str, loc: Loc, help: str | None = None):
        super().__init__(message)
        self.message = message
        self.loc = loc
        self.help = help


@dataclass
class InputStep:
    at: float
    signal: str
    value: Any
    loc: Loc
    keys: dict[str, Loc]
    info: SignalInfo | None = None  # after bind
    coerced: Any = None


@dataclass
class PlaceStep:
    """``[[place]]``: at ``at``, move the object at ``path`` ("" the root model) as ``sim.place`` does."""

    at: float
    path: str
    position: tuple[float, float, float] | None
    rotation: tuple[float, float, float, float] | None  # (w, x, y, z)
    loc: Loc
    keys: dict[str, Loc]


@dataclass
class Expect:
    at: float | None
    during: tuple[float, float] | None
    of: str
    checks: list[tuple[str, Any]]  # (comparator, threshold(s)) in the unit written
    tolerance: float | None
    unit: str | None
    loc: Loc
    keys: dict[str, Loc]
    # after bind
    output: str = ""  # the output signal path read
    index: int | None = None  # component of a vector output; None with norm=True
    norm: bool = False  # |v| of a vector output ("speed")
    angular: bool = False
    count: int | None = None  # `of = "scene.bodies"`: a count of the assembled scene (check/scenecounts.py)
    fixed: float | None = None  # a material's or contact model's value (check/scenario_objects.py)
    connector: tuple | None = None  # (placement, vector, component) of a connector's world frame

    def _condition(self, op: str, v, of: str | None) -> str:
        """One comparison as written: about ``of`` (``x between 1 and 2``) or alone (``between 1 and 2``)."""
        u = f" {self.unit}" if self.unit else ""
        subject = f"{of} " if of else ""
        if op == "between":
            return f"{subject}between {v[0]:g} and {v[1]:g}{u}"
        if op == "abs_below":
            return f"|{of or 'value'}| below {v:g}{u}"
        if op == "equals":
            return f"{subject}{'equals ' if of else ''}{v:g}{u} +- {self.tolerance:g}"
        return f"{subject}{op} {v:g}{u}"

    def describe(self) -> str:
        """``box_truck.chassis.x below -1`` / ``|...yaw| below 2 deg``, as written."""
        when = f"at t={self.at:g} s" if self.at is not None else \
            f"during [{self.during[0]:g}, {self.during[1]:g}] s"  # type: ignore[index]
        return f"{' and '.join(self._condition(op, v, self.of) for op, v in self.checks)} {when}"

    def scale(self) -> float:
        return UNITS.get(self.unit or "rad", 1.0) if self.angular else 1.0

    def _gap(self, op: str, v, m: float) -> float:
        """How far ``m`` (in the unit written) is past the limit of one comparison; it holds when
        the gap is below 0 (strict comparisons) or at most 0 (ranges, equals within tolerance)."""
        if op == "below":
            return m - v
        if op == "above":
            return v - m
        if op == "abs_below":
            return abs(m) - v
        if op == "between":
            return max(v[0] - m, m - v[1])
        return abs(m - v) - (self.tolerance or 0.0)  # equals

    def failures(self, measured: float) -> list[str]:
        """The comparisons ``measured`` (SI) fails, as text in the unit written ([] when it passes)."""
        m = measured / self.scale()
        bad = []
        for op, v in self.checks:
            gap = self._gap(op, v, m)
            ok = gap < 0 if op in _STRICT else gap <= 0
            if not (ok and math.isfinite(m)):
                bad.append(op)
        return bad

    def violation(self, measured: float) -> float:
        """How far ``measured`` (SI) is outside the expectation, in the unit written (0 when it holds)."""
        m = measured / self.scale()
        if not math.isfinite(m):
            return math.inf
        return max([0.0] + [self._gap(op, v, m) for op, v in self.checks])

    def show(self, measured: float) -> str:
        u = f" {self.unit}" if self.unit and self.angular else ""
        return f"{measured / self.scale():.6g}{u}"

    def expected_text(self) -> str:
        return " and ".join(self._condition(op, v, None) for op, v in self.checks)


@dataclass
class Scenario:
    path: str
    name: str
    model_file: Path | None
    model_loc: Loc
    root: str | None
    root_loc: Loc | None
    duration: float | None
    duration_loc: Loc | None
    inputs: list[InputStep] = field(default_factory=list)
    expects: list[Expect] = field(default_factory=list)
    places: list[PlaceStep] = field(default_factory=list)

    @property
    def end(self) -> float:
        """The run's length: ``duration`` or the latest time named."""
        if self.duration is not None:
            return self.duration
        times = [i.at for i in [*self.inputs, *self.places]]
        times += [e.at if e.at is not None else e.during[1] for e in self.expects]  # type: ignore[index]
        return max(times, default=0.0)


# ----------------------------------------------------------------------------- locating keys


_HEADER = re.compile(r"^\s*\[\[\s*([A-Za-z_][\w-]*)\s*\]\]\s*(#.*)?$")
_TABLE = re.compile(r"^\s*\[\s*([^\]]+)\]\s*(#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z_][\w-]*|\"[^\"]*\")\s*=")


class _Lines:
    """Where each key of the top level and of each ``[[input]]`` / ``[[expect]]`` table is written."""

    def __init__(self, text: str, file: str):
        self.file = file
        self.top: dict[str, Loc] = {}
        self.tables: dict[str, list[tuple[Loc, dict[str, Loc]]]] = {}
        cur: dict[str, Loc] | None = self.top
        for n, line in enumerate(text.splitlines(), 1):
            m = _HEADER.match(line)
            if m:
                keys: dict[str, Loc] = {}
                self.tables.setdefault(m.group(1), []).append((Loc(file, n, line.index("[") + 1), keys))
                cur = keys
                continue
            if _TABLE.match(line):
                cur = None
                continue
            k = _KEY.match(line)
            if k and cur is not None:
                key = k.group(1).strip('"')
                cur.setdefault(key, Loc(file, n, line.index(k.group(1)) + 1))

    def table(self, kind: str, i: int) -> tuple[Loc, dict[str, Loc]]:
        rows = self.tables.get(kind, [])
        if i < len(rows):
            return rows[i]
        return Loc(self.file, 1), {}


# ----------------------------------------------------------------------------- parse


def _is_num(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _kind(v: Any) -> str:
    if isinstance(v, bool):
        return "a boolean"
    if _is_num(v):
        return "a number"
    if isinstance(v, str):
        return "a text"
    if isinstance(v, list):
        return "a list"
    if isinstance(v, dict):
        return "a table"
    return type(v).__name__


def display_path(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


def parse(path: Path) -> tuple[Scenario | None, list[ScenarioError]]:
    """Read a scenario file; the errors say what is wrong and where (the scenario is None when it
    cannot be used at all)."""
    file = display_path(path)
    text, doc, error = _read(path, file)
    if doc is None:
        return None, [error]  # type: ignore[list-item]
    lines = _Lines(text, file)
    first = Loc(file, 1)
    errors: list[ScenarioError] = []
    _unknown_keys(doc, TOP_KEYS, lines.top, first, errors, where="", help="top-level keys")
    model_file, model_loc = _model_file(doc.get("model"), path, lines.top.get("model", first), first, errors)
    root, root_loc = _root(doc.get("root"), lines.top.get("root"), first, errors)
    duration, dur_loc = _duration(doc.get("duration"), lines.top.get("duration"), first, errors)
    sc = Scenario(file, _name(doc.get("name"), path), model_file, model_loc, root, root_loc,
                  float(duration) if duration else None, dur_loc)
    for kind, keys_allowed in (("input", INPUT_KEYS), ("expect", EXPECT_KEYS), ("place", PLACE_KEYS)):
        _parse_tables(doc, kind, keys_allowed, lines, sc, errors)
    if not errors and not sc.expects:
        errors.append(ScenarioError("the scenario expects nothing: add an [[expect]] table", first))
    if not errors and sc.end <= 0:
        errors.append(ScenarioError("the scenario runs for 0 s: give a duration or a time after 0", dur_loc or first))
    return sc, errors


def _read(path: Path, file: str) -> tuple[str, dict | None, ScenarioError | None]:
    """The file's text and TOML document, or the error that stops everything."""
    from plxtools.cache import reads
    from plxtools.config import DEFAULT_MAX_FILE_MB

    try:  # a regular file only, bounded: a FIFO named as a scenario must not block
        text = reads.read_bytes(path, DEFAULT_MAX_FILE_MB << 20).decode("utf-8")
    except OSError as exc:
        return "", None, ScenarioError(f"cannot read the scenario: {exc.strerror or exc}", Loc(file, 1))
    except UnicodeDecodeError:
        return "", None, ScenarioError("the scenario is not UTF-8 text", Loc(file, 1))
    try:
        return text, tomllib.loads(text), None
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"\(at line (\d+), column (\d+)\)", str(exc))
        loc = Loc(file, int(m.group(1)), int(m.group(2))) if m else Loc(file, 1)
        msg = re.sub(r"\s*\(at line \d+, column \d+\)", "", str(exc)) if m else str(exc)
        return text, None, ScenarioError(f"invalid TOML: {msg}", loc)


def _unknown_keys(row: dict, allowed: tuple[str, ...], keys: dict[str, Loc], fallback: Loc,
                  errors: list[ScenarioError], where: str, help: str) -> None:
    """An error for every key of ``row`` not in ``allowed``, with the nearest allowed one."""
    for k in row:
        if k not in allowed:
            hint = did_you_mean(k, list(allowed))
            errors.append(ScenarioError(f"unknown key '{k}'{where}" + (f"; did you mean '{hint}'?" if hint else ""),
                                        keys.get(k, fallback), help=f"{help}: {', '.join(allowed)}"))


def _model_file(model: Any, path: Path, model_loc: Loc, first: Loc,
                errors: list[ScenarioError]) -> tuple[Path | None, Loc]:
    """``model = "FILE.openplx"``: the file, relative to the scenario, that must exist."""
    if model is None:
        errors.append(ScenarioError("the scenario names no model: add model = \"FILE.openplx\"", first))
        return None, model_loc
    if not isinstance(model, str) or not model:
        errors.append(ScenarioError(f"model must be a file name, not {_kind(model)}", model_loc))
        return None, model_loc
    model_file = path.parent / model
    if not model_file.is_file():
        errors.append(ScenarioError(f"model file '{model}' not found (looked for {display_path(model_file)})",
                                    model_loc))
        return None, model_loc
    return model_file, model_loc


def _root(root: Any, root_loc: Loc | None, first: Loc, errors: list[ScenarioError]) -> tuple[str | None, Loc | None]:
    if root is not None and (not isinstance(root, str) or not root):
        errors.append(ScenarioError(f"root must be a model name, not {_kind(root)}", root_loc or first))
        return None, root_loc
    return root, root_loc


def _duration(duration: Any, dur_loc: Loc | None, first: Loc,
              errors: list[ScenarioError]) -> tuple[Any, Loc | None]:
    """``duration``: seconds in (0, 3600], or None (the run ends at the latest time named)."""
    if duration is None:
        return None, dur_loc
    if not _is_num(duration):
        errors.append(ScenarioError(f"duration must be a number of seconds, not {_kind(duration)}", dur_loc or first))
        return None, dur_loc
    if not math.isfinite(duration) or duration <= 0 or duration > 3600:
        errors.append(ScenarioError(f"duration must be a number of seconds in (0, 3600], not {duration!r}",
                                    dur_loc or first))
        return None, dur_loc
    return duration, dur_loc


def _name(name: Any, path: Path) -> str:
    if isinstance(name, str) and name:
        return name
    return path.name[: -len(SUFFIX)] if path.name.endswith(SUFFIX) else path.stem


def _parse_tables(doc: dict, kind: str, keys_allowed: tuple[str, ...], lines: _Lines, sc: Scenario,
                  errors: list[ScenarioError]) -> None:
    """Every ``[[input]]`` (or ``[[expect]]``) table, into ``sc.inputs`` (``sc.expects``)."""
    rows = doc.get(kind, [])
    if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
        errors.append(ScenarioError(f"'{kind}' must be tables written [[{kind}]]",
                                    lines.top.get(kind, Loc(lines.file, 1))))
        return
    parse_row, into = {"input": (_parse_input, sc.inputs), "expect": (_parse_expect, sc.expects),
                       "place": (_parse_place, sc.places)}[kind]
    for i, row in enumerate(rows):
        loc, keys = lines.table(kind, i)
        _unknown_keys(row, keys_allowed, keys, loc, errors, where=f" in [[{kind}]]", help=f"[[{kind}]] keys")
        item = parse_row(row, loc, keys, errors)
        if item is not None:
            into.append(item)


def _time(v: Any, what: str, loc: Loc, errors: list[ScenarioError]) -> float | None:
    if not _is_num(v) or not math.isfinite(v):
        errors.append(ScenarioError(f"{what} must be a time in seconds, not {_kind(v) if not _is_num(v) else v}", loc))
        return None
    if v < 0:
        errors.append(ScenarioError(f"{what} = {v:g} is before the run starts (t = 0)", loc))
        return None
    return float(v)


def _parse_input(row: dict, loc: Loc, keys: dict[str, Loc], errors: list[ScenarioError]) -> InputStep | None:
    n = len(errors)
    at = _time(row.get("at", 0.0), "at", keys.get("at", loc), errors)
    sig = row.get("signal")
    if not isinstance(sig, str) or not sig:
        errors.append(ScenarioError("[[input]] needs signal = \"dotted.path.of.an.input\"" if sig is None else
                                    f"signal must be a dotted path, not {_kind(sig)}", keys.get("signal", loc)))
    if "value" not in row:
        errors.append(ScenarioError("[[input]] needs a value", loc))
    if len(errors) > n:
        return None
    return InputStep(at, sig, row["value"], loc, keys)  # type: ignore[arg-type]


def _parse_place(row: dict, loc: Loc, keys: dict[str, Loc], errors: list[ScenarioError]) -> PlaceStep | None:
    n = len(errors)
    at = _time(row.get("at", 0.0), "at", keys.get("at", loc), errors)
    path = row.get("path")
    if not isinstance(path, str):
        errors.append(ScenarioError("[[place]] needs path = \"a.system.or.body\" (\"\" for the root model)"
                                    if path is None else f"path must be a dotted path, not {_kind(path)}",
                                    keys.get("path", loc)))
    pose = [_numbers(row, key, size, keys.get(key, loc), errors) for key, size in (("position", 3), ("rotation", 4))]
    if "position" not in row and "rotation" not in row:
        errors.append(ScenarioError("[[place]] moves nothing: add position = [x, y, z] and/or "
                                    "rotation = [w, x, y, z]", loc))
    if pose[1] is not None and math.sqrt(sum(x * x for x in pose[1])) < 1e-12:
        errors.append(ScenarioError("rotation = [0, 0, 0, 0] is no rotation: give a quaternion [w, x, y, z]",
                                    keys.get("rotation", loc)))
    if len(errors) > n:
        return None
    return PlaceStep(at, path, pose[0], pose[1], loc, keys)  # type: ignore[arg-type]


def _numbers(row: dict, key: str, size: int, kl: Loc, errors: list[ScenarioError]) -> Any:
    """``position = [x, y, z]`` / ``rotation = [w, x, y, z]``: ``size`` finite numbers, or None if absent."""
    v = row.get(key)
    if v is None:
        return None
    if not (isinstance(v, list) and len(v) == size and all(_is_num(x) and math.isfinite(x) for x in v)):
        form = "[x, y, z]" if size == 3 else "[w, x, y, z] (a quaternion)"
        got = v if isinstance(v, list) else _kind(v)
        errors.append(ScenarioError(f"{key} must be {size} numbers {form}, not {got}", kl))
        return None
    return tuple(float(x) for x in v)


def _parse_expect(row: dict, loc: Loc, keys: dict[str, Loc], errors: list[ScenarioError]) -> Expect | None:
    n = len(errors)
    at, during = _when(row, loc, keys, errors)
    of = row.get("of")
    if not isinstance(of, str) or not of:
        errors.append(ScenarioError("[[expect]] needs of = \"an.output.path\" or \"a.body.x\"" if of is None else
                                    f"of must be a dotted path, not {_kind(of)}", keys.get("of", loc)))
    checks = _comparisons(row, loc, keys, errors)
    tol = _tolerance(row, loc, keys, errors)
    unit = row.get("unit")
    if unit is not None and unit not in UNITS:
        errors.append(ScenarioError(f"unit must be \"deg\" or \"rad\", not {unit!r}", keys.get("unit", loc)))
    if len(errors) > n:
        return None
    return Expect(at, during, of, checks, float(tol) if tol is not None else None, unit, loc, keys)  # type: ignore


def _when(row: dict, loc: Loc, keys: dict[str, Loc],
          errors: list[ScenarioError]) -> tuple[float | None, tuple[float, float] | None]:
    """(at, during) of an expectation: exactly one of ``at = T`` and ``during = [T0, T1]``."""
    if "at" in row and "during" in row:
        errors.append(ScenarioError("give either at or during, not both", keys.get("during", loc)))
        return None, None
    if "during" in row:
        return None, _during(row["during"], keys.get("during", loc), errors)
    if "at" in row:
        return _time(row["at"], "at", keys.get("at", loc), errors), None
    errors.append(ScenarioError("[[expect]] needs a time: at = SECONDS or during = [START, END]", loc))
    return None, None


def _during(d: Any, dl: Loc, errors: list[ScenarioError]) -> tuple[float, float] | None:
    if not (isinstance(d, list) and len(d) == 2):
        errors.append(ScenarioError(f"during must be [start, end] in seconds, not {_kind(d)}", dl))
        return None
    t0, t1 = _time(d[0], "during start", dl, errors), _time(d[1], "during end", dl, errors)
    if t0 is None or t1 is None:
        return None
    if t0 > t1:
        errors.append(ScenarioError(f"during = [{t0:g}, {t1:g}] ends before it starts", dl))
    return t0, t1


def _comparisons(row: dict, loc: Loc, keys: dict[str, Loc], errors: list[ScenarioError]) -> list[tuple[str, Any]]:
    """The comparisons written (below, above, ...), each with its threshold(s), in COMPARATORS order."""
    checks: list[tuple[str, Any]] = []
    for op in COMPARATORS:
        if op not in row:
            continue
        parse_limit = _range if op == "between" else _number
        limit = parse_limit(op, row[op], keys.get(op, loc), errors)
        if limit is not None:
            checks.append((op, limit))
    if not checks and not any(op in row for op in COMPARATORS):
        errors.append(ScenarioError(f"[[expect]] states nothing: add one of {', '.join(COMPARATORS)}", loc))
    return checks


def _range(op: str, v: Any, kl: Loc, errors: list[ScenarioError]) -> tuple[float, float] | None:
    if not (isinstance(v, list) and len(v) == 2 and all(_is_num(x) and math.isfinite(x) for x in v)):
        errors.append(ScenarioError(f"between must be [low, high], not {_kind(v)}", kl))
        return None
    if v[0] > v[1]:
        errors.append(ScenarioError(f"between = [{v[0]:g}, {v[1]:g}]: low is above high", kl))
        return None
    return float(v[0]), float(v[1])


def _number(op: str, v: Any, kl: Loc, errors: list[ScenarioError]) -> float | None:
    if not _is_num(v) or not math.isfinite(v):
        errors.append(ScenarioError(f"{op} must be a number, not {_kind(v) if not _is_num(v) else v}", kl))
        return None
    return float(v)


def _tolerance(row: dict, loc: Loc, keys: dict[str, Loc], errors: list[ScenarioError]) -> Any:
    """``tolerance``: required by ``equals``, and only allowed with it."""
    tol = row.get("tolerance")
    if "equals" in row and tol is None:
        errors.append(ScenarioError("equals needs a tolerance (tolerance = 0.05)", keys.get("equals", loc)))
    elif tol is not None and (not _is_num(tol) or not math.isfinite(tol) or tol < 0):
        errors.append(ScenarioError(f"tolerance must be a number >= 0, not {tol!r}", keys.get("tolerance", loc)))
    elif tol is not None and "equals" not in row:
        errors.append(ScenarioError("tolerance only goes with equals", keys.get("tolerance", loc)))
    return tol


# ----------------------------------------------------------------------------- bind to a model


def bind(sc: Scenario, signals: list[SignalInfo], bodies: list[str], bound: set[str],
         unbound: dict[str, str], model_file: str, counts: dict[str, int] | None = None,
         objects: Any = None) -> list[ScenarioError]:
    """Check the scenario's paths, values and times against the loaded model; fills in what each
    input and expectation refers to.  ``bound`` are the signal paths that act on the MuJoCo model,
    ``unbound`` why the others do not; ``counts`` what the assembled scene holds (`scene.bodies`);
    ``objects`` its materials, contact models and connectors (check/scenario_objects.py)."""
    errors: list[ScenarioError] = []
    model = _Model(signals, bodies, bound, unbound, model_file, counts)
    if sc.duration is not None:
        errors.extend(_after_the_end(sc, sc.duration))
    for step in sc.inputs:
        err = _bind_input(step, model)
        if err is not None:
            errors.append(err)
    for place in sc.places:
        why = objects.unknown_place(place.path) if objects is not None else None
        if why:
            errors.append(ScenarioError(why, place.keys.get("path", place.loc)))
    for e in sc.expects:
        if objects is not None and e.of not in model.by_path and objects.claims(e.of):
            err = _bind_object(e, objects)
        else:
            err = _bind_count(e, model) if model.is_count(e.of) else _bind_expect(e, model)
        if err is not None:
            errors.append(err)
    return errors


@dataclass
class _Model:
    """What :func:`bind` checks a scenario against: the model's signals, bodies and scene counts."""

    signals: list[SignalInfo]
    bodies: list[str]
    bound: set[str]
    unbound: dict[str, str]
    model_file: str
    counts: dict[str, int] | None
    by_path: dict[str, SignalInfo] = field(init=False)

    def __post_init__(self) -> None:
        self.by_path = {s.path: s for s in self.signals}

    def paths(self, direction: str) -> list[str]:
        return [s.path for s in self.signals if s.direction == direction]

    def not_simulated(self, path: str) -> str:
        return self.unbound.get(path, f"{path} is not simulated")

    def is_count(self, of: str) -> bool:
        """``scene.bodies``, ``scene.mates.hinge``...: unless a signal or body has that path."""

        head = of.rsplit(".", 1)[0]
        return (self.counts is not None and of.startswith(PREFIX) and of not in self.by_path
                and head not in self.by_path and head not in self.bodies)


COUNTED = ("bodies", "mates", "controllers", "shafts", "shaft_couplings", "shaft_motors")


def _after_the_end(sc: Scenario, duration: float) -> list[ScenarioError]:
    out = []
    for x in [*sc.inputs, *sc.places, *sc.expects]:
        t = x.at if x.at is not None else x.during[1]  # type: ignore[union-attr,index]
        if t > duration + 1e-12:
            key = "at" if x.at is not None else "during"
            out.append(ScenarioError(f"{key} = {t:g} s is after the end of the run (duration = "
                                     f"{duration:g} s)", x.keys.get(key, x.loc)))
    return out


def _bind_input(step: InputStep, model: _Model) -> ScenarioError | None:
    """Point an ``[[input]]`` at a simulated input signal and convert its value."""
    kl = step.keys.get("signal", step.loc)
    info = model.by_path.get(step.signal)
    if info is not None and info.direction != "input":
        return ScenarioError(f"{step.signal} is an output; [[input]] sends to an input", kl)
    if info is None:
        hint = did_you_mean(step.signal, model.paths("input"))
        return ScenarioError(f"{model.model_file} has no input '{step.signal}'" +
                             (f"; did you mean '{hint}'?" if hint else ""), kl)
    if step.signal not in model.bound:
        return ScenarioError(model.not_simulated(step.signal), kl)
    try:
        step.coerced = coerce(info, step.value)
    except SignalValueError as exc:
        return ScenarioError(str(exc), step.keys.get("value", step.loc),
                             help=f"{info.type} takes {KIND_TEXT[info.value_kind or 'real']}")
    step.info = info
    return None


def _bind_count(e: Expect, model: _Model) -> ScenarioError | None:
    """An expectation on a count of the assembled scene (``scene.mates.hinge``)."""

    counts = model.counts or {}
    what = e.of[len(PREFIX):]
    if e.unit is not None:
        return ScenarioError(f"{e.of} is a count; it takes no unit", e.keys.get("unit", e.loc))
    group, _, kind = what.partition(".")
    kinds = _known_kinds(group)
    if what not in counts and kind and kinds and kind not in kinds:
        hint = did_you_mean(kind, sorted(kinds))
        return ScenarioError(f"no {group} are counted as '{kind}' (kinds: {', '.join(sorted(kinds))})"
                             + (f"; did you mean '{PREFIX}{group}.{hint}'?" if hint else ""),
                             e.keys.get("of", e.loc))
    if what in counts or group in COUNTED:
        e.count = counts.get(what, 0)  # a kind the scene does not hold: 0 of them
        return None
    hint = did_you_mean(what, list(counts))
    return ScenarioError(f"the scene has no count '{what}' (counts: bodies, mates, controllers, "
                         "shafts, shaft_couplings, shaft_motors, and per kind such as mates.hinge)"
                         + (f"; did you mean '{PREFIX}{hint}'?" if hint else ""), e.keys.get("of", e.loc))


def _bind_object(e: Expect, objects: Any) -> ScenarioError | None:
    """An expectation on a material, a contact model or a connector: none of them is an angle."""

    if e.unit is not None:
        return ScenarioError(f"{e.of} is not an angle; it takes no unit", e.keys.get("unit", e.loc))
    why = objects.bind(e)
    return ScenarioError(why, e.keys.get("of", e.loc)) if why else None


def _known_kinds(group: str) -> set[str]:
    """The kinds a mate or controller count may name (the mapping's tables); other groups: any."""

    if group == "mates":
        return set(MATES.values())
    if group == "controllers":
        return {name for _kind, _dof, name in CONTROLLERS.values()}
    return set()


def _bind_expect(e: Expect, model: _Model) -> ScenarioError | None:
    """Point an ``[[expect]]`` at an output (or a body quantity) and check its unit."""

    err = _bind_subject(e, model.by_path, model.bodies, model.paths("output"), model.bound, model.unbound,
                        model.model_file, BODY_QUANTITIES, component_index)
    if err is not None:
        return ScenarioError(err, e.keys.get("of", e.loc))
    e.angular = model.by_path[e.output].type.endswith(ANGULAR_OUTPUTS) and not e.norm
    if e.unit == "deg" and not e.angular:
        return ScenarioError(f"unit = \"deg\" but {e.of} is not an angle or an angular speed",
                             e.keys.get("unit", e.loc))
    return None


def _bind_subject(e: Expect, by_path: dict, bodies: list[str], outputs: list[str], bound: set[str],
                  unbound: dict[str, str], model_file: str, body_q: dict, component_index) -> str | None:
    path, comp = e.of, None
    info = by_path.get(path)
    if info is None and "." in path:
        head, tail = path.rsplit(".", 1)
        if head in by_path:
            info, comp = by_path[head], tail
        elif head in bodies and tail in body_q:
            out, idx = body_q[tail]
            info = by_path.get(f"{head}.{out}")
            if info is None:
                return f"the body {head} has no {out}"
            e.output, e.index, e.norm = info.path, idx, idx is None
            return None if info.path in bound else unbound.get(info.path, f"{info.path} is not simulated")
        elif head in bodies:
            hint = _body_quantity_hint(tail, body_q)
            return f"{tail!r} is not a body quantity; " + (f"{hint} (all: {', '.join(body_q)})" if hint else
                                                          f"use one of {', '.join(body_q)}")
    if info is None:
        cands = outputs + [f"{b}.{q}" for b in bodies for q in ("x", "y", "z", "yaw")]
        hint = did_you_mean(path, cands)
        return f"{model_file} has no output or body quantity '{path}'" + (f"; did you mean '{hint}'?" if hint else "")
    if info.direction != "output":
        return f"{info.path} is an input; expectations read outputs (or body quantities such as {info.source}.x)"
    if info.path not in bound:
        return unbound.get(info.path, f"{info.path} is not simulated")
    kind = info.value_kind
    e.output = info.path
    if kind in ("real", "bool"):  # a true / false output is compared as 1 / 0
        if comp is not None:
            return f"{info.path} is a single number; it has no component '{comp}'"
        return None
    if comp is None:
        names = ", ".join(f"{info.path}.{c}" for c in _components(info))
        return f"{info.path} is {KIND_TEXT[kind or 'real']}: name one component ({names})"
    idx = component_index(info, comp)
    if idx is None:
        return f"{info.path} has no component '{comp}'; use one of {', '.join(_components(info))}"
    e.index = idx
    return None


def _components(info: SignalInfo) -> list[str]:
    if info.quantity in RPY_QUANTITIES:
        return list(RPY_COMPONENTS)
    return list(COMPONENTS.get(info.value_kind or "", ()))


def discover(paths: list[str]) -> list[Path]:
    """The scenario files named or found (recursively, ``*.scenario.toml``) under ``paths``;
    raises FileNotFoundError for a path that does not exist."""
    out: list[Path] = []
    for p in paths:
        q = Path(p)
        if q.is_dir():
            out.extend(sorted(x for x in q.rglob("*" + SUFFIX) if x.is_file() and not any(
                part.startswith(".") or part in ("node_modules", "__pycache__") for part in x.relative_to(q).parts)))
        elif q.is_file():
            out.append(q)
        else:
            raise FileNotFoundError(p)
    seen: set[Path] = set()
    uniq = []
    for x in out:
        r = x.resolve()
        if r not in seen:
            seen.add(r)
            uniq.append(x)
    return uniq


def _body_quantity_hint(tail: str, body_q: dict) -> str:
    """"did you mean 'vx' or 'vy' or ... (the body's linear_velocity_world_output)?": the quantities of the
    body output that means what `tail` says (model/suggest.py ranks the outputs by meaning)."""
    by_output: dict[str, list[str]] = {}
    for q, (out, _idx) in body_q.items():
        by_output.setdefault(out, []).append(q)
    near = suggest.best(tail, list(body_q) + list(by_output), cutoff=0.6)
    if near is None:
        return ""
    if near in by_output:
        return f"did you mean {' or '.join(repr(q) for q in by_output[near])} (the body's {near})?"
    return f"did you mean {near!r}?"
