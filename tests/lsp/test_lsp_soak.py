"""Issue 40.3: the server's memory stays flat through a long editing session (PLX_LSP_SOAK=MINUTES,
a stage of .ci/run; bench/lsp_soak.py is the 30-minute run). It grew 69 -> 278 MB in 11 minutes: one
pygls Future per keystroke, and cyclic garbage frozen by each check's gc.freeze()."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

MINUTES = float(os.environ.get("PLX_LSP_SOAK") or 0)
if not MINUTES:
    pytest.skip("the soak runs with PLX_LSP_SOAK=MINUTES (as .ci/run sets)", allow_module_level=True)

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from lsp_soak import REPO, soak  # noqa: E402


def test_memory_is_flat_after_warm_up():
    r = soak(REPO, MINUTES, warmup=0.3, trace=False)
    assert r["requests"] - r["warm_req"] > 500, r["requests"]  # a real session, not an idle server
    growth = (r["end_rss"] - r["warm_rss"]) / r["warm_rss"]
    assert growth < 0.10, (f"RSS {r['warm_rss'] / 1024:.1f} MB after warm-up, {r['end_rss'] / 1024:.1f} MB "
                           f"after {r['requests']} requests and {r['edits']} edits")
