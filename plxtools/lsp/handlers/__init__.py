"""The server's request and notification handlers, one module per group of features. Each module's
`register(server, server_feature)` adds its handlers; every handler converts LSP params to a call
into `plxtools.ide` (or the server's runtime) and the answer back to LSP objects.

To add an editor feature: a plain function in `plxtools/ide/`, then a handler in the module of its
group here (or a new module, added to the groups `register_all` registers).
"""

from __future__ import annotations

import asyncio
import functools
import logging
import os

from pygls.exceptions import JsonRpcException

from plxtools.ide.runtime.settings import CONFIG_SECTION, section  # noqa: F401 - the handlers' names

log = logging.getLogger("plxtools.lsp")

CONFIG_FILES = ("plx.toml", "pyproject.toml", "config.openplx")  # a change may choose another bundle set


def _guard(method: str, fn):
    """Log a request's failure with its traceback; the request gets an error, the server lives on.

    `PLX_LSP_FAULT=<method>` makes that request fail on purpose (for the robustness tests)."""

    @functools.wraps(fn)
    def wrapper(ls, params):
        if os.environ.get("PLX_LSP_FAULT") == method:
            raise RuntimeError(f"injected fault in {method} (PLX_LSP_FAULT)")
        try:
            return fn(ls, params)
        except JsonRpcException:
            raise
        except Exception:
            log.exception("%s failed", method)
            raise
    return wrapper


def register_all(server) -> None:
    """Register every group's handlers on `server` (synchronous handlers guarded by `_guard`)."""
    from plxtools.lsp.handlers import custom, documents, editing, lifecycle, navigation, presentation

    def server_feature(method: str, options=None):
        def register(fn):
            if asyncio.iscoroutinefunction(fn):
                return server.feature(method, options)(fn)
            return server.feature(method, options)(_guard(method, fn))
        return register

    for group in (lifecycle, documents, navigation, editing, custom, presentation):
        group.register(server, server_feature)
