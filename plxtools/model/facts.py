"""What the checker finds, as typed facts: no code, no message text (docs/architecture.md, "The
rule engine").

The model cannot import `rules/`, so it does not say how a finding is reported: it records what it
found (the names, types and places involved) and the rule modules under `plxtools/rules/` turn
each kind into its diagnostic, with the code, severity, message, help and fix the registry and the
module give. Facts are frozen, so a fact kept for the next version of a file (model/reuse.py) is
shared, never copied; every `Span` field is a place in the checked file, moved with it
(`Fact.moved`). Names are kept as text (qualified names, types as displayed), never as symbols:
a fact outlives the program version it was found in, and pickles.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

from plxtools.diagnostics import Span


@dataclass(frozen=True, slots=True)
class Fact:
    """One finding of the model at `span` (where it is reported)."""

    span: Span

    def moved(self, move) -> "Fact | None":
        """This fact with every place in it moved by `move(span) -> span | None` (None: one of
        them cannot be moved, so the finding must be made again)."""
        changes = {}
        for f in _span_fields(type(self)):
            old = getattr(self, f)
            if old is None:
                continue
            new = move(old)
            if new is None:
                return None
            if new is not old:
                changes[f] = new
        return replace(self, **changes) if changes else self


_SPAN_FIELDS: dict[type, tuple[str, ...]] = {}


def _span_fields(cls: type) -> tuple[str, ...]:
    """The fields of `cls` that hold a place (annotated `Span` or `Span | None`)."""
    got = _SPAN_FIELDS.get(cls)
    if got is None:
        got = _SPAN_FIELDS[cls] = tuple(f.name for f in fields(cls) if str(f.type).split(" |")[0] == "Span")
    return got


# ---------------------------------------------------------------- definitions and inheritance


@dataclass(frozen=True, slots=True)
class TooDeepToCheck(Fact):
    """A definition nests or refers to itself too deeply for the checker to follow."""


@dataclass(frozen=True, slots=True)
class InheritanceCycle(Fact):
    models: tuple[str, ...]  # qualified names, the first repeated at the end


@dataclass(frozen=True, slots=True)
class DeclaredTwice(Fact):
    """An attribute declared twice in one model."""

    name: str
    owner: str
    first_line: int  # 0-based, in this file


@dataclass(frozen=True, slots=True)
class DefinedTwice(Fact):
    """A top-level name defined twice in one namespace."""

    name: str
    first_path: str | None = None  # the file of the first definition, when it is another file
    first_line: int | None = None  # 0-based; None: unknown


@dataclass(frozen=True, slots=True)
class Redeclared(Fact):
    """`name is T` for a name the model (`in_model`) or the object configured already has."""

    name: str
    owner: str  # the model declaring it, or the type of the object
    in_model: bool
    written_type: str | None = None  # the first alternative of the new type, as written


@dataclass(frozen=True, slots=True)
class BecomesNotInherited(Fact):
    name: str
    where: str  # the model, or the type of the object configured
    suggestion: str | None  # the closest inherited name


@dataclass(frozen=True, slots=True)
class BecomesIncompatible(Fact):
    name: str
    new: str  # the type it would become
    declared: str  # its declared type
    owner: str  # the model declaring it


@dataclass(frozen=True, slots=True)
class ReferenceWithBlock(Fact):
    name: str


# ---------------------------------------------------------------- names, imports, bundles


@dataclass(frozen=True, slots=True)
class WrongKindOfType(Fact):
    """A model after `with` (`wanted` "trait") or a trait after `is` (`wanted` "model")."""

    type: str  # qualified name of what was found
    wanted: str
    written: str


@dataclass(frozen=True, slots=True)
class OpaqueImportName(Fact):
    """A one-part type name only an import plx cannot read may define."""

    written: str
    source: str  # what the unread import is, as the program describes it


@dataclass(frozen=True, slots=True)
class OutsideDependencies(Fact):
    """A type of a bundle the file's bundle does not depend on."""

    written: str
    bundle: str
    home: str


@dataclass(frozen=True, slots=True)
class ImportBindsNoName(Fact):
    """An import without `as` of a file whose stem is no valid name."""

    stem: str
    source: str  # the path as written, quotes and prefix included
    hint: str  # a valid name made from the stem


@dataclass(frozen=True, slots=True)
class ImportNamesNoFile(Fact):
    """An import of an empty path."""


@dataclass(frozen=True, slots=True)
class ImportFileMissing(Fact):
    shown: str  # the path as it may be shown (a $"..." path as written: no environment values)
    is_folder: bool
    from_environment: bool  # a $"..." path


@dataclass(frozen=True, slots=True)
class NoMemberOnValue(Fact):
    """`.name` on an array, alternatives or a primitive."""

    type: str
    name: str


@dataclass(frozen=True, slots=True)
class NoStaticFunction(Fact):
    model: str
    name: str
    suggestion: str | None


@dataclass(frozen=True, slots=True)
class NoAttributeOrMethod(Fact):
    model: str
    name: str
    suggestion: str | None


@dataclass(frozen=True, slots=True)
class DeprecatedMember(Fact):
    name: str
    note: str  # the bundle's deprecation note


@dataclass(frozen=True, slots=True)
class UnknownAnnotation(Fact):
    name: str


# ---------------------------------------------------------------- values and types


@dataclass(frozen=True, slots=True)
class Named:
    """What a name stands for where a value is needed: a "model" (named `name`, qualified `qname`,
    `declared_at` the header of its declaration when it is in this file), a "type", "namespace",
    "method" or "other"."""

    kind: str
    qname: str = ""
    name: str = ""


@dataclass(frozen=True, slots=True)
class NotAValue(Fact):
    """A type, namespace or method where a value is needed; `argument`: as a call's argument."""

    what: Named
    argument: bool = False
    declared_at: Span | None = None  # a model of this file: its declaration's header (to add `const`)


@dataclass(frozen=True, slots=True)
class ModelForValue(Fact):
    """A model given as a value where it is a kind of the attribute's type (`becomes` meant)."""

    model: str  # qualified
    name: str
    attribute_type: str


@dataclass(frozen=True, slots=True)
class TypeMismatch(Fact):
    """A value of type `found` where `expected` is needed. The hints say what the value most
    likely meant, when the model can tell."""

    expected: str
    found: str
    expected_primitive: str | None = None
    found_primitive: str | None = None
    # an array literal for a positional model: (its kind, its field names, the items' text or None
    # when their count differs)
    braces: tuple | None = None
    unquoted: str | None = None  # a Bool written in quotes: the word
    const: tuple | None = None  # a const's string given for it: (its name, the string, its attribute)


@dataclass(frozen=True, slots=True)
class BraceForPrimitive(Fact):
    primitive: str


@dataclass(frozen=True, slots=True)
class RealForInt(Fact):
    pass


@dataclass(frozen=True, slots=True)
class BraceLength(Fact):
    model: str
    fields: tuple[str, ...]
    given: int


@dataclass(frozen=True, slots=True)
class OperatorArity(Fact):
    op: str
    given: int


@dataclass(frozen=True, slots=True)
class CallArity(Fact):
    owner: str
    method: str
    wanted: int
    given: int
    signature: str  # the method's signature as OpenPLX writes it


@dataclass(frozen=True, slots=True)
class ArgumentType(Fact):
    method: str
    expected: str
    found: str
    signature: str


@dataclass(frozen=True, slots=True)
class NoOperator(Fact):
    op: str
    operands: tuple[str, ...]
    quat_times: bool = False  # a Quat on the left of `*`


@dataclass(frozen=True, slots=True)
class ReturnsNothing(Fact):
    owner: str
    method: str


@dataclass(frozen=True, slots=True)
class MethodNotCalled(Fact):
    """`.name` after a method that was not called."""

    method: str
    name: str


@dataclass(frozen=True, slots=True)
class NotCallable(Fact):
    what: Named | None  # None: a value
    type: str = ""  # the value's type


@dataclass(frozen=True, slots=True)
class InstanceMethodOnType(Fact):
    method: str
    owner: str


@dataclass(frozen=True, slots=True)
class StaticOnInstance(Fact):
    method: str
    owner: str


@dataclass(frozen=True, slots=True)
class IndexNotInt(Fact):
    type: str


@dataclass(frozen=True, slots=True)
class NotIndexable(Fact):
    type: str


# ---------------------------------------------------------------- bundle configs (config.openplx)


@dataclass(frozen=True, slots=True)
class ConfigWithoutName(Fact):
    """A bundle config without `config is BundleConfig:` (`declared` False) or without a name."""

    declared: bool


@dataclass(frozen=True, slots=True)
class BadDependency(Fact):
    """`dependencies` that is no array ("not-array"), an item that is no string ("not-string") or a
    string of no form OpenPLX reads ("malformed", `value`)."""

    kind: str
    value: str = ""


@dataclass(frozen=True, slots=True)
class UnreadDependencyForm(Fact):
    """A dependency like `Physics>=0.19`: read as its bare `name`, selecting no version."""

    written: str
    name: str


@dataclass(frozen=True, slots=True)
class UnknownDependency(Fact):
    """A dependency no loaded bundle is named; or (`loaded_from`) a second bundle of one name."""

    name: str
    loaded_from: str | None = None


@dataclass(frozen=True, slots=True)
class DependencyCycle(Fact):
    bundles: tuple[str, ...]


# ---------------------------------------------------------------- unknown names (and older versions' names)


@dataclass(frozen=True, slots=True)
class UnknownType(Fact):
    """A type name that does not resolve ("unknown"), names a namespace or a global value. The
    workspace adds what it knows of the bundles: one that is not loaded (`bundle`), newer bundles
    (`newer`), the official versions that have the name (`versions`)."""

    written: str
    kind: str = "unknown"  # "unknown" | "namespace" | "global"
    suggestion: str | None = None  # the name most likely meant
    listing: tuple | None = None  # (namespace, some of its names, whether it has more)
    bundle: tuple | None = None  # see UnknownName
    newer: tuple | None = None  # ("agx", written, using, AGX version, its OpenPLX version, its bundles)
    # or ("release", written, newest release)
    versions: tuple | None = None  # (written, the versions that have it as text, the last of them, using)


@dataclass(frozen=True, slots=True)
class UnknownAttribute(Fact):
    """An attribute path step that the object (`owner`) does not have."""

    name: str
    owner: str
    suggestion: str | None = None
    broken_line: int | None = None  # a line declaring the name did not parse (0-based)
    on_value: bool = False  # the object is an array, alternatives or a primitive (`owner`: its type)
    kind_of: tuple | None = None  # a kind of the owner has it: (its name, qualified, the path, its last part)


@dataclass(frozen=True, slots=True)
class UnknownName(Fact):
    """A name in an expression that does not resolve (or not in `namespace`)."""

    name: str
    suggestion: str | None = None
    broken_line: int | None = None
    namespace: str | None = None
    # a bundle of that name is not loaded: ("nearby", name, its folder), ("dependency", name, the
    # config naming it), ("agx", what AGX installation was found or None, its bundle folder or None)
    bundle: tuple | None = None


@dataclass(frozen=True, slots=True)
class OlderName(Fact):
    """An unknown type that an older official version had, renamed one to one since."""

    written: str
    new: str
    older: str  # the newest version that had it
    using: str
    declared: bool  # a rename OpenPLX's own migration list declares
    command: str  # the `plx migrate` command that works as printed for this file


@dataclass(frozen=True, slots=True)
class RenamedAttribute(Fact):
    """An unknown attribute that an older official version renamed."""

    written: str
    new: str
    since: str
    owners: str  # some of the models that renamed it
    older_version: str | None
    command: str = ""
