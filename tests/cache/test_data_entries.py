"""Entries a replayed run reads are marshal data: decoded only after their tag checks, an entry of
another form (an older plx's JSON) is a miss, and values JSON would have flattened (subclasses of
str, tuples) come back as JSON gave them before."""

from __future__ import annotations

import os

import pytest

from plxtools.cache import folder, store


@pytest.fixture()
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("PLX_CACHE_DIR", str(tmp_path / "c"))
    monkeypatch.setenv("PLX_CACHE_SECRET_FILE", str(tmp_path / "secret"))
    folder.forget()
    yield tmp_path / "c"
    folder.forget()


class Word(str):
    pass


def test_plain_data_round_trips(cache):
    value = {"deps": [["f", "/a b/ü.openplx", [3, 1, 2, 4, 5, "00ff", 9]], ["e", "HOME", None]], "code": 1}
    assert store.put_data("replays", "k1", value)
    assert store.get_data("replays", "k1") == value


def test_a_str_subclass_is_stored_as_json_would_store_it(cache):
    assert store.put_data("results", "k2", {"diags": [[Word("S011"), ("a", 1)]]})
    got = store.get_data("results", "k2")
    assert got == {"diags": [["S011", ["a", 1]]]} and type(got["diags"][0][0]) is str


def test_an_authentic_entry_of_another_form_is_a_miss(cache):
    assert store.put("replays", "k3", b'{"deps":[],"out":"All checks passed.\\n","err":"","code":0}')
    assert store.get("replays", "k3") is not None  # authentic bytes ...
    assert store.get_data("replays", "k3") is None  # ... but not this form: a miss


def test_a_planted_data_entry_is_a_miss(cache):
    assert store.put_data("replays", "k4", {"code": 0})
    path = store.entry_path("replays", "k4")
    with open(path, "rb") as fh:
        data = fh.read()
    with open(path, "wb") as fh:
        fh.write(bytes(32) + data[32:])
    assert store.get_data("replays", "k4") is None
    assert os.path.exists(path)
