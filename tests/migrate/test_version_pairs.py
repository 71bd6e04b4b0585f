"""One test per pair of consecutive official versions whose API changed in a way `plx migrate`
handles (automatically, by the reviewed table or by OpenPLX's declared list): a usage of every such
change is built from the API index (a declaration of each moved or renamed model, a read of each
renamed attribute), the file is migrated, and the result must use only the new names and lint with
no more errors under the new version than the original had under the old one.

Needs both versions' bundles: run with `PLX_ALL_VERSIONS=1` (.ci/run does), which fetches the wheels
once into plx's cache."""

from __future__ import annotations

import json
import os

import pytest

from plxtools.model import apichanges
from tests.bundles.conftest import fetched  # noqa: F401 - the fixture that provides old versions
from tests.conftest import run_plx

HANDLED = ("automatic", "table", "declared")
MODEL_KINDS = ("model-moved", "model-renamed")


def _pairs() -> list[tuple[str, str]]:
    vs = apichanges.versions()
    return [(a, b) for a, b in zip(vs, vs[1:])
            if any(c.handling in HANDLED for c in apichanges.step(a, b))]


def usage(changes) -> tuple[str, list[str], list[str]]:
    """(file text, old names it uses, new names the migration must produce)."""
    lines, olds, news = ["Usage is Physics3D.System:"], [], []
    for i, c in enumerate(changes):
        if c.handling not in HANDLED:
            continue
        if c.kind in MODEL_KINDS:
            lines.append(f"    m{i} is {c.model}")
            olds.append(c.model)
            news.append(c.new)
        elif c.kind == "attr-renamed":
            lines.append(f"    a{i} is {c.model}")
            lines.append(f"    r{i} is {c.model}:")
            lines.append(f"        {c.attr}: a{i}.{c.attr}")
            olds.append(f"{c.attr}: a{i}.{c.attr}")
            news.append(f"{c.new}: a{i}.{c.new}")
    return "\n".join(lines) + "\n", olds, news


def _errors(path, version: str) -> int:
    r = run_plx("lint", "--openplx-version", version, "--output-format", "json", str(path))
    assert r.returncode in (0, 1), r.stderr
    return sum(1 for d in json.loads(r.stdout) if d["severity"] == "error")


def test_there_are_pairs_to_migrate():
    assert len(_pairs()) >= 4  # 0.17.31->32, 0.17.33->0.18.0, 0.18.1->2, 0.18.2->3, 0.18.10->11


@pytest.mark.skipif(not os.environ.get("PLX_ALL_VERSIONS"), reason="slow: set PLX_ALL_VERSIONS=1 (CI does)")
@pytest.mark.parametrize("pair", _pairs(), ids=lambda p: f"{p[0]}-{p[1]}")
def test_every_handled_change_of_a_version_pair_migrates(pair, tmp_path, fetched):  # noqa: F811
    old_v, new_v = pair
    fetched(old_v)
    fetched(new_v)
    text, olds, news = usage(apichanges.step(old_v, new_v))
    assert olds, pair
    f = tmp_path / "usage.openplx"
    f.write_text(text, encoding="utf-8")
    before = _errors(f, old_v)
    r = run_plx("migrate", "--from", old_v, "--to", new_v, str(f))
    assert r.returncode == 0, r.stderr
    out = f.read_text(encoding="utf-8")
    for old, new in zip(olds, news):
        assert new in out, (old, new, out)
        if not new.startswith(old):
            assert f" {old}\n" not in out and f" {old}:" not in out, (old, out)
    assert _errors(f, new_v) <= before, out
