"""Lifecycle and settings: `initialize` (root, settings, push or pull diagnostics),
`initialized` (configuration, file watchers, the bundles loaded in a thread), and
`workspace/didChangeConfiguration`."""

from __future__ import annotations

import asyncio
import logging
from typing import TYPE_CHECKING

from lsprotocol import types

from plxtools.ide.runtime.collector import freeze_loaded
from plxtools.lsp import prefetch
from plxtools.lsp.handlers import CONFIG_FILES, CONFIG_SECTION, section

if TYPE_CHECKING:
    from plxtools.lsp.server import PlxServer

log = logging.getLogger("plxtools.lsp")

CONFIGURATION_WAIT = 10  # seconds the bundles' load waits for the editor's settings


def register(server, server_feature) -> None:
    @server_feature(types.INITIALIZE)
    def initialize(ls: PlxServer, params: types.InitializeParams) -> None:
        ls.init_options = section(params.initialization_options) or {}
        root = None
        if params.root_uri:
            root = ls.path_of(params.root_uri)
        elif params.workspace_folders:
            root = ls.path_of(params.workspace_folders[0].uri)
        elif params.root_path:
            root = params.root_path
        ls.host.root = root
        ls.apply_settings(None)
        if ls.loop is not None:  # until `initialized` has loaded the bundles, requests do not wait
            ls.warming = ls.loop.create_future()
        # pull diagnostics when the client can pull them (as ruff's server does), push otherwise;
        # never both, or editors show every diagnostic twice
        ls.pull_diagnostics = ls.cap("text_document.diagnostic") is not None and ls.diagnostic_mode != "push"
        if not ls.pull_diagnostics:
            ls.protocol.fm.features.pop(types.TEXT_DOCUMENT_DIAGNOSTIC, None)

    @server_feature(types.INITIALIZED)
    async def initialized(ls: PlxServer, params: types.InitializedParams) -> None:
        if ls.cap("workspace.configuration"):
            await _pull_configuration(ls)
        if ls.cap("workspace.did_change_watched_files.dynamic_registration"):
            # not awaited: nothing below needs the editor's answer, and an editor busy elsewhere may
            # answer late or never (Emacs in the middle of a go-to-definition did not, and completion,
            # waiting for the bundles behind it, timed out)
            ls.registering = asyncio.ensure_future(_watch_files(ls))
        # load the bundles now, not on the first keystroke, and in a thread: a request that arrives
        # meanwhile (Helix asks for completion right after opening a file) is answered at once
        loop = asyncio.get_running_loop()
        if ls.warming is None:
            ls.warming = loop.create_future()
        try:
            await loop.run_in_executor(None, _load, ls)
        except asyncio.CancelledError:
            return  # the editor quit while the bundles were loading
        finally:
            done, ls.warming = ls.warming, None
            if not done.done():
                done.set_result(None)
        freeze_loaded()
        ls.notify_messages()
        ls.checks.wake()

    def _load(ls: PlxServer):
        prefetch.wait()  # a cold start's forked loader (lsp/prefetch.py) fills plx's cache first
        return ls.host.workspace

    async def _watch_files(ls: PlxServer) -> None:
        """Ask the editor to report model and config files changed on disk (a changed config may
        choose another bundle set)."""
        globs = ["**/*.openplx", *(f"**/{name}" for name in CONFIG_FILES if not name.endswith(".openplx"))]
        try:
            await ls.client_register_capability_async(types.RegistrationParams(registrations=[types.Registration(
                id="plx-watched-files", method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=types.DidChangeWatchedFilesRegistrationOptions(
                    watchers=[types.FileSystemWatcher(glob_pattern=g) for g in globs]))]))
        except Exception as exc:  # noqa: BLE001 - without watchers the editor's own events still arrive
            log.info("could not register file watchers: %s", exc)

    async def _pull_configuration(ls: PlxServer) -> None:
        try:
            got = await asyncio.wait_for(ls.workspace_configuration_async(types.ConfigurationParams(
                items=[types.ConfigurationItem(section=CONFIG_SECTION)])), CONFIGURATION_WAIT)
        except asyncio.TimeoutError:
            log.warning("workspace/configuration: no answer in %d s; the settings so far stay", CONFIGURATION_WAIT)
            return
        except Exception as exc:  # noqa: BLE001 - a client that cannot answer keeps the defaults
            log.info("workspace/configuration failed: %s", exc)
            return
        if got:
            ls.apply_settings(section(got[0]) if isinstance(got[0], dict) else None)

    @server_feature(types.WORKSPACE_DID_CHANGE_CONFIGURATION)
    async def did_change_configuration(ls: PlxServer, params: types.DidChangeConfigurationParams) -> None:
        if ls.warming is not None and ls.warming.get_loop().is_running():
            await asyncio.shield(ls.warming)  # new settings after the bundles' loader, never during it
        if ls.cap("workspace.configuration"):
            await _pull_configuration(ls)
        else:
            ls.apply_settings(section(params.settings) if isinstance(params.settings, dict) else None)
        ls.recheck_all()
