"""The "migrate this file" source action (kind `source.migrate.plx`): `plx migrate`'s safe rewrites
of a whole buffer, from the OpenPLX version it was written for to the workspace's.

Offered when the file has U001/U002 diagnostics (names of an older version) or its bundle pins an
older version than the workspace uses. The version it was written for is the pin, else the oldest
version those diagnostics point at (U001: the newest older version that has the old name; U002: the
version before the rename). Its bundles must be on this machine (installed or in plx's cache); when
they are not, the action offered instead runs `plx bundles install VERSION`'s fetch (the command
`plx.fetchBundles`, only when the user picks it), after which the migration itself is offered. The rewrite and its safety checks are
`plxtools.migrate.rewrite.migrate_text`, exactly as on the command line; the models of both versions
are separate from the server's own (its open buffers are never touched).

`Migrations.offer` is what an editor asks: the action for a file state, computed once per version of
the text; `plxtools.lsp` only turns it into an LSP code action.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass
from pathlib import Path

from plxtools.rules import registry
from plxtools.migrate.endpoints import plan_for_sets
from plxtools.migrate.rewrite import migrate_text
from plxtools.model.apiindex import version_key
from plxtools.model.versions import cached_root, installed
from plxtools.model.versions import resolve_bundle_set
from plxtools.model.workspace import workspace_for_set

log = logging.getLogger("plxtools.lsp")  # the language server's log, where these run

KIND = "source.migrate.plx"


@dataclass
class Migration:
    title: str
    new_text: str | None  # None: refused (see `reason`)
    reason: str | None = None
    changes: int = 0
    fetch: str | None = None  # refused only because this version's bundles are not on the machine


FETCH_COMMAND = "plx.fetchBundles"  # workspace/executeCommand: `plx bundles install VERSION`'s fetch
EXPLAIN_COMMAND = "plx.explainMigration"  # shows why a migration is refused (clients without disabledSupport)


def fetch_bundles(version: str) -> str:
    """What `plx bundles install VERSION` does (pip, then the cache); returns the folder. Raises
    BundleSetError with the reason when it cannot."""
    from plxtools.model.versions import install

    return str(install(version))


def wanted(only: list[str] | None) -> bool:
    return only is None or any(KIND == k or KIND.startswith(k + ".") for k in only)


def has_version_diagnostics(diagnostics) -> bool:
    """Whether any diagnostic names something of an older OpenPLX version (U001/U002)."""
    return any(d.code in registry.tagged("version") for d in diagnostics)


def _available(version: str) -> bool:
    inst = installed()
    return (inst is not None and inst[1] == version) or cached_root(version) is not None


def source_version(path: str, diagnostics, to_v: str) -> str | None:
    """The version the file was written for, when it is older than `to_v` (else None)."""

    if os.path.isabs(path):
        try:
            from plxtools.model.versions import resolve_bundle_set

            pinned = resolve_bundle_set([Path(path)], [], None).official_version
        except Exception:  # noqa: BLE001 - a setup plx cannot use: fall back to the diagnostics
            pinned = None
        if pinned and version_key(pinned) < version_key(to_v):
            return pinned
    found = [d.older_version for d in diagnostics if d.code in registry.tagged("version") and d.older_version]
    found = [v for v in found if version_key(v) < version_key(to_v)]
    return min(found, key=version_key) if found else None


def migration(host, st) -> Migration | None:
    """The action for a file state, or None when there is nothing to migrate."""
    ws = host.workspace
    bs = getattr(ws, "bundle_set", None)
    to_v = getattr(bs, "official_version", None)
    if not to_v or not st.checked:
        return None
    if not has_version_diagnostics(st.diagnostics) and not os.path.isabs(st.path):
        return None
    from_v = source_version(st.path, st.diagnostics, to_v)
    if from_v is None:
        return None
    title = f"Migrate this file from OpenPLX {from_v} to {to_v}"
    if not _available(from_v):
        from plxtools.model.apiindex import version_key
        from plxtools.model.versions import cached_root

        # the newest version on this machine that is not newer than the one written for
        from plxtools.model.apiindex import versions

        have = [v for v in versions() if version_key(v) <= version_key(from_v) and cached_root(v) is not None]
        if not have:
            return Migration(f"Fetch the bundles of OpenPLX {from_v} to migrate this file to {to_v} "
                             f"(plx bundles install {from_v})", None,
                             f"the bundles of OpenPLX {from_v} are not on this machine", fetch=from_v)
        from_v = have[-1]
        title = f"Migrate this file from OpenPLX {from_v} to {to_v}"

    targets = [Path(st.path)] if os.path.isabs(st.path) else []
    try:
        from_ws = workspace_for_set(resolve_bundle_set(targets, [], from_v))
        to_ws = workspace_for_set(bs)  # the same set as the server's, in a model of its own
    except Exception as exc:  # noqa: BLE001 - a version plx cannot load: the action says why
        return Migration(title, None, f"cannot load OpenPLX {from_v}: {exc}")
    try:  # the server's set may be an AGX installation's: the plan comes from both sets, as in the CLI
        p = plan_for_sets(from_ws.bundle_set, bs)
    except ValueError as exc:
        return Migration(title, None, f"cannot plan the migration: {exc}")
    fm = migrate_text(Path(st.path), st.text, p, host.config(st.path), from_ws, to_ws)
    # the models of the migration must not keep this buffer's symbols
    for w in (from_ws, to_ws):
        if st.path in w.program.units and w.program.units[st.path].bundle is None:
            w.program.remove_unit(st.path)
    if fm.refused:
        return Migration(title, None, fm.refused)
    if not fm.changed:
        return None
    n = fm.edits
    return Migration(f"{title} ({n} change{'' if n == 1 else 's'})", fm.new_text, None, n)


class Migrations:
    """The last action computed (one per document path and text), so that asking for code actions
    again on an unchanged buffer does not load two bundle versions again."""

    def __init__(self) -> None:
        self._last: tuple | None = None  # (path, text, Migration | None)

    def offer(self, host, st, only: list[str] | None) -> Migration | None:
        """The action when `only` asks for it (None: when the file has U001/U002 diagnostics)."""
        if not wanted(only):
            return None
        if only is None and not has_version_diagnostics(st.diagnostics):
            return None
        last = self._last
        if last is not None and last[0] == st.path and last[1] is st.text:
            return last[2]
        try:
            m = migration(host, st)
        except Exception:  # noqa: BLE001 - the other actions are still answered
            log.exception("migrating %s failed", st.path)
            m = None
        self._last = (st.path, st.text, m)
        return m

    def forget(self) -> None:
        """Bundles were fetched: the next request computes the action again."""
        self._last = None
