"""The simulated motion as a CSV table (``plx check --trace``): one row per sample, one column per
quantity, so that a spreadsheet, numpy or pandas can plot or test it without plxtools.

Columns: ``time``; per mate joint ``<mate>.q`` and ``<mate>.qdot`` (OpenPLX's sign: connectors[1]
relative to connectors[0]; cylindrical mates have ``:hinge`` / ``:slide`` suffixes); per body
``<body>.x/.y/.z`` (world position of the body frame), ``.qw/.qx/.qy/.qz`` (world orientation),
``.vx/.vy/.vz`` (centre-of-mass velocity) and ``.wx/.wy/.wz`` (angular velocity), all SI units.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path
from typing import Any
from plxtools.fileio import write_output

BODY_FIELDS = (("position", ("x", "y", "z")), ("quaternion", ("qw", "qx", "qy", "qz")),
               ("velocity", ("vx", "vy", "vz")), ("angular_velocity", ("wx", "wy", "wz")))


def trace_rows(trace: dict[str, Any]) -> tuple[list[str], list[list[float]]]:
    """Header and rows of a recorded trace (see :class:`plxtools.check.mujoco.simulate.Trace`)."""
    header = ["time"]
    columns: list[list[float]] = [trace["time"]]
    for key, q in trace["joints"].items():
        header += [f"{key}.q", f"{key}.qdot"]
        columns += [q, trace["joint_speeds"][key]]
    for path, series in trace["bodies"].items():
        for field, names in BODY_FIELDS:
            values = series[field]
            for k, name in enumerate(names):
                header.append(f"{path}.{name}")
                columns.append([v[k] for v in values])
    rows = [list(r) for r in zip(*columns)]
    return header, rows


def trace_csv(trace: dict[str, Any]) -> str:
    header, rows = trace_rows(trace)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([repr(float(x)) for x in r])
    return buf.getvalue()


class TraceWriteError(OSError):
    pass


def write_trace(trace: dict[str, Any], out: Path) -> None:
    """Write through the one safe writer (plxtools.fileio.write_output): a reader never sees half a
    table, a failed write leaves what was there, a symlink is written through and a device or
    folder is refused."""

    try:
        write_output(out, trace_csv(trace))
    except OSError as exc:
        raise TraceWriteError(exc.strerror or str(exc)) from None
