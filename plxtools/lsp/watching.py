"""What the server learns from the file system: `workspace/didChangeWatchedFiles`.

Diagnostics depend on more than the open buffers: config files (`plx.toml`, `pyproject.toml`,
`config.openplx`: the bundle set, but also `select`/`ignore`), user bundles' `.openplx` files, and
the files imports name (a mesh that is created or deleted turns N006 on or off). The server asks
the editor to watch all of them by dynamic registration when the client supports it:

- `plx-watched-files` (registered once at `initialized`): `**/*.openplx` and the config files;
- `plx-imported-files`: the files the open documents import, exactly, and (when the client
  supports RelativePattern) the `.openplx` files of the user bundles loaded, which may lie outside
  the workspace; registered again whenever that set changes.

On an event the open documents that depend on what changed are checked again from scratch (a
re-used analysis would keep a stale import error), and the editor is told (pushed diagnostics,
or a diagnostic refresh when it pulls).
"""

from __future__ import annotations

import logging
import os

from lsprotocol import types

log = logging.getLogger(__name__)

IMPORTS_ID = "plx-imported-files"


def on_watched_files(ls, params: types.DidChangeWatchedFilesParams,
                     config_files: tuple[str, ...]) -> tuple[bool, bool]:
    """Apply the changes: (open documents must be checked again, the bundle set is a new one);
    the caller reloads the model and re-checks."""
    host = ls.host
    changed = config = new_set = False
    for ev in params.changes:
        path = os.path.normpath(ls.path_of(ev.uri))
        if os.path.basename(path) in config_files:
            config = True
        if path.endswith(".openplx"):
            changed = host.file_changed_on_disk(path) or changed
        else:
            changed = bool(host.import_changed(path)) or changed
    if config:
        new_set = host.config_changed()
        if not new_set:
            host.config_reread()  # the same set, other keys (an ignore added): diagnostics again
        changed = True
    return changed, new_set


def imported_files(ls) -> set[str]:
    out: set[str] = set()
    for path in list(ls.host.docs):
        out |= ls.host.imports_of(path)
    return out


def refresh_import_watchers(ls) -> None:
    """Register the files the open documents import, when that set changed since the last time."""
    if not ls.cap("workspace.did_change_watched_files.dynamic_registration"):
        return
    relative = bool(ls.cap("workspace.did_change_watched_files.relative_pattern_support"))
    files = imported_files(ls)
    bundles = ls.host.user_bundle_roots() if relative else []
    state = getattr(ls, "_watched_imports", None)
    if state is not None and state[0] == (files, bundles):
        return
    count = state[1] + 1 if state is not None else 0
    ls._watched_imports = ((files, bundles), count)
    watchers = []
    for f in sorted(files):
        folder, name = os.path.split(f)
        pattern = types.RelativePattern(base_uri=ls.uri_of(folder), pattern=name) if relative else f
        watchers.append(types.FileSystemWatcher(glob_pattern=pattern))
    for root in bundles:
        watchers.append(types.FileSystemWatcher(
            glob_pattern=types.RelativePattern(base_uri=ls.uri_of(root), pattern="**/*.openplx")))
    try:
        if state is not None:
            ls.client_unregister_capability(types.UnregistrationParams(unregisterations=[
                types.Unregistration(id=f"{IMPORTS_ID}-{state[1]}", method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES)]))
        if watchers:
            ls.client_register_capability(types.RegistrationParams(registrations=[types.Registration(
                id=f"{IMPORTS_ID}-{count}", method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=types.DidChangeWatchedFilesRegistrationOptions(watchers=watchers))]))
    except Exception as exc:  # noqa: BLE001 - without the watchers the editor's own events still arrive
        log.info("could not register watchers of imported files: %s", exc)
