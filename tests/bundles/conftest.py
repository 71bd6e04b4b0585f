"""Shared helpers of the bundle-set tests: the real CLI, an offline pip, fetched versions."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.conftest import run_plx


def offline_env(cache: Path) -> dict:
    """pip pointed at a closed port with no config files: what a machine without network sees."""
    return {"PLX_CACHE_DIR": str(cache), "PIP_CONFIG_FILE": os.devnull, "PIP_INDEX_URL": "http://127.0.0.1:9/simple",
            "PIP_FIND_LINKS": "", "PIP_NO_INDEX": "", "PLX_PIP_TIMEOUT": "2", "OPENPLX_BUNDLE_PATH": ""}


@pytest.fixture(scope="session")
def fetched():
    """fetched(version) -> bundle root, installed into the test cache with the real `plx bundles install`.

    No network and no cached copy is a test failure with pip's reason, never a skip: these tests are
    what proves that old versions work.
    """
    from plxtools.model.versions import cached_root, installed

    def get(version: str) -> Path:
        inst = installed()
        if inst is not None and inst[1] == version:
            return inst[0]
        root = cached_root(version)
        if root is None:
            r = run_plx("bundles", "install", version)
            assert r.returncode == 0, f"cannot fetch openplx-bundles {version}: {r.stderr}"
            root = cached_root(version)
        assert root is not None
        return root

    return get
