"""How a mapped signal acts on a compiled MuJoCo model: its read and write functions (a Binding),
or why it cannot (Unbindable).

Apart from signals.py so that the modules binding quantities of their own (body_loads.py,
connector_signals.py), which signals.py dispatches to, do not import it back.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable


@dataclass(slots=True)
class Binding:
    info: Any  # the signals.SignalInfo it acts for
    read: Callable[[Any, Any], Any] | None = None  # (model, data) -> value
    write: Callable[[Any, Any, Any], None] | None = None  # (model, data, value)
    refuse: Callable[[Any], str | None] | None = None  # a value this binding cannot take: why


class SignalValueError(ValueError):
    """A value of the wrong kind for a signal (the message says which kind it takes)."""


class Unbindable(Exception):
    """A mapped signal that cannot act on this compiled model (the message says why)."""


def rpy_of_mat(xmat: Any) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of a row-major 3x3 rotation, ``R = Rz(yaw) Ry(pitch) Rx(roll)``."""
    r = [float(x) for x in xmat]
    r00, r10, r20, r21, r22 = r[0], r[3], r[6], r[7], r[8]
    pitch = math.asin(max(-1.0, min(1.0, -r20)))
    return (math.atan2(r21, r22), pitch, math.atan2(r10, r00))
