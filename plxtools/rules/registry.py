"""The rule registry: one entry per diagnostic code, with the docs page that `plx rule` prints.

Every code any layer emits (syntax, semantic model, assembly checks, simulation) is registered
here, so docs, SARIF rule tables, `select`/`ignore` and the severity every command prints all come
from one list: the table below, the only place a code is written (`docs/architecture.md`, "The rule
engine"). A rule in the module form names its module there; its documentation is that module's
docstring and its findings are made by that module's `check`. The pages of the other rules are in
`catalog/`, keyed by their constant here.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass, replace
from functools import cache

from plxtools.diagnostics import Severity


@dataclass(frozen=True, slots=True)
class Rule:
    code: str
    name: str  # kebab-case
    severity: Severity
    summary: str
    why: str
    example: str = ""
    use_instead: str = ""
    fix: str = "none"  # "none" | "safe" | "unsafe"
    stage: str = "lint"  # "syntax" | "lint" | "check" | "simulate"
    # the rule module under plxtools/rules/ that makes this code's findings and holds its docs
    # ("assembly.shared_connector"); None for a rule still in the older form
    module: str | None = None
    tags: tuple[str, ...] = ()  # "deprecated", "unnecessary": how an editor may draw the finding
    # codes this one makes redundant: when both are reported on one line, only this one stands
    owns: tuple[str, ...] = ()
    # the severity of the code's graver form, when the raising site tells two forms apart (S003: a
    # tab that makes a line's block ambiguous is an error); None: one severity for every finding
    graver: Severity | None = None
    # the severity of the code's milder form (A031: a missing visual mesh, or a file behind an
    # environment variable, is a warning where a missing file is otherwise an error)
    milder: Severity | None = None

    def page(self) -> str:
        """The rule's documentation page as Markdown."""
        out = [f"# {self.code} {self.name}", "", f"Default severity: **{self.severity.value}** · "
               f"stage: `{self.stage}` · fix: {self._fix_text()}", "", "## What it does", "",
               self.summary, "", "## Why it matters", "", self.why, ""]
        if self.example:
            out += ["## Example", "", "```openplx", self.example.rstrip(), "```", ""]
        if self.use_instead:
            out += ["## Use instead", "", "```openplx", self.use_instead.rstrip(), "```", ""]
        return "\n".join(out)

    def _fix_text(self) -> str:
        return {"none": "not fixable", "safe": "safe fix available", "unsafe": "unsafe fix available"}[self.fix]


RULES: dict[str, Rule] = {}


def rule(code: str, name: str, severity: Severity, summary: str = "", why: str = "", *, example: str = "",
         use_instead: str = "", fix: str = "none", stage: str = "lint", module: str | None = None,
         tags: tuple[str, ...] = (), owns: tuple[str, ...] = (), graver: Severity | None = None,
         milder: Severity | None = None) -> Rule:
    if code in RULES:
        raise ValueError(f"duplicate rule code {code}")
    r = Rule(code, name, severity, summary, why, example, use_instead, fix, stage, module, tags, owns, graver, milder)
    RULES[code] = r
    return r


def entry(code: str, name: str, severity: Severity, *, stage: str = "lint", fix: str = "none",
          module: str | None = None, tags: tuple[str, ...] = (), owns: tuple[str, ...] = (),
          graver: Severity | None = None, milder: Severity | None = None) -> str:
    """Register one code (its documentation comes later: `doc()` or its module's docstring) and
    return it, so that the table below gives every code its constant."""
    rule(code, name, severity, stage=stage, fix=fix, module=module, tags=tags, owns=owns, graver=graver, milder=milder)
    return code


# ---------------------------------------------------------------- every code
# The only place a code is written. Layers above `rules` name a code by its constant here
# (`registry.MISSING_VALUE`); a rule in the module form is found through `module` (under
# plxtools/rules/) and documented by that module's docstring; the others by `doc()` in catalog/.
# `stage`: who reports it (syntax, lint, check, simulate); `fix`: none, safe or unsafe; `graver`:
# the severity of its graver form; `tags`: deprecated, unnecessary (how an editor draws it), layout
# (decides which block a line is read into), version (a name of an older bundle version: migrate);
# `owns`: codes it makes redundant: dropped on its line when it is at least as grave, and not made
# by check's evaluator in a file where it is an error (no A004, a missing value, after M007).
E, W, I = Severity.ERROR, Severity.WARNING, Severity.INFO

# ---------------------------------------------------------------- syntax (docs: catalog/syntax.py)
BINARY_FILE = entry("S001", "binary-file", E, stage="syntax", owns=("A004",))
INVALID_UTF8 = entry("S002", "invalid-utf8", E, stage="syntax", owns=("A004",))
TAB_INDENTATION = entry("S003", "tab-indentation", W, stage="syntax", graver=E, tags=("layout",), owns=("A004",))
UNBALANCED_BRACKET = entry("S004", "unbalanced-bracket", E, stage="syntax", owns=("A004",))
INVALID_NUMBER = entry("S005", "invalid-number", E, stage="syntax", owns=("A004",))
EMPTY_BACKTICK_NAME = entry("S006", "empty-backtick-name", E, stage="syntax", owns=("A004",))
NESTING_TOO_DEEP = entry("S007", "nesting-too-deep", E, stage="syntax", owns=("A004",))
UNEXPECTED_CHARACTER = entry("S008", "unexpected-character", E, stage="syntax", owns=("A004",))
UNTERMINATED_STRING = entry("S009", "unterminated-string", E, stage="syntax", owns=("A004",))
EXPECTED_INDENTED_BLOCK = entry("S010", "expected-indented-block", E, stage="syntax", owns=("A004",))
INVALID_SYNTAX = entry("S011", "invalid-syntax", E, stage="syntax", owns=("A004",))
MISPLACED_STATEMENT = entry("S012", "misplaced-statement", E, stage="syntax", owns=("A004",))
INCOMPLETE_MEMBER = entry("S013", "incomplete-member", E, stage="syntax", owns=("A004",))
NON_LITERAL_ANNOTATION = entry("S014", "non-literal-annotation", E, stage="syntax", owns=("A004",))
INDENTATION_BETWEEN_LEVELS = entry("S015", "indentation-between-levels", E, stage="syntax", tags=("layout",), owns=("A004",))
MISSING_COLON = entry("S016", "missing-colon", E, stage="syntax", fix="safe", owns=("A004",))
# ---------------------------------------------------------------- semantic (docs: catalog/semantic.py)
UNREADABLE_FILE = entry("E001", "unreadable-file", E)
UNRESOLVED_TYPE = entry("N001", "unresolved-type", E, fix="unsafe", owns=("A003",))
UNKNOWN_ATTRIBUTE = entry("N002", "unknown-attribute", E, fix="unsafe", owns=("A003", "A004",))
UNRESOLVED_NAME = entry("N003", "unresolved-name", E, fix="unsafe", owns=("A003",))
BUNDLES_UNAVAILABLE = entry("B000", "bundles-unavailable", W)
NAMING_CONVENTION = entry("C001", "naming-convention", I)
MISALIGNED_INDENTATION = entry("C006", "misaligned-indentation", I)
# ---------------------------------------------------------------- hygiene (docs: catalog/hygiene.py)
UNUSED_SUPPRESSION = entry("C002", "unused-suppression", W, fix="safe", tags=("unnecessary",))
# ---------------------------------------------------------------- assembly (docs: catalog/assembly.py)
ROOT_MODEL_NOT_FOUND = entry("A001", "root-model-not-found", E, stage="check")
ROOT_IS_TRAIT = entry("A002", "root-is-trait", E, stage="check")
EVALUATION_ERROR = entry("A003", "evaluation-error", E, stage="check")
MISSING_VALUE = entry("A004", "missing-value", E, stage="check")
EVALUATED_UNBOUND_REFERENCE = entry("A005", "unbound-reference", E, stage="check")
VALUE_CYCLE = entry("A006", "value-cycle", E, stage="check")
ENVIRONMENT_VARIABLE_UNSET = entry("A007", "environment-variable-unset", W, stage="check")
UNSUPPORTED_FUNCTION = entry("A008", "unsupported-function", W, stage="check")
INSTANTIATION_TOO_DEEP = entry("A009", "instantiation-too-deep", E, stage="check")
ZERO_MAIN_AXIS = entry("A010", "zero-main-axis", E, stage="check")
DEGENERATE_NORMAL = entry("A011", "degenerate-normal", E, stage="check")
NORMAL_NOT_ORTHOGONAL = entry("A012", "normal-not-orthogonal", I, stage="check")
CONNECTOR_COUNT = entry("A013", "connector-count", E, stage="check")
MATE_SAME_CONNECTOR = entry("A014", "mate-same-connector", E, stage="check")
MATE_SAME_BODY = entry("A015", "mate-same-body", E, stage="check")
MATE_NOT_COINCIDENT = entry("A016", "mate-not-coincident", E, stage="check")
MATE_WITHOUT_DYNAMIC_BODY = entry("A017", "mate-without-dynamic-body", W, stage="check")
HINGE_AXIS_OFF_CYLINDER_AXIS = entry("A018", "hinge-axis-off-cylinder-axis", W, stage="check")
CONTROLLER_WITHOUT_MATE = entry("A020", "controller-without-mate", E, stage="check")
CONTROLLER_DOF_MISMATCH = entry("A021", "controller-dof-mismatch", E, stage="check")
ANGLE_PROBABLY_DEGREES = entry("A022", "angle-probably-degrees", I, stage="check")
MIRRORED_DRIVE_MOTORS = entry("A023", "mirrored-drive-motors", I, stage="check")
INVERTED_LIMITS = entry("A024", "inverted-limits", E, stage="check")
NON_POSITIVE_SIZE = entry("A030", "non-positive-size", E, stage="check")
MISSING_FILE = entry("A031", "missing-file", E, stage="check", milder=W)
NEGATIVE_MASS = entry("A032", "negative-mass", E, stage="check")
ZERO_MASS_DYNAMIC_BODY = entry("A033", "zero-mass-dynamic-body", E, stage="check", owns=("A047",))
INVALID_INERTIA = entry("A034", "invalid-inertia", E, stage="check")
DUPLICATE_CONTACT_MODEL = entry("A035", "duplicate-contact-model", E, stage="check")
INVALID_CONTACT_PARAMETER = entry("A036", "invalid-contact-parameter", E, stage="check")
UNPLACED_BODY_OVERLAPS = entry("A037", "unplaced-body-overlaps", W, stage="check")
NON_POSITIVE_DENSITY = entry("A038", "non-positive-density", W, stage="check")
BODY_NOT_IN_SYSTEM = entry("A039", "body-not-in-system", W, stage="check")
NOT_SIMULATED = entry("A040", "unsupported-feature", W, stage="check")
RANGE_STARTS_VIOLATED = entry("A045", "range-starts-violated", W, stage="check")
IMPORTED_FILE_NOT_ANALYSED = entry("A042", "imported-file-not-analysed", I, stage="check")
NON_FINITE_VALUE = entry("A041", "non-finite-value", E, stage="check")
COLLISION_PAIR_WITHOUT_EFFECT = entry("A044", "collision-pair-without-effect", I, stage="check")
SIMULATION_BLOWUP = entry("A101", "simulation-blowup", E, stage="simulate")
FELL_THROUGH = entry("A102", "fell-through-ground", E, stage="simulate")
MATE_DRIFT = entry("A103", "mate-came-apart", W, stage="simulate")
OVERLAP_AT_START = entry("A104", "initial-penetration", W, stage="simulate")
JOINT_LIMIT_EXCEEDED = entry("A105", "joint-limit-exceeded", W, stage="simulate")
MOTOR_OFF_TARGET = entry("A106", "motor-not-tracking", W, stage="simulate")
BAD_CONTROL = entry("A107", "bad-control", E, stage="simulate")
SIMULATION_INCOMPLETE = entry("A108", "simulation-incomplete", I, stage="simulate")
SIMULATION_TIMEOUT = entry("A109", "simulation-timeout", E, stage="simulate")
MUJOCO_COMPILE_ERROR = entry("A110", "mujoco-compile-error", E, stage="simulate")
VELOCITY_MOTOR_GAIN_CLAMPED = entry("A111", "velocity-motor-gain-clamped", I, stage="simulate", graver=W)
SPRING_STIFFNESS_CLAMPED = entry("A112", "spring-stiffness-clamped", W, stage="simulate")
FRICTION_MODEL_APPROXIMATED = entry("A113", "friction-model-approximated", I, stage="simulate")
LOOP_CLOSURE = entry("A114", "loop-closure", I, stage="simulate")
LOOP_CLOSURE_UNSUPPORTED = entry("A115", "loop-closure-unsupported", W, stage="simulate")
DISTANCE_MATE_APPROXIMATED = entry("A116", "distance-mate-approximated", W, stage="simulate")
CONCAVE_MESH_HULL = entry("A117", "concave-mesh-hull", I, stage="simulate")
MESH_FORMAT_UNSUPPORTED = entry("A118", "mesh-format-unsupported", W, stage="simulate")
RANGE_EFFORT_IGNORED = entry("A119", "range-effort-ignored", I, stage="simulate")
INITIAL_VELOCITY_IGNORED = entry("A120", "initial-velocity-ignored", I, stage="simulate")
KINEMATIC_BODY = entry("A121", "kinematic-body", I, stage="simulate")
CONTROLLER_REVERSED = entry("A122", "controller-reversed", I, stage="simulate")
CONTROLLER_ON_DISABLED_MATE = entry("A123", "controller-on-disabled-mate", W, stage="simulate")
CONTROLLER_ON_LOOP_MATE = entry("A124", "controller-on-loop-mate", W, stage="simulate")
STACKED_CONTROLLERS = entry("A125", "stacked-controllers", I, stage="simulate")
MASS_WITHOUT_GEOMETRY = entry("A126", "mass-without-geometry", W, stage="simulate")
PLANE_ON_DYNAMIC_BODY = entry("A127", "plane-on-dynamic-body", W, stage="simulate")
CONTACT_MODEL_UNUSED = entry("A128", "contact-model-unused", I, stage="simulate")
DISABLED_ELEMENT = entry("A129", "disabled-element", I, stage="simulate")
INVALID_CONTROLLER_PARAMETER = entry("A130", "invalid-controller-parameter", E, stage="simulate")
SCENE_INCONSISTENT = entry("A131", "scene-inconsistent", E, stage="simulate")
TIMESTEP_SHORTENED = entry("A133", "timestep-shortened", I, stage="simulate")
ENERGY_GAIN = entry("A134", "energy-gain", W, stage="simulate")
IMPLAUSIBLE_SPEED = entry("A135", "implausible-speed", W, stage="simulate")
RESTITUTION_APPROXIMATED = entry("A137", "restitution-approximated", I, stage="simulate", graver=W)
VISUAL_MESH_SKIPPED = entry("A138", "visual-mesh-skipped", I, stage="simulate")
MJCF_EXPORT_UNLOADABLE = entry("A132", "mjcf-export-unloadable", E, stage="simulate")
EXPECTATION_FAILED = entry("A140", "expectation-failed", E, stage="test")
INVALID_SCENARIO = entry("A141", "invalid-scenario", E, stage="test")
SCENARIO_MODEL_NOT_SIMULATED = entry("A142", "scenario-model-not-simulated", E, stage="test")

# ---------------------------------------------------------------- rules in the module form
# One line per code. `module` is under plxtools/rules/; its docstring is the docs page and its
# `check(facts, report)` makes the findings (plxtools/rules/engine.py runs it for lint, check and
# the language server). Several tightly tied codes may share one module: it names the one it
# reports with `report(..., rule="their-name")`.
#
#     code    name                           severity  module                      stage, fix, tags, owns
MODULE_RULES = (
    ("A009", "instantiation-too-deep", E, "assembly.self_containing", dict(stage="lint")),
    ("A013", "connector-count", E, "assembly.controller_connectors", dict(stage="lint")),
    ("A015", "mate-same-body", E, "assembly.shared_connector", dict(fix="unsafe", stage="lint")),
    ("A022", "angle-probably-degrees", W, "assembly.angle_in_degrees", dict(fix="unsafe", stage="lint", milder=I)),
    ("A043", "connector-used-by-two-mates", E, "assembly.shared_connector", dict(fix="unsafe")),
    ("A046", "controller-on-other-mate", W, "assembly.controller_connectors", dict()),
    ("A047", "explicit-zero-mass", W, "assembly.explicit_zero_mass", dict()),
    ("A048", "length-in-millimetres", W, "assembly.length_in_millimetres", dict()),
    ("A049", "dynamic-ground", W, "assembly.dynamic_ground", dict()),
    ("B001", "bundle-config-name", E, "bundles.bundle_config_name", dict()),
    ("B002", "bad-dependency-string", E, "bundles.bad_dependency_string", dict()),
    ("B003", "unknown-dependency", E, "bundles.unknown_dependency", dict()),
    ("B004", "dependency-cycle", E, "bundles.dependency_cycle", dict()),
    ("B005", "outside-dependencies", E, "bundles.outside_dependencies", dict()),
    ("B006", "unread-dependency-form", W, "bundles.unread_dependency_form", dict()),
    ("C003", "unused-model", W, "semantic.unused_model", dict()),
    ("C004", "deprecated-attribute", W, "conventions.deprecated_attribute", dict(tags=("deprecated",))),
    ("C005", "unknown-annotation", I, "conventions.unknown_annotation", dict()),
    ("C007", "root-not-system", W, "semantic.root_not_system", dict()),
    ("M001", "redeclared-attribute", E, "structure.redeclared_attribute", dict()),
    ("M002", "becomes-not-inherited", E, "structure.becomes_not_inherited", dict()),
    ("M003", "becomes-incompatible", E, "structure.becomes_incompatible", dict()),
    ("M004", "duplicate-definition", E, "structure.duplicate_definition", dict()),
    ("M005", "inheritance-cycle", E, "structure.inheritance_cycle", dict()),
    ("M006", "default-cycle", E, "semantic.default_cycle", dict(owns=("A006",))),
    ("M007", "missing-assignment", E, "semantic.missing_assignment", dict(owns=("A004",))),
    ("M008", "unbound-reference", E, "semantic.unbound_reference", dict(owns=("A005",))),
    ("M009", "reference-with-block", E, "structure.reference_with_block", dict()),
    ("M010", "assigned-twice", E, "semantic.assigned_twice", dict()),
    ("N001", "unresolved-type", E, "names.unresolved_type", dict(fix="unsafe", owns=("A003",))),
    ("N002", "unknown-attribute", E, "names.unknown_attribute", dict(fix="unsafe", owns=("A003", "A004",))),
    ("N003", "unresolved-name", E, "names.unresolved_name", dict(fix="unsafe", owns=("A003",))),
    ("N004", "unknown-member", E, "names.unknown_member", dict(fix="unsafe", owns=("A003",))),
    ("N005", "wrong-kind-of-type", E, "names.wrong_kind_of_type", dict(owns=("A003",))),
    ("N006", "import-file-not-found", E, "names.import_file_not_found", dict(owns=("A003",))),
    ("N007", "import-needs-alias", E, "names.import_needs_alias", dict(owns=("A003",))),
    ("N008", "name-from-opaque-import", I, "names.name_from_opaque_import", dict(owns=("A003",))),
    ("T001", "type-mismatch", E, "types.type_mismatch", dict(owns=("A003", "A005",))),
    ("T002", "real-for-int", W, "types.real_for_int", dict(owns=("A003",))),
    ("T003", "brace-literal-length", E, "types.brace_literal_length", dict(owns=("A003",))),
    ("T004", "wrong-arity", E, "types.wrong_arity", dict(owns=("A003",))),
    ("T005", "argument-type", E, "types.argument_type", dict(owns=("A003",))),
    ("T006", "no-operator", E, "types.no_operator", dict(owns=("A003",))),
    ("T007", "void-in-expression", E, "types.void_in_expression", dict(owns=("A003",))),
    ("T008", "bad-call", E, "types.bad_call", dict(owns=("A003",))),
    ("T009", "bad-index", E, "types.bad_index", dict(owns=("A003",))),
    ("U001", "renamed-model", E, "names.older_name", dict(fix="safe", tags=("version",))),
    ("U002", "renamed-attribute", E, "names.renamed_attribute", dict(fix="unsafe", tags=("version",))),
)

_loaded = False

for _code, _name, _severity, _module, _more in MODULE_RULES:
    if _code in RULES:  # a code of the table above (raised elsewhere by its constant) moved to a module
        RULES[_code] = replace(RULES[_code], name=_name, severity=_severity, module=_module, **_more)
    else:
        entry(_code, _name, _severity, module=_module, **_more)


def _load() -> None:
    global _loaded
    if _loaded:
        return
    _loaded = True
    # the catalogue holds the documentation of the rules not in the module form; read only when a
    # page or the whole list is asked for (lint's own runs never need it)
    from plxtools.rules.catalog import pages

    constants = globals()
    for constant, docs in pages.DOCS.items():
        code = constants.get(constant)
        if not isinstance(code, str) or code not in RULES:
            raise ValueError(f"rules/catalog/: a page for {constant}, which is no code of the registry")
        RULES[code] = replace(RULES[code], **docs)
    for r in list(RULES.values()):
        if r.module is not None:
            RULES[r.code] = replace(r, **_docs_of(r.module))


@cache
def tagged(tag: str) -> frozenset[str]:
    """The codes carrying `tag` ("layout": decides which block a line is read into; "deprecated",
    "unnecessary": how an editor draws them)."""
    return frozenset(r.code for r in RULES.values() if tag in r.tags)


def owned_by(codes) -> frozenset[str]:
    """The codes that `codes` make redundant (their `owns`)."""
    return frozenset(owned for c in codes if c in RULES for owned in RULES[c].owns)


def module_of(r: Rule):
    """The imported rule module of `r` (None for a rule in the older form)."""
    return importlib.import_module(f"plxtools.rules.{r.module}") if r.module else None


_SECTION = re.compile(r"^## (.+)$", re.M)
_CODE_BLOCK = re.compile(r"```openplx\n(.*?)```", re.S)


def _docs_of(module: str) -> dict[str, str]:
    """summary, why, example and use_instead read from a rule module's docstring: the paragraph(s)
    before its first `## ` heading, then `## Why it matters`, `## Example` and `## Use instead`."""
    doc = (importlib.import_module(f"plxtools.rules.{module}").__doc__ or "").strip()
    parts = _SECTION.split(doc)
    sections = dict(zip(parts[1::2], parts[2::2]))
    out = {"summary": _one_paragraph(parts[0]), "why": _one_paragraph(sections.get("Why it matters", ""))}
    for title, field in (("Example", "example"), ("Use instead", "use_instead")):
        block = _CODE_BLOCK.search(sections.get(title, ""))
        out[field] = block.group(1).rstrip("\n") if block else ""
    if not out["summary"] or not out["why"]:
        raise ValueError(f"rule module plxtools.rules.{module}: its docstring needs a summary and '## Why it matters'")
    return out


def _one_paragraph(text: str) -> str:
    return " ".join(text.split())


def severity_of(code: str, raised: Severity) -> Severity:
    """The severity every command reports `code` with: the registry's (`raised`, the raising site's,
    for an unknown code). A site may only say that a finding is the graver (or milder) form of its
    code when the registry names that form (`graver`, `milder`)."""
    _load()
    r = RULES.get(code)
    if r is None:
        return raised
    if r.graver is not None and raised.rank > r.severity.rank:
        return r.graver
    if r.milder is not None and raised.rank < r.severity.rank:
        return r.milder
    return r.severity


def all_rules() -> list[Rule]:
    _load()
    return sorted(RULES.values(), key=lambda r: r.code)


def get(code_or_name: str) -> Rule | None:
    _load()
    if code_or_name.upper() in RULES:
        return RULES[code_or_name.upper()]
    for r in RULES.values():
        if r.name == code_or_name:
            return r
    return None


def describe_codes(codes: set[str]) -> list[tuple[str, str, str]]:
    _load()
    return [(c, RULES[c].name, RULES[c].summary) for c in sorted(codes) if c in RULES]


def unknown_selectors(selectors) -> list[tuple[str, str | None]]:
    """The codes or prefixes in `selectors` that match no rule, each with the nearest real one.

    `N0002` in a `select` would otherwise silently select nothing, which reads as "all clear"."""
    selectors = [s for s in selectors if s.strip()]
    if not selectors:
        return []  # nothing to look up: the catalogue is not even loaded
    import difflib

    _load()
    prefixes = {code[:i] for code in RULES for i in range(1, len(code) + 1)}
    out = []
    for s in selectors:
        s = s.strip().upper()
        if not s or s == "ALL" or s in prefixes:
            continue
        near = difflib.get_close_matches(s, sorted(RULES) if len(s) >= 3 else sorted(prefixes), n=1, cutoff=0.6)
        out.append((s, near[0] if near else None))
    return out


def check_selectors(selectors, where: str) -> None:
    """Raise ValueError naming every unknown code or prefix in `selectors` (from `where`)."""
    bad = unknown_selectors(selectors)
    if bad:
        parts = [f"'{code}'" + (f" (did you mean '{near}'?)" if near else "") for code, near in bad]
        noun = "rule code or prefix" if len(bad) == 1 else "rule codes or prefixes"
        raise ValueError(f"{where}: unknown {noun} {', '.join(parts)}; `plx rule --all` lists them")
