"""`plx lsp` start-up: answer `initialize` before pygls and lsprotocol are imported.

Importing lsprotocol's types (~250 ms) and pygls is most of the time from start to the
`initialize` reply. The reply is a function of the request's params and of this server's code,
so it is kept in plx's cache, keyed by both (less the process id and the workspace folder, which it
does not depend on); an editor sends the same params at every start, so from the second start on,
in any folder, the reply goes out as soon as the request is read. The request is then
handled by the real server as usual (its state is the same as without the cache); its own
reply is dropped, and stored if it differs. A first start, or one with other params, is served
the usual way and fills the cache.

This module imports no pygls or lsprotocol, and stays small: it runs before the server exists.
"""

from __future__ import annotations

import json
import os
import sys
from plxtools.cache import store
from plxtools.cache.stamp import code_stamp, tree_digest
from plxtools.cache.store import new_hash
from plxtools.lsp.transport import FrameReader


def _code_stamp() -> str:
    """What the reply depends on besides the params: this server's code (plxtools' code stamp, by
    content) and its libraries' versions."""
    from importlib.util import find_spec

    parts = [code_stamp()]
    try:
        for name in ("pygls", "lsprotocol"):
            spec = find_spec(name)
            if spec is None or not spec.origin:
                return ""
            parts.append(tree_digest(os.path.dirname(spec.origin)))
    except (ImportError, ValueError):
        return ""
    return "\n".join(parts)


# params the reply does not depend on: the process, and the folder (the reply is the server's
# capabilities: its features and the client's capabilities and initializationOptions, never the
# folder's files; tests/lsp/test_lsp_quickstart.py starts fresh servers on two folders and compares)
NOT_IN_KEY = frozenset({"processId", "rootUri", "rootPath", "workspaceFolders"})


def cache_key(raw: dict) -> str | None:
    params = raw.get("params")
    if not isinstance(params, dict) or os.environ.get("PLX_LSP_FAULT"):
        return None
    stamp = _code_stamp()
    if not stamp:
        return None
    kept = {k: v for k, v in params.items() if k not in NOT_IN_KEY}
    try:
        text = json.dumps(kept, sort_keys=True)
    except (TypeError, ValueError):
        return None

    return new_hash(f"{stamp}\n{text}".encode()).hexdigest()


def cached_result(key: str):
    """The stored reply (an authenticated JSON entry of plx's cache), or None."""

    got = store.get_json("lsp", key)
    return got.get("result") if isinstance(got, dict) else None


def store_result(key: str, result) -> None:
    try:
        store.put_json("lsp", key, {"result": result})
    except (TypeError, ValueError):
        pass


class InitReplay:
    """What the real server must know about the first `initialize`: its id, the cache key, and
    whether its reply has already been sent from the cache."""

    def __init__(self, msg_id, key: str | None, sent_result) -> None:
        self.msg_id = msg_id
        self.key = key
        self.sent_result = sent_result  # None: not sent, the server's reply goes out as usual

    def filter(self, body: str) -> bool:
        """Called with outgoing bodies until the initialize reply went by (then `msg_id` is no
        longer an id); True: drop this body (the cache already answered)."""
        try:
            msg = json.loads(body)
        except ValueError:
            return False
        if not isinstance(msg, dict) or "method" in msg or msg.get("id") != self.msg_id:
            return False
        self.msg_id = _DONE
        result = msg.get("result")
        if "result" not in msg or self.key is None:
            return self.sent_result is not None  # an error reply after a cached answer: the answer stands
        if result != self.sent_result:
            store_result(self.key, result)
        return self.sent_result is not None


_DONE = object()


def start(args) -> int:
    """Read the first message; answer it from the cache when it is a known `initialize`; then run
    the real server with that message as its first input."""

    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    body = FrameReader(stdin).next_body()
    replay = None
    if body is not None:
        try:
            raw = json.loads(body)
        except (ValueError, UnicodeDecodeError):
            raw = None
        if isinstance(raw, dict) and raw.get("method") == "initialize" and raw.get("jsonrpc") == "2.0" \
                and isinstance(raw.get("id"), (int, str)) and not isinstance(raw.get("id"), bool):
            key = cache_key(raw)
            result = cached_result(key) if key else None
            if result is not None:
                data = json.dumps({"jsonrpc": "2.0", "id": raw["id"], "result": result}).encode("utf-8")
                try:
                    stdout.write(b"Content-Length: %d\r\n\r\n" % len(data) + data)
                    stdout.flush()
                except (OSError, ValueError):
                    pass
            replay = InitReplay(raw["id"], key, result)
            if result is not None and not os.environ.get("PLX_LSP_NO_EARLY"):
                # answered: serve completion while the server's modules load (early.py)
                from plxtools.lsp.early import Early

                early = Early(raw, result, stdin, stdout)
                early.run()
                from plxtools.lsp.server import run_server

                return run_server(args, first=body, replay=replay, early=early)
            if not os.environ.get("PLX_LSP_NO_EARLY"):
                from plxtools.lsp import prefetch

                prefetch.start(raw)  # the bundles parsed by a child while pygls loads here
    from plxtools.lsp.server import run_server

    return run_server(args, first=body, replay=replay)
