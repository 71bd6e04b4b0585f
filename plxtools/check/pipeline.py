"""`plx check` for one file: lint -> instantiate -> evaluate -> SNAP -> static checks -> scene IR
-> (optionally) MuJoCo compile / simulate / export / render.

mujoco is imported only when a MuJoCo step is requested (inside :func:`run_backend`).
"""

from __future__ import annotations

import enum
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plxtools.check.assemble import Assembler, Assembly, Kinds, Placement
from plxtools.check.checks import StaticChecks, scan_strings
from plxtools.check.convert import Collector, to_scene
from plxtools.check.evaluate import Evaluator
from plxtools.check.frames import mat_to_quat_wxyz
from plxtools.check.instance import Builder
from plxtools.check.report import Reporter
from plxtools.diagnostics import EMPTY_SPAN, Diagnostic, Pos, Severity, Span
from plxtools.model.symbols import ModelSym
from plxtools.rules.analysis import analyse_file
from plxtools.syntax import ast, parse_bytes
from plxtools.syntax.source import unreadable
from plxtools.rules import registry
from plxtools.check import aftersim
from plxtools.check.mujoco import backend as mjb  # (imports MuJoCo only when it compiles)
from plxtools.rules.analysis import finalize
from plxtools.model.completeness import root_model


class Skip(enum.Enum):
    """Why a file was not (fully) checked or not simulated; the value is the text reports show."""

    UNREADABLE = "the file cannot be read"
    NOT_TEXT = "not an OpenPLX text file"
    SYNTAX = "the file has syntax errors"
    NO_MODEL = "the file defines no model"
    NO_ROOT = "no root model"
    BLOCKED = "errors make the scene unreliable"
    INTERNAL = "internal error"


# errors whose scene is exactly what the file says; they do not stop simulation, export or render
SCENE_AS_WRITTEN = frozenset({registry.MATE_NOT_COINCIDENT})
NO_SUCH_ROOT, TRAIT_AS_ROOT = registry.ROOT_MODEL_NOT_FOUND, registry.ROOT_IS_TRAIT  # the root model asked for (--model, a scenario's root) is not a model


@dataclass
class AssemblySummary:
    bodies: int
    snap: int  # placed by SNAP
    declared: int  # with a declared transform (the root not counted)
    mates: int
    controllers: int
    poses: dict[str, dict[str, Any]]  # FileCheck.assembled_bodies()


@dataclass
class FileCheck:
    path: str
    tree: ast.File | None = None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    model: str | None = None
    assembly: Assembly | None = None
    scene: Any = None  # plxtools.check.scene.Scene
    compiled: Any = None  # CompiledScene
    simulation: Any = None  # SimulationResult
    skip: Skip | None = None  # why the simulation (or the whole check) did not run
    skip_detail: str = ""  # the particulars (which errors block the backend)
    internal_error: str | None = None
    timings: dict[str, float] = field(default_factory=dict)
    objects: int = 0
    rep: Reporter | None = field(default=None, repr=False)  # the check diagnostics, before merging
    raw: list[Diagnostic] = field(default_factory=list, repr=False)  # lint's, before filtering
    cfg: Any = field(default=None, repr=False)
    evaluator: Any = field(default=None, repr=False)  # the Evaluator the assembly used (its values memoised)
    kinds: Any = field(default=None, repr=False)  # the Kinds the assembly used
    summary: AssemblySummary | None = field(default=None, repr=False)  # of the assembly, for the reports

    @property
    def skipped(self) -> str | None:
        """Display text of ``skip`` (reports, JSON); state is ``skip``."""
        if self.skip is None:
            return None
        return self.skip_detail or self.skip.value

    @property
    def has_errors(self) -> bool:
        return any(d.severity == Severity.ERROR for d in self.diagnostics)

    @property
    def assembled(self) -> bool:
        return self.assembly is not None or self.summary is not None

    def assembly_summary(self) -> AssemblySummary | None:
        """What the reports show of the assembly (counts and body poses)."""
        if self.summary is None and self.assembly is not None:
            asm = self.assembly
            self.summary = AssemblySummary(
                bodies=len(asm.bodies),
                snap=sum(1 for n in asm.bodies if n.placement is Placement.SNAP),
                declared=sum(1 for n in asm.bodies if n.explicit and n is not asm.root_node),
                mates=len(asm.mates), controllers=len(asm.controllers), poses=self._poses())
        return self.summary

    def for_report(self) -> FileCheck:
        """The part of the check the reports use, without the syntax tree, the assembly's objects or
        the MuJoCo model: what a worker process sends back (it pickles)."""
        return FileCheck(self.path, diagnostics=self.diagnostics, model=self.model, simulation=self.simulation,
                         skip=self.skip, skip_detail=self.skip_detail, internal_error=self.internal_error,
                         timings=self.timings, objects=self.objects, summary=self.assembly_summary())

    def assembled_bodies(self) -> dict[str, dict[str, Any]]:
        summary = self.assembly_summary()
        return summary.poses if summary is not None else {}

    def _poses(self) -> dict[str, dict[str, Any]]:
        out = {}
        for n in self.assembly.nodes:
            if n.kind != "body":
                continue
            out[n.path] = {
                "position": [round(float(x), 12) + 0.0 for x in n.world[1]],
                "quaternion": [round(x, 12) + 0.0 for x in mat_to_quat_wxyz(n.world[0])],
                "placed_by": n.placed_by,
                "placement": n.placement.value,
                "dynamic": n.is_dynamic,
            }
        return out


def _pick_root(program, unit, name: str | None, rep: Reporter) -> ModelSym | None:
    if not name:
        root = root_model(program, unit)
        if root is None:
            return None
        return root
    found = program.lookup(name.split("."), unit)
    if isinstance(found, ModelSym) and found.is_trait:
        span = found.stmt.header if found.unit is unit and found.stmt is not None else EMPTY_SPAN
        rep.add(TRAIT_AS_ROOT, f"'{name}' is a trait; a trait cannot be instantiated as the root model", span=span,
                help="name a model with --model, or leave it out to load the last model of the file")
        return None
    if not isinstance(found, ModelSym):
        models = [s.path.parts[0].name for s in unit.tree.statements
                  if isinstance(s, ast.Declaration) and s.keyword != "becomes" and len(s.path.parts) == 1
                  and s.value is None]
        rep.add(NO_SUCH_ROOT, f"no model named '{name}'" + (f"; this file defines {', '.join(models)}" if models else ""),
                span=EMPTY_SPAN)
        return None
    return found


def analyse(path: Path, workspace, cfg, *, model: str | None = None, text: str | None = None) -> FileCheck:
    """Everything up to the scene IR (no MuJoCo).  ``text``: the file's content as an editor holds
    it (unsaved), checked in place of what is on disk (``plx view --web`` previews it)."""
    fc = FileCheck(str(path))
    t0 = time.perf_counter()
    try:
        from plxtools.cache import reads
        from plxtools.config import DEFAULT_MAX_FILE_MB

        data = (reads.read_bytes(path, cfg.max_file_bytes if cfg is not None else DEFAULT_MAX_FILE_MB << 20)
                if text is None else text.encode("utf-8", "surrogatepass"))
    except OSError as exc:
        fc.diagnostics = [unreadable(str(path), exc)]
        fc.skip = Skip.UNREADABLE
        return fc
    tree = parse_bytes(data, str(path))
    fc.tree = tree
    raw: list[Diagnostic] = list(tree.diagnostics)
    if any(d.code == registry.BINARY_FILE for d in tree.diagnostics):
        fc.skip = Skip.NOT_TEXT
        fc.diagnostics = _finish(tree, raw, cfg)
        return fc
    fa = analyse_file(workspace, tree, root_name=model)
    raw.extend(fa.diagnostics)
    fc.timings["lint"] = time.perf_counter() - t0
    rep = Reporter(fa.unit, str(path), skip_codes=_owned_by_lint(raw))
    if tree.has_errors:
        fc.skip = Skip.SYNTAX
        fc.diagnostics = _finish(tree, raw, cfg)
        return fc
    t1 = time.perf_counter()
    program = workspace.program
    root = _pick_root(program, fa.unit, model, rep)
    if root is None:
        if not rep.entries:
            fc.skip = Skip.NO_MODEL
        else:
            fc.skip = Skip.NO_ROOT
        scan_strings(tree, rep)
        fc.diagnostics = _finish(tree, _merge(raw, rep.diagnostics()), cfg)
        return fc
    fc.model = root.name
    rep.root_stmt = root.stmt if root.unit is fa.unit else None
    builder = Builder(program)
    builder.report = lambda code, msg, obj: rep.add(code, msg, obj=obj)
    obj = builder.root(root)
    fc.objects = builder.objects
    _not_analysed(builder, fa.unit, rep)
    ev = Evaluator(program, builder, fa.unit,
                   lambda code, msg, node, unit, anchor, help: rep.add(code, msg, node=node, unit=unit, obj=anchor,
                                                                       help=help))
    kinds = Kinds(program)
    asmb = Assembler(program, ev, rep, kinds)
    asm = asmb.run(obj)
    fc.assembly = asm
    col = Collector(asm, asmb, kinds, rep)
    col.run()
    StaticChecks(asm, asmb, col, kinds, rep).run()
    scan_strings(tree, rep)
    fc.scene = to_scene(asm, col, rep, os.path.dirname(os.path.abspath(str(path))))
    if cfg is not None:  # [check] integrator / timestep of the project's config (the CLI's flags win)
        if getattr(cfg, "check_timestep", None) is not None:
            fc.scene.timestep = cfg.check_timestep
        if getattr(cfg, "check_integrator", None) is not None:
            fc.scene.integrator = cfg.check_integrator
    fc.timings["assemble"] = time.perf_counter() - t1
    fc.rep, fc.raw, fc.cfg = rep, raw, cfg
    fc.evaluator, fc.kinds = ev, kinds
    fc.diagnostics = _finish(tree, _merge(raw, rep.diagnostics()), cfg)
    return fc


def _not_analysed(builder: Builder, unit, rep: Reporter) -> None:
    """One A042 (info) per imported file that plx cannot read and the scene uses: what is not analysed."""
    by_import: dict[int, tuple[ModelSym, list]] = {}
    for o, imp in builder.opaque:
        by_import.setdefault(id(imp), (imp, []))[1].append(o)
    for imp, objs in by_import.values():
        stmt = getattr(imp, "import_stmt", None)
        written = stmt.source.raw if stmt is not None else imp.qname
        names = [o.display for o in objs]
        shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
        span = stmt.source.span if stmt is not None and imp.unit is unit else None
        suffix = os.path.splitext(stmt.source.value)[1] if stmt is not None else ""
        rep.add(registry.IMPORTED_FILE_NOT_ANALYSED, f"{shown} {'is' if len(names) == 1 else 'are'} built from {written}, which plx cannot "
                f"read{f' ({suffix} file)' if suffix else ''}: the bodies, mates and values inside are not "
                f"analysed or simulated", obj=objs[0], span=span, severity=Severity.INFO,
                help="plx check analyses what is written in .openplx files (and reads .obj meshes)")


def blocking_reason(fc: FileCheck) -> str | None:
    """Why the MuJoCo backend (simulation, export, render) must not run on this file, or None.

    One rule: any error blocks it, because the scene then differs from the file (a value replaced by
    a fallback, an element dropped), so a motion, an exported model or a picture of it would
    mislead.  The exceptions are the errors whose scene is built exactly as written (A016: mates
    that do not coincide): simulating shows what they do."""
    if fc.skipped:
        return fc.skipped
    if fc.scene is None:
        return "no scene"
    bad = [d for d in fc.diagnostics if d.severity == Severity.ERROR and d.code not in SCENE_AS_WRITTEN]
    if bad:
        codes = ", ".join(sorted({d.code for d in bad}))
        return f"{len(bad)} error{'s make' if len(bad) != 1 else ' makes'} the scene unreliable ({codes})"
    return None


def run_backend(fc: FileCheck, *, simulate: bool, duration: float, compile_only: bool = False,
                record: bool = False, timeout: float | None = None, deadline: float | None = None) -> None:
    """Compile (and simulate) the file's scene; backend notes become diagnostics."""
    t0 = time.perf_counter()
    fc.compiled = mjb.compile_scene(fc.scene)
    fc.timings["compile"] = time.perf_counter() - t0
    notes = list(fc.compiled.notes)
    if simulate and fc.compiled.ok:
        t1 = time.perf_counter()
        fc.simulation = mjb.simulate(fc.compiled, duration, record=record, timeout=timeout, deadline=deadline)
        fc.timings["simulate"] = time.perf_counter() - t1
        notes = list(fc.simulation.notes)
        notes += aftersim.bodies_out_of_world(fc.simulation, fc.compiled.names.sources)
    add_backend_notes(fc.rep, fc.tree, notes)
    aftersim.tie_mirrored_motors(fc.rep)
    refresh(fc)


def refresh(fc: FileCheck) -> None:
    """Recompute the file's diagnostics after check added some (lint's and check's, filtered)."""
    fc.diagnostics = _finish(fc.tree, _merge(fc.raw, fc.rep.diagnostics()), fc.cfg)


def add_backend_notes(rep: Reporter, tree: ast.File, notes: list) -> None:
    """The backend's notes carry their rule codes (A1xx): each is reported as it is."""
    for n in notes:
        span = _span_of_source(tree, n.source) if n.source is not None else rep.anchor(None)
        rep.add(n.code, n.message, span=span, severity=n.severity, path=n.path)


def _span_of_source(tree: ast.File, src) -> Span:
    if src is None or src.line <= 0:
        return EMPTY_SPAN
    line, col = src.line - 1, max(src.column - 1, 0)
    end_line = (src.end_line - 1) if src.end_line > 0 else line
    end_col = (src.end_column - 1) if src.end_column > 0 else col
    try:
        a = tree.index.offset(line, col)
        b = tree.index.offset(end_line, end_col)
    except Exception:  # out of range: keep the line, drop the offset
        a = b = 0
    return Span(Pos(a, line, col), Pos(b, end_line, end_col))


def _owned_by_lint(lint: list[Diagnostic]) -> frozenset[str]:
    """The evaluation codes that lint's errors in this file already own (the registry's `owns`): a
    missing value (A004) after M007, a misspelt attribute or a syntax error; an unbound reference
    (A005) after M008 or T001; a value cycle (A006) after M006; an evaluation error (A003) after a
    type or name error. The evaluator does not make them again."""
    return registry.owned_by(d.code for d in lint if d.severity == Severity.ERROR)


def _merge(lint: list[Diagnostic], check: list[Diagnostic]) -> list[Diagnostic]:
    """Lint's findings, then check's, without the ones lint already made on the same line (a
    literal value out of its physical range is lint's, see rules/literals.py). A model that
    contains itself is lint's wherever check meets the ring (lint names the attribute that closes
    it, check the object where it stopped: one cause, said once)."""
    made = {(d.code, d.span.start.line) for d in lint}
    rings = any(d.code == registry.INSTANTIATION_TOO_DEEP for d in lint)
    return lint + [d for d in check if (d.code, d.span.start.line) not in made
                   and not (rings and d.code == registry.INSTANTIATION_TOO_DEEP)]


def _finish(tree: ast.File, diags: list[Diagnostic], cfg) -> list[Diagnostic]:
    """Lint's own config filtering and suppressions, over lint's and check's findings together."""

    return finalize(tree, diags, cfg)
