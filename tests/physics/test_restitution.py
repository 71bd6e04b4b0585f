"""Normal restitution: an impact at normal speed v leaves at e v, for every e, impact speed, mass
ratio and step (the rebound speed ratio within 3 % of e), or the A137 note warns, naming the impact
speed below which it may not be.  The whole grid is bench/restitution.py (docs/physics.md)."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("mujoco")

from impacts import drop, head_on, within  # noqa: E402



def _warned_below(notes: list) -> float:
    """The impact speed an A137 warning names (0 when the note is an info)."""
    for d in notes:
        m = re.search(r"slower than ([0-9.e+-]+) m/s", d.message)
        if d.severity == "warning" and m:
            return float(m.group(1))
    return 0.0


@pytest.mark.parametrize("e", [0.0, 0.2, 0.5, 0.8, 1.0])
@pytest.mark.parametrize("height", [0.05, 1.0, 5.0])
def test_drop_rebounds_at_e_or_warns(e, height):
    got = drop(e, height, 0.002)
    assert bool(got["notes"]) == (e > 0), "every restitution but a plastic one is noted (A137)"
    assert all("with that restitution" not in n.message for n in got["notes"])
    if not within(e, got["ratio"]):
        assert got["speed"] < _warned_below(got["notes"]), (e, height, got["ratio"])


@pytest.mark.parametrize("e", [0.0, 0.2, 0.5, 1.0])
@pytest.mark.parametrize("mass_ratio", [1.0, 10.0])
@pytest.mark.parametrize("timestep", [0.0005, 0.002, 0.005])
def test_head_on_impact_leaves_at_e(e, mass_ratio, timestep):
    # no gravity along the normal: the impact law itself, exact to 0.1 %
    assert head_on(e, mass_ratio, timestep)["ratio"] == pytest.approx(e, abs=1e-3)


def test_a_4_4_m_per_s_impact_sinks_at_most_one_step_deep():
    got = drop(0.5, 1.0, 0.002)  # 4.43 m/s
    assert 0.0 < got["depth"] <= got["speed"] * 0.002
    assert got["ratio"] == pytest.approx(0.5, rel=0.03)


def test_a_slow_impact_with_a_low_e_is_a_warning():
    got = drop(0.2, 0.2, 0.002)  # 1.98 m/s: resolved 0-4 mm deep, about 8 % short
    assert _warned_below(got["notes"]) > got["speed"]
    assert "3 % short" in got["notes"][0].message
