"""Fast pickling for slotted dataclasses: the bundle cache holds ~100k of them.

The default state protocol of a slotted dataclass calls `fields()` for every object it restores,
which made loading the cache several times slower than parsing would be. Here each class gets a
`__getstate__` / `__setstate__` pair written for its own fields (one tuple, unpacked straight into
the slots), so restoring an object is one short Python call. Loading the official bundles'
program (about 26k such objects and 45k positions) is most of a warm run's start-up.
"""

from __future__ import annotations

from dataclasses import fields


def fast_pickling(*classes) -> None:
    """Give each class its own `__getstate__` / `__setstate__` (one compile for all of them)."""
    src = []
    for k, cls in enumerate(classes):
        names = tuple(f.name for f in fields(cls))
        if not names:
            src.append(f"def get{k}(self):\n    return ()\ndef set{k}(self, state):\n    pass\n")
        elif cls.__dataclass_params__.frozen:  # it refuses attribute assignment: set the slots directly
            sets = "".join(f"    _set(self, {n!r}, state[{i}])\n" for i, n in enumerate(names))
            src.append(f"def get{k}(self):\n    return ({''.join(f'self.{n}, ' for n in names)})\n"
                       f"def set{k}(self, state):\n{sets}")
        else:
            targets = "".join(f"self.{n}, " for n in names)
            src.append(f"def get{k}(self):\n    return ({targets})\ndef set{k}(self, state):\n    {targets}= state\n")
    scope: dict = {"_set": object.__setattr__}
    exec(compile("".join(src), "<plxtools.pickling>", "exec"), scope)
    for k, cls in enumerate(classes):
        cls.__getstate__ = scope[f"get{k}"]
        cls.__setstate__ = scope[f"set{k}"]


def tuple_reducers(*classes) -> dict:
    """A pickler's `dispatch_table` that rebuilds these tuple subclasses without a Python call."""
    import copyreg

    table = dict(copyreg.dispatch_table)
    for c in classes:
        table[c] = lambda obj, c=c: (tuple.__new__, (c, tuple(obj)))
    return table
