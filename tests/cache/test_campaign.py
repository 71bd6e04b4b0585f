"""The differential campaign (tests/cache/campaign.py): a cached run answers what a fresh run on
an empty cache folder answers, after any sequence of what users and tools do to a project.

A short run here; PLX_CACHE_CAMPAIGN=N runs N steps (CI: 3000; 10,000 were run by hand, see docs/caching.md)."""

import os

from tests.cache.campaign import campaign


def test_cached_runs_answer_as_fresh_runs_do(tmp_path):
    steps = int(os.environ.get("PLX_CACHE_CAMPAIGN") or 25)
    done, diffs = campaign(steps, seed=int(os.environ.get("PLX_CACHE_CAMPAIGN_SEED", "27")), top=tmp_path)
    assert not diffs, "\n".join(diffs)
    assert done == steps


def test_the_campaign_finds_a_cache_that_ignores_a_read(tmp_path, monkeypatch):
    """The campaign can fail: with environment variable reads not checked, it finds a stale answer."""
    from plxtools.cache import reads

    real = reads.holds
    monkeypatch.setattr(reads, "holds", lambda d: True if d[0] in ("e", "k") else real(d))
    _done, diffs = campaign(300, seed=2, top=tmp_path)
    assert diffs
