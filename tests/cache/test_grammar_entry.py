"""The LALR fallback's parser is an authenticated entry of the cache (kind `grammars`, issue 27):
a run that finds it answers as a run that builds the grammar, and a planted or foreign entry is a
miss that is never unpickled."""

from __future__ import annotations

import os
import pickle
from pathlib import Path

import lark

from plxtools.cache import folder
from plxtools.syntax import lalr
from tests.cache.inproc import environment
from tests.conftest import run_plx

# three lines the fast path leaves to the grammar (its error messages come from the LALR tables)
SOURCE = ("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody:\n        inertia.mass: 1 +\n"
          "    c is Real: 2 3\n    fn is Real -> Real\n")
GRAMMAR = (Path(lalr.__file__).with_name("openplx.lark")).read_text(encoding="utf-8")


class _Exec:
    def __init__(self, marker: Path) -> None:
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"echo PWNED > {self.marker}",))


def _entries(cache: Path) -> list[Path]:
    return sorted((cache / "plxtools" / "grammars").glob("*"))


def _lint(f: Path, cache: Path):
    r = run_plx("lint", "--output-format", "json", str(f), env={"PLX_CACHE_DIR": str(cache)})
    return r.returncode, r.stdout, r.stderr


def test_a_stored_parser_answers_as_a_built_one_and_a_planted_one_is_not_loaded(tmp_path):
    f = tmp_path / "a.openplx"
    f.write_text(SOURCE)
    cache = tmp_path / "cache"
    built = _lint(f, cache)
    assert built[0] == 1 and built[1].count('"S011"') == 3, built
    assert len(_entries(cache)) == 1
    f.write_text(SOURCE + "\n")  # not a replay: the file is parsed again, by the stored parser
    loaded = _lint(f, cache)
    assert loaded[:2] == built[:2]
    marker = tmp_path / "pwned"
    evil = pickle.dumps(_Exec(marker))
    for p in _entries(cache):
        p.write_bytes(bytes(32) + evil)  # a forged tag
    f.write_text(SOURCE + "\n\n")
    assert _lint(f, cache)[:2] == built[:2]
    assert not marker.exists()
    assert all(p.read_bytes()[32:] != evil for p in _entries(cache))  # the miss rewrote the entry


def test_build_parser_loads_an_authentic_entry_and_rebuilds_on_a_foreign_one(tmp_path, monkeypatch):
    with environment({"PLX_CACHE_DIR": str(tmp_path / "c"), "PLX_CACHE_SECRET_FILE": str(tmp_path / "s1")}):
        folder.forget()
        first = lalr.build_parser(GRAMMAR)
        builds = []
        real_init = lark.Lark.__init__

        def counting_init(self, *a, **kw):
            builds.append(1)
            real_init(self, *a, **kw)

        monkeypatch.setattr(lark.Lark, "__init__", counting_init)
        again = lalr.build_parser(GRAMMAR)
        assert builds == []  # loaded, not built
        tokens_of = [t.name for t in first.terminals]
        assert [t.name for t in again.terminals] == tokens_of
        assert again.options.transformer is not None and again.options.lexer is lalr.PassThrough
        lalr.build_parser(GRAMMAR, use_cache=False)
        assert builds == [1]
    # the same folder, another user's secret (a cache restored from elsewhere): a miss
    with environment({"PLX_CACHE_DIR": str(tmp_path / "c"), "PLX_CACHE_SECRET_FILE": str(tmp_path / "s2")}):
        folder.forget()
        lalr.build_parser(GRAMMAR)
        assert builds == [1, 1]
    folder.forget()
