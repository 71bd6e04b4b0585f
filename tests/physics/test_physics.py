"""`plx check --simulate` against closed-form physics: every case of physics_cases.py, run through
the command line (`--trace`), must land within its stated tolerance and must not report a blow-up,
an energy gain or an implausible speed."""

from __future__ import annotations

import pytest

pytest.importorskip("mujoco")

from physics_cases import CASES, run_model  # noqa: E402

_RUNS: dict = {}


def _run(case):
    key = (case.model, case.duration)
    if key not in _RUNS:
        _RUNS[key] = run_model(case.path, case.duration)
    return _RUNS[key]


@pytest.mark.parametrize("case", [c for c in CASES if c.fast], ids=lambda c: c.name)
def test_matches_closed_form(case):
    run = _run(case)
    assert run.exit_code in (0, 1), run.report["diagnostics"]
    assert not any(d["severity"] == "error" for d in run.report["diagnostics"]), run.report["diagnostics"]
    measured = case.measure(run)
    assert case.error(measured) <= case.tol, (f"{case.name}: {case.what}: expected {case.expected:.6g}, "
                                              f"plx gives {measured:.6g} (tolerance {case.tol:g})")
    assert not (case.must_not_report & run.codes), sorted(case.must_not_report & run.codes)
