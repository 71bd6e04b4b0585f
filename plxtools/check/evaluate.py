"""Evaluate values on an instantiated object tree, lazily and memoised, with cycle detection.

Names resolve as the type checker resolves them (spec C.6): a bare name is first an attribute of
the *scope* object (the instance of the outermost model whose body holds the expression), then a
global: a const model (its singleton), a global attribute (``Math.PI``), a namespace, or a type
for a static call.  ``this`` is the scope object.  Functions and operators are the numpy
implementations of :mod:`plxtools.model.natives`.

Defaults are evaluated late, on the final object: ``MateConnector.normal`` is
``main_axis.get_orthogonal_unit_vector()`` evaluated with the connector as scope, so it follows a
``main_axis`` overridden anywhere.

Errors never escape as Python exceptions to the caller of :meth:`Evaluator.get`: each problem is
reported once, as a located diagnostic (through ``report``), and the caller gets
:class:`Unavailable`.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from plxtools import envpath
from plxtools.check.instance import VALUE, Builder, Obj, Prim, Ref
from plxtools.model import natives, resolve
from plxtools.model.natives import NativeError, Transform, struct_types
from plxtools.model.program import Program
from plxtools.model.symbols import GlobalSym, MethodSym, ModelSym, Ty
from plxtools.model.values import MethodRef, NsRef, TypeObj
from plxtools.syntax import ast
from plxtools.rules import registry


class Unavailable(Exception):
    """A value could not be computed; the reason has already been reported."""


# The codes this module raises (their home): the evaluator's own findings.  The pipeline imports
# these names to drop the ones lint already owns; the assembler reports a non-finite value through
# report_non_finite() below.


def report_non_finite(rep: Any, message: str, **where: Any) -> Any:
    """A041: a value that is not a finite number (an overflow, inf - inf), placed as ``Reporter.add``
    places it."""
    return rep.add(registry.NON_FINITE_VALUE, message, **where)


class EvalError(Exception):
    def __init__(self, code: str, message: str, node: Any = None, unit: Any = None, help: str | None = None):
        super().__init__(message)
        self.code = code
        self.message = message
        self.node = node  # an ast node (span) or None
        self.unit = unit
        self.help = help


@dataclass(frozen=True, slots=True)
class SView:
    """A value-type object (or a part of one: ``transform.position``) seen from an expression."""

    obj: Obj
    sub: tuple
    tname: str


@dataclass(frozen=True, slots=True)
class Bound:
    """A method looked up on a receiver (None for static functions)."""

    recv: Any
    meth: MethodSym | None
    qname: str


_MISSING = object()


def _codec_field_type(structs: dict, tname: str, sub: tuple) -> str | None:
    cur = tname
    for f in sub:
        codec = structs.get(cur)
        if codec is None or f not in codec.field_types:
            return None
        cur = codec.field_types[f]
    return cur


def _component(structs: dict, value: Any, tname: str, sub: tuple) -> Any:
    cur, t = value, tname
    for f in sub:
        codec = structs[t]
        cur = codec.to_fields(cur)[f]
        t = codec.field_types[f]
    return cur


class Evaluator:
    def __init__(self, program: Program, builder: Builder, unit, report: Callable[..., None]):
        """``report(code, message, span_node_or_None, unit_or_None, anchor_obj, help)``."""
        self.p = program
        self.structs = struct_types(program)
        self.b = builder
        self.unit = unit
        self.report = report
        self._memo: dict[Any, Any] = {}
        self._active: dict[Any, str] = {}  # keys being evaluated -> display name (cycle detection)
        self._stack: list[str] = []
        self._failed: set = set()
        # values may chain through thousands of others; each link takes ~10 Python frames (3.11 does
        # not use the C stack for them).  Deeper chains end in a located A006, not a crash.
        if sys.getrecursionlimit() < 20000:
            sys.setrecursionlimit(20000)

    # ------------------------------------------------------------------ public API

    def get(self, obj: Obj, path: str, default: Any = _MISSING) -> Any:
        """The value at a dotted path below ``obj``: a Python/numpy value, an :class:`Obj`, a list,
        or None for an unbound optional reference.  Returns ``default`` when the attribute does not
        exist (if given), raises :class:`Unavailable` when it cannot be computed."""
        cur: Any = obj
        parts = path.split(".") if path else []
        for i, name in enumerate(parts):
            if isinstance(cur, SView):
                ftype = _codec_field_type(self.structs, cur.tname, (name,))
                if ftype is None:
                    if default is not _MISSING:
                        return default
                    raise KeyError(f"{cur.obj.display}: no field {name}")
                cur = SView(cur.obj, cur.sub + (name,), ftype)
                continue
            if not isinstance(cur, Obj):
                if default is not _MISSING:
                    return default
                raise KeyError(f"{path}: {parts[i - 1]} is not an object")
            nxt = self._attr(cur, name)
            if nxt is _MISSING:
                if default is not _MISSING:
                    return default
                raise KeyError(f"{cur.display} has no attribute {name}")
            cur = nxt
        return self.value(cur)

    def child(self, obj: Obj, path: str) -> Any:
        """The owned object / reference target at a dotted path (no value conversion), or None."""
        cur: Any = obj
        for name in path.split("."):
            if not isinstance(cur, Obj):
                return None
            c = cur.children.get(name)
            if c is None:
                return None
            if isinstance(c, Ref):
                try:
                    c = self.deref(c)
                except Unavailable:
                    return None
            cur = c
        return cur

    def value(self, v: Any) -> Any:
        """Turn an expression result into a plain value (struct objects become numpy values)."""
        if isinstance(v, SView):
            return self.struct_value(v.obj, v.sub, v.tname)
        if isinstance(v, Obj) and v.struct is not None:
            return self.struct_value(v, (), v.struct)
        return v

    def where(self, obj: Obj, path: str = "") -> tuple[Any, Any]:
        """(ast node, unit) of the statement that decides the value at ``path`` below ``obj``: the
        winning effect, or (None, None) when it comes from a default."""
        cur: Any = obj
        parts = path.split(".") if path else []
        for i, name in enumerate(parts):
            if isinstance(cur, Obj) and cur.struct is not None:
                return self._struct_where(cur, tuple(parts[i:]))
            if not isinstance(cur, Obj):
                return None, None
            if name in cur.prims:
                pr = cur.prims[name]
                if i == len(parts) - 1:
                    e = pr.value
                    return (e[0].stmt, e[0].unit) if e is not None else (None, None)
                return None, None
            c = cur.children.get(name)
            if c is None:
                return None, None
            if isinstance(c, Ref):
                if i == len(parts) - 1:
                    return (c.value[0].stmt, c.value[0].unit) if c.value is not None else (None, None)
                try:
                    c = self.deref(c)
                except Unavailable:
                    return None, None
                if c is None:
                    return None, None
            cur = c
        if isinstance(cur, Obj) and cur.struct is not None:
            return self._struct_where(cur, ())
        return None, None

    def _struct_where(self, obj: Obj, sub: tuple) -> tuple[Any, Any]:
        best = None
        for t, _s, d in obj.effects:
            if t.kind != VALUE:
                continue
            rel = t.path[d:]
            n = min(len(rel), len(sub))
            if rel[:n] == sub[:n]:
                best = t
        return (best.stmt, best.unit) if best is not None else (None, None)

    def effects_in_unit(self, obj: Obj, unit) -> list:
        """Value statements of ``unit`` that an owner routed into a struct object (newest last)."""
        return [t.stmt for t, _s, _d in obj.effects if t.kind == VALUE and t.unit is unit]

    # ------------------------------------------------------------------ attributes

    def _attr(self, obj: Obj, name: str) -> Any:
        if obj.struct is not None:
            ftype = _codec_field_type(self.structs, obj.struct, (name,))
            if ftype is None:
                return _MISSING
            return SView(obj, (name,), ftype)
        c = obj.children.get(name)
        if c is not None:
            if isinstance(c, Ref):
                return self.deref(c)
            if c.struct is not None:
                return SView(c, (), c.struct)
            return c
        pr = obj.prims.get(name)
        if pr is not None:
            return self.prim_value(obj, pr)
        return _MISSING

    def _guard(self, key: Any, label: str, compute: Callable[[], Any], anchor: Obj | None, node=None, unit=None) -> Any:
        memo = self._memo.get(key, _MISSING)
        if memo is not _MISSING:
            return memo
        if key in self._failed:
            raise Unavailable(label)
        if key in self._active:
            start = self._stack.index(label) if label in self._stack else 0
            ring = self._stack[start:] + [label]
            raise EvalError(registry.VALUE_CYCLE, "values depend on each other in a cycle: " + " -> ".join(ring), node, unit,
                            help="give one of them a value that does not depend on the others")
        self._active[key] = label
        self._stack.append(label)
        try:
            v = compute()
        except EvalError as err:
            self._failed.add(key)
            if err.code != registry.VALUE_CYCLE and not err.message.startswith(label):
                err.message = f"{label}: {err.message}"
            self._emit(err, anchor)
            raise Unavailable(label) from None
        except Unavailable:
            self._failed.add(key)
            raise
        except NativeError as err:
            self._failed.add(key)
            self._emit(EvalError(registry.EVALUATION_ERROR, f"{label}: {err}", node, unit), anchor)
            raise Unavailable(label) from None
        except OverflowError:  # an integer beyond float range used as a Real (issue 14)
            self._failed.add(key)
            self._emit(EvalError(registry.NON_FINITE_VALUE, f"{label} is too large for a number (beyond 1.8e308)", node, unit), anchor)
            raise Unavailable(label) from None
        except RecursionError:
            self._failed.add(key)
            self._emit(EvalError(registry.VALUE_CYCLE, f"{label}: the values it depends on nest too deeply to evaluate",
                                 node, unit), anchor)
            raise Unavailable(label) from None
        finally:
            self._active.pop(key, None)
            self._stack.pop()
        self._memo[key] = v
        return v

    def _emit(self, err: EvalError, anchor: Obj | None) -> None:
        self.report(err.code, err.message, err.node, err.unit, anchor, err.help)

    def prim_value(self, obj: Obj, pr: Prim) -> Any:
        label = f"{obj.path + '.' if obj.path else ''}{pr.name}"

        def compute() -> Any:
            if pr.value is None:
                if pr.ty is not None and pr.ty.array:
                    return []
                if pr.optional:
                    return None
                what = pr.ty.display() if pr.ty is not None else "value"
                raise EvalError(registry.MISSING_VALUE, f"{label} ({what}) has no value", None, None,
                                help=f"assign it, e.g. '{pr.name}: ...'")
            t, scope, _d = pr.value
            v = self._eval_effect(pr.value, pr.ty)
            return self._coerce(v, pr.ty, t.expr, t.unit, label)

        node = pr.value[0].expr if pr.value is not None else None
        unit = pr.value[0].unit if pr.value is not None else None
        return self._guard(("p", id(obj), pr.name), label, compute, obj, node, unit)

    def deref(self, ref: Ref) -> Any:
        def compute() -> Any:
            if ref.const_model is not None:
                obj = self.b.singleton(ref.const_model)
                if obj is None:
                    raise EvalError(registry.VALUE_CYCLE, f"const model {ref.const_model.qname} refers to itself", None, None)
                return obj
            if ref.value is None:
                if ref.optional:
                    return None
                raise EvalError(registry.EVALUATED_UNBOUND_REFERENCE, f"{ref.path} ({ref.ty.display()}) is not bound to an object", None, None,
                                help=f"give it an existing object, e.g. '{ref.name}: ...'")
            t = ref.value[0]
            v = self._eval_effect(ref.value, ref.ty)
            if isinstance(v, SView) and v.sub == ():
                v = v.obj
            if isinstance(v, TypeObj):  # a model named where an object is needed (issue 16)
                name = getattr(v.sym, "name", v.sym)
                raise EvalError(registry.EVALUATED_UNBOUND_REFERENCE, f"{ref.path} must refer to an object ({ref.ty.display()}), but '{name}' is "
                                f"a model, not an object", t.expr, t.unit,
                                help=f"a model used as a value must be declared 'const {name} is ...', or "
                                f"instantiated ('{ref.name} is {name}')")
            if v is not None and not isinstance(v, Obj):
                raise EvalError(registry.EVALUATED_UNBOUND_REFERENCE, f"{ref.path} must refer to an object ({ref.ty.display()}), "
                                f"not to {_kind(v)}", t.expr, t.unit)
            return v

        node = ref.value[0].expr if ref.value is not None else None
        unit = ref.value[0].unit if ref.value is not None else None
        return self._guard(("r", id(ref)), ref.path, compute, ref.owner, node, unit)

    def struct_value(self, obj: Obj, sub: tuple, tname: str) -> Any:
        label = obj.display + "".join("." + s for s in sub)
        return self._guard(("s", id(obj), sub), label, lambda: self._struct_compute(obj, sub, tname), obj)

    def _struct_compute(self, obj: Obj, sub: tuple, tname: str) -> Any:
        best = -1
        best_rel: tuple = ()
        deeper_after = False
        for i, (t, _s, d) in enumerate(obj.effects):
            if t.kind != VALUE:
                continue
            rel = t.path[d:]
            if len(rel) <= len(sub):
                if sub[: len(rel)] == rel:
                    best, best_rel, deeper_after = i, rel, False
            elif rel[: len(sub)] == sub:
                deeper_after = True
        codec = self.structs.get(tname)
        if best >= 0 and not (codec is not None and deeper_after):
            e = obj.effects[best]
            whole_t = _codec_field_type(self.structs, obj.struct, best_rel) if obj.struct else None
            v = self._eval_effect(e, whole_t or tname)
            v = self.value(v)
            if whole_t is not None and whole_t in self.structs:
                v = self._coerce_struct(v, whole_t, e[0].expr, e[0].unit)
                v = _component(self.structs, v, whole_t, sub[len(best_rel):])
            elif sub[len(best_rel):]:
                raise EvalError(registry.EVALUATION_ERROR, f"{obj.display}: cannot take a field of this value", e[0].expr, e[0].unit)
            if codec is None:
                return self._coerce(v, Ty(tname), e[0].expr, e[0].unit, obj.display)
            return v
        if codec is None:  # a primitive field with no assignment: the parent codec's default
            parent = _codec_field_type(self.structs, obj.struct, sub[:-1]) if sub else None
            pc = self.structs.get(parent) if parent else None
            if pc is not None and sub[-1] in pc.defaults:
                d = pc.defaults[sub[-1]]
                return float(d) if isinstance(d, (int, float, np.floating)) else d
            raise EvalError(registry.MISSING_VALUE, f"{obj.display}{''.join('.' + s for s in sub)} has no value", None, None)
        fields = {f: self.struct_value(obj, sub + (f,), codec.field_types[f]) for f in codec.fields}
        return codec.from_fields(fields)

    def global_value(self, sym: GlobalSym) -> Any:
        def compute() -> Any:
            ty = self.p.resolve_type_expr(sym.stmt.type, sym.unit)
            v = self.eval(sym.stmt.value, None, sym.unit, ty)
            return self._coerce(self.value(v), ty, sym.stmt.value, sym.unit, sym.qname)

        return self._guard(("g", id(sym)), sym.qname, compute, None, sym.stmt.value, sym.unit)

    def _eval_effect(self, e, expected: Any) -> Any:
        t, scope, _d = e
        key = ("e", id(t), id(scope))
        memo = self._memo.get(key, _MISSING)
        if memo is not _MISSING:
            return memo
        v = self.eval(t.expr, scope, t.unit, expected)
        self._memo[key] = v
        return v

    # ------------------------------------------------------------------ coercion

    def _coerce(self, v: Any, ty: Any, node, unit, label: str) -> Any:
        v = self.value(v)
        if ty is None or isinstance(ty, str):
            return v
        prim = ty.primitive if isinstance(ty, Ty) else None
        if ty.array:
            if not isinstance(v, list):
                raise EvalError(registry.EVALUATION_ERROR, f"{label}: expected an array, got {_kind(v)}", node, unit)
            return [self.value(x) if isinstance(x, SView) else x for x in v]
        if prim == "Real":
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise EvalError(registry.EVALUATION_ERROR, f"{label}: expected a Real, got {_kind(v)}", node, unit)
            return float(v)
        if prim == "Int":
            if isinstance(v, (bool, np.bool_)) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise EvalError(registry.EVALUATION_ERROR, f"{label}: expected an Int, got {_kind(v)}", node, unit)
            return int(v) if float(v).is_integer() else float(v)
        if prim == "Bool":
            if not isinstance(v, (bool, np.bool_)):
                raise EvalError(registry.EVALUATION_ERROR, f"{label}: expected a Bool, got {_kind(v)}", node, unit)
            return bool(v)
        if prim == "String":
            if not isinstance(v, str):
                raise EvalError(registry.EVALUATION_ERROR, f"{label}: expected a String, got {_kind(v)}", node, unit)
            return v
        if isinstance(ty, Ty) and ty.model is not None:
            sname = self.b.struct_name(ty.model)
            if sname is not None:
                return self._coerce_struct(v, sname, node, unit)
        return v

    def _coerce_struct(self, v: Any, sname: str, node, unit) -> Any:
        codec = self.structs[sname]
        if isinstance(v, codec.python_type):
            if isinstance(v, np.ndarray):
                want = natives.SHAPES.get(sname)
                if want is not None and v.shape != want:
                    raise EvalError(registry.EVALUATION_ERROR, f"expected a {sname}, got an array of shape {v.shape}", node, unit)
            return v
        raise EvalError(registry.EVALUATION_ERROR, f"expected a {sname}, got {_kind(v)}", node, unit)

    # ------------------------------------------------------------------ expressions

    def eval(self, e: Any, scope: Obj | None, unit, expected: Any = None) -> Any:  # noqa: C901
        if isinstance(e, ast.Number):
            return e.value
        if isinstance(e, ast.Bool):
            return e.value
        if isinstance(e, ast.String):
            if e.kind == "interp":  # an unset variable reads as "" (check reports it: A007)
                return envpath.expand(e.value)[0]
            return e.value
        if isinstance(e, ast.Paren):
            return self.eval(e.inner, scope, unit, expected)
        if isinstance(e, ast.This):
            if scope is None:
                raise EvalError(registry.EVALUATION_ERROR, "'this' is used outside a model", e, unit)
            return scope
        if isinstance(e, ast.Name):
            return self._name(e, scope, unit)
        if isinstance(e, ast.Member):
            base = self.eval(e.obj, scope, unit)
            return self._member(base, e.name.name, e, unit)
        if isinstance(e, ast.Call):
            return self._call(e, scope, unit)
        if isinstance(e, ast.Index):
            base = self.value(self.eval(e.obj, scope, unit))
            idx = self.value(self.eval(e.index, scope, unit))
            if not isinstance(base, list):
                raise EvalError(registry.EVALUATION_ERROR, f"{_kind(base)} cannot be indexed", e, unit)
            if isinstance(idx, bool) or not isinstance(idx, (int, np.integer)):
                raise EvalError(registry.EVALUATION_ERROR, f"an index must be an Int, not {_kind(idx)}", e.index, unit)
            if not -len(base) <= int(idx) < len(base):
                raise EvalError(registry.EVALUATION_ERROR, f"index {int(idx)} is out of range for an array of {len(base)}", e, unit)
            return base[int(idx)]
        if isinstance(e, ast.Unary):
            v = self.value(self.eval(e.operand, scope, unit, expected))
            return self._op("-", [v], e, unit)
        if isinstance(e, ast.Binary):
            left = self.value(self.eval(e.left, scope, unit))
            right = self.value(self.eval(e.right, scope, unit))
            return self._op(e.op, [left, right], e, unit)
        if isinstance(e, ast.Brace):
            return self._brace(e, scope, unit, expected)
        if isinstance(e, ast.Array):
            elem = None
            if isinstance(expected, Ty) and expected.array:
                elem = expected.element()
            return [self.eval(x, scope, unit, elem) for x in e.items]
        raise EvalError(registry.EVALUATION_ERROR, "this expression cannot be evaluated", e, unit)

    def _name(self, e: ast.Name, scope: Obj | None, unit) -> Any:
        name = e.ident.name
        if scope is not None:
            v = self._attr(scope, name)
            if v is not _MISSING:
                return v
        found = self.p.lookup([name], unit) if unit is not None else None
        v = self._global(found)
        if v is not _MISSING:
            return v
        raise EvalError(registry.EVALUATION_ERROR, f"unknown name '{name}'", e, unit)

    def _global(self, found: Any) -> Any:
        """The value of a name model/resolve.py found: a const model is its single instance."""
        meaning = resolve.global_meaning(self.p, found)
        if meaning is None:
            return _MISSING
        if isinstance(found, GlobalSym):
            return self.global_value(found)
        if isinstance(found, ModelSym) and isinstance(meaning, Ty):
            obj = self.b.singleton(found)
            if obj is None:
                raise EvalError(registry.VALUE_CYCLE, f"const model {found.qname} refers to itself", None, None)
            if obj.struct is not None:
                return SView(obj, (), obj.struct)
            return obj
        return meaning

    def _member(self, base: Any, name: str, e: ast.Member, unit) -> Any:
        if isinstance(base, NsRef):
            found = resolve.member_target(self.p, base, name)
            v = self._global(found)
            if v is _MISSING:
                raise EvalError(registry.EVALUATION_ERROR, f"'{name}' is not in namespace {base.ns.dotted}", e, unit)
            return v
        if isinstance(base, TypeObj):
            ref = resolve.member_target(self.p, base, name)
            if isinstance(ref, MethodRef):
                return Bound(None, ref.method, ref.method.qname)
            raise EvalError(registry.EVALUATION_ERROR, f"{getattr(base.sym, 'qname', base.sym)} has no static function '{name}'", e, unit)
        if isinstance(base, SView):
            ftype = _codec_field_type(self.structs, base.tname, (name,))
            if ftype is not None:
                if ftype in self.structs:
                    return SView(base.obj, base.sub + (name,), ftype)
                return self.struct_value(base.obj, base.sub + (name,), ftype)
            return self._method_on_value(self.value(base), base.tname, name, e, unit)
        if isinstance(base, Obj):
            v = self._attr(base, name)
            if v is not _MISSING:
                return v
            meth = self.p.methods_of(Ty(base.model, False, tuple(base.traits))).get(name)
            if meth is not None:
                return Bound(None if meth.static else base, meth, meth.qname)
            if self.b.opaque_import(base) is not None:
                raise Unavailable(f"{base.display}.{name}")  # inside an imported file: said once (A042)
            raise EvalError(registry.EVALUATION_ERROR, f"{base.display} ({self.p.concrete(base.model).qname}) has no attribute '{name}'",
                            e, unit)
        if base is None:
            raise EvalError(registry.EVALUATED_UNBOUND_REFERENCE, f"'.{name}' on an unbound optional reference", e, unit)
        tname = natives.type_of(base)
        if tname in self.structs:
            codec = self.structs[tname]
            if name in codec.fields:
                return codec.to_fields(base)[name]
        if tname is not None:
            return self._method_on_value(base, tname, name, e, unit)
        raise EvalError(registry.EVALUATION_ERROR, f"{_kind(base)} has no member '{name}'", e, unit)

    def _method_on_value(self, value: Any, tname: str, name: str, e, unit) -> Any:
        sym = self.p.lookup_outside_visibility(tname.split("."))
        if isinstance(sym, ModelSym):
            meth = self.p.all_methods(sym).get(name)
            if meth is not None:
                return Bound(None if meth.static else value, meth, meth.qname)
        qn = f"{tname}.{name}"
        if qn in natives.FUNCTIONS:
            return Bound(value, None, qn)
        raise EvalError(registry.EVALUATION_ERROR, f"a {tname} has no member '{name}'", e, unit)

    def _call(self, e: ast.Call, scope: Obj | None, unit) -> Any:
        f = self.eval(e.func, scope, unit)
        if not isinstance(f, Bound):
            raise EvalError(registry.EVALUATION_ERROR, f"{_kind(f)} cannot be called", e.func, unit)
        params: list = []
        if f.meth is not None:
            params = [self.p.resolve_type_ref(prm.type, f.meth.owner.unit) for prm in f.meth.stmt.params]
        args = []
        for i, a in enumerate(e.args):
            exp = params[i] if i < len(params) else None
            args.append(self.value(self.eval(a, scope, unit, exp)))
        fn = natives.FUNCTIONS.get(f.qname)
        if fn is None and f.meth is not None:
            # a method inherited by an anonymous or derived model: try the declaring chain
            fn = natives.FUNCTIONS.get(f"{self.p.concrete(f.meth.owner).qname}.{f.meth.name}")
        if fn is None:
            what = "is not supported by the plxtools evaluator" if f.qname in natives.UNSUPPORTED \
                else "has no native implementation"
            raise EvalError(registry.UNSUPPORTED_FUNCTION, f"{f.qname}() {what}", e, unit)
        try:
            if f.recv is not None:
                return fn(self.value(f.recv), *args)
            return fn(*args)
        except NativeError as err:
            raise EvalError(registry.EVALUATION_ERROR, f"{f.qname}: {err}", e, unit) from None

    def _op(self, op: str, vals: list, e, unit) -> Any:
        types = [natives.type_of(v) for v in vals]
        if any(t is None for t in types):
            bad = next(v for v, t in zip(vals, types) if t is None)
            raise EvalError(registry.EVALUATION_ERROR, f"operator {op} cannot be applied to {_kind(bad)}", e, unit)
        try:
            if len(vals) == 1:
                return natives.apply_operator(op, types[0], vals[0])
            return natives.apply_operator(op, types[0], vals[0], types[1], vals[1])
        except NativeError as err:
            raise EvalError(registry.EVALUATION_ERROR, str(err), e, unit) from None

    def _brace(self, e: ast.Brace, scope, unit, expected: Any) -> Any:
        tname = None
        if isinstance(expected, str):
            tname = expected if expected in self.structs else None
        elif isinstance(expected, Ty):
            if expected.alts:
                for a in expected.alts:
                    sn = self.b.struct_name(a.model) if a.model is not None else None
                    if sn is not None and len(self.structs[sn].fields) == len(e.items):
                        tname = sn
                        break
            elif expected.model is not None and not expected.array:
                tname = self.b.struct_name(expected.model)
        # no guessing from the item count (a 4-item literal is not always a Quat): the expected type decides
        codec = self.structs.get(tname) if tname else None
        if codec is None or tname in ("Math.AffineTransform", "Math.Line"):
            raise EvalError(registry.EVALUATION_ERROR, f"a {{...}} literal of {len(e.items)} values has no known type here", e, unit)
        if len(e.items) != len(codec.fields):
            raise EvalError(registry.EVALUATION_ERROR, f"{tname} takes {len(codec.fields)} values, this literal has {len(e.items)}",
                            e, unit)
        vals = {}
        for f, item in zip(codec.fields, e.items):
            ftype = codec.field_types[f]
            v = self.value(self.eval(item, scope, unit, ftype))
            vals[f] = v
        try:
            return codec.from_fields(vals)
        except NativeError as err:
            raise EvalError(registry.EVALUATION_ERROR, str(err), e, unit) from None


def _kind(v: Any) -> str:
    if v is None:
        return "nothing (an unbound optional reference)"
    if isinstance(v, Obj):
        return f"the object {v.display}"
    if isinstance(v, (SView,)):
        return f"a {v.tname}"
    if isinstance(v, (TypeObj,)):
        return f"the type {getattr(v.sym, 'qname', v.sym)}"
    if isinstance(v, NsRef):
        return f"the namespace {v.ns.dotted}"
    if isinstance(v, Bound):
        return f"the function {v.qname} (call it with ())"
    if isinstance(v, list):
        return "an array"
    t = natives.type_of(v)
    if t:
        return f"a {t}"
    if isinstance(v, Transform):
        return "a Math.AffineTransform"
    return f"a {type(v).__name__}"


def is_finite_vec(v: Any) -> bool:
    try:
        return bool(np.all(np.isfinite(np.asarray(v, dtype=float))))
    except (TypeError, ValueError):
        return False


__all__ = ["Evaluator", "EvalError", "SView", "Unavailable", "is_finite_vec", "math"]
