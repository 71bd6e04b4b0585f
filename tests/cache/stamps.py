"""The code stamp of a copied plxtools tree, computed with a cache folder of the test's own."""

from __future__ import annotations

import os
from pathlib import Path

from plxtools.cache import folder, stamp


def tree_digest(tree: Path, cache: Path) -> str:
    saved = os.environ.get("PLX_CACHE_DIR")
    os.environ["PLX_CACHE_DIR"] = str(cache)
    folder.forget()
    try:
        return stamp.tree_digest(str(tree))
    finally:
        os.environ["PLX_CACHE_DIR"] = saved
        folder.forget()
