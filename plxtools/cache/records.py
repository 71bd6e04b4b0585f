"""The record of a bundle set's last load: what it read, and the digest of those reads.

The workspace writes it after loading a set; a lint run whose files are all cached reads it
instead of loading the set (parsing, building the program) only to learn that nothing changed.
Here, not in the model, so that such a run imports no parser.
"""

from __future__ import annotations

from plxtools.cache import reads, store


def set_key(code_stamp: str, set_key_value, official_version) -> str:
    return store.new_hash(repr((code_stamp, set_key_value, official_version)).encode()).hexdigest()


def recorded_digest(key: str) -> str | None:
    """The digest of the last load's reads if every one still holds (they are then noted as this
    run's reads), else None."""
    entry = store.get_data("bundle-sets", key)
    if not isinstance(entry, dict) or not isinstance(entry.get("digest"), str) or not reads.all_hold(entry.get("deps")):
        return None
    reads.note_all(entry["deps"])
    return entry["digest"]
