"""A non-optional `reference` attribute of an instantiated object is never given an object.

## Why it matters

A reference never creates its own object; unbound, it points at nothing.
"""

# The references are the model's facts (model/completeness.py `Unset`, with `reference` set), the
# same computation as M007's; check's evaluator leaves them to this finding (M008 owns A005).

from __future__ import annotations

from plxtools.rules.semantic.missing_assignment import instances


WHOLE_FILE = True  # reads the whole file's facts: the server judges it on the whole file (rules/incremental.py)


def check(facts, report) -> None:
    for u in facts.unset:
        if u.reference:
            report(f"reference '{u.path}' ({u.type}){instances(u)} is never bound", u.anchor,
                   help=f"give it an existing object: '{u.name}: ...' (declared in {u.owner})")
