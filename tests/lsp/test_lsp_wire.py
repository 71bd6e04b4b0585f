"""Raw bytes on stdin: the server skips what it cannot read and still serves a normal session."""

from __future__ import annotations

import json
import queue
import subprocess
import sys
import threading


def _frame(payload: bytes) -> bytes:
    return b"Content-Length: %d\r\n\r\n" % len(payload) + payload


def test_garbage_on_the_wire():
    """Raw bytes: broken JSON, a broken header, then a normal session still works."""
    proc = subprocess.Popen([sys.executable, "-m", "plxtools", "lsp"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    out: queue.Queue = queue.Queue()

    def reader():
        stream = proc.stdout
        while True:
            header = b""
            while not header.endswith(b"\r\n\r\n"):
                ch = stream.read(1)
                if not ch:
                    return
                header += ch
            length = int(header.split(b"Content-Length:")[1].split(b"\r\n")[0])
            out.put(json.loads(stream.read(length)))

    threading.Thread(target=reader, daemon=True).start()
    try:
        proc.stdin.write(_frame(b"{this is not json"))
        proc.stdin.write(_frame(b'{"jsonrpc": "2.0", "id": 7, "method": 12}'))
        proc.stdin.write(_frame(json.dumps({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                                            "params": {"capabilities": {}}}).encode()))
        proc.stdin.flush()
        got = None
        while got is None:
            msg = out.get(timeout=30)
            if msg.get("id") == 1:
                got = msg
        assert "capabilities" in got["result"]
        proc.stdin.write(_frame(json.dumps({"jsonrpc": "2.0", "id": 2, "method": "shutdown"}).encode()))
        proc.stdin.write(_frame(json.dumps({"jsonrpc": "2.0", "method": "exit"}).encode()))
        proc.stdin.flush()
        assert proc.wait(timeout=30) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
