"""Fast pickling for slotted dataclasses: the bundle cache holds ~100k of them.

The default state protocol of a slotted dataclass calls `fields()` for every object it restores,
which made loading the cache several times slower than parsing would be.
"""

from __future__ import annotations

from dataclasses import fields


def fast_pickling(cls) -> None:
    names = tuple(f.name for f in fields(cls))

    def getstate(self):
        return tuple(getattr(self, n) for n in names)

    def setstate(self, state):
        for n, v in zip(names, state):
            object.__setattr__(self, n, v)

    cls.__getstate__ = getstate
    cls.__setstate__ = setstate
