"""What a name means in an expression when it is not an ordinary value.

The checker, the editor features and the evaluator all resolve `Math.Vec3.from_xyz(...)` the same
way: `Math` is a namespace, `Math.Vec3` a type used for a static call, `from_xyz` a method.
"""

from __future__ import annotations

from dataclasses import dataclass

from plxtools.model.symbols import MethodSym, Namespace


@dataclass(frozen=True, slots=True)
class TypeObj:
    """A type named in an expression (for static calls), not a value."""

    sym: object  # ModelSym or a primitive name


@dataclass(frozen=True, slots=True)
class NsRef:
    ns: Namespace


@dataclass(frozen=True, slots=True)
class MethodRef:
    method: MethodSym
    on_type: bool
