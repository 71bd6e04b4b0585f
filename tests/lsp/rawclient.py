"""A minimal LSP client over raw pipes, for what pytest-lsp cannot send: bad frames, bad params,
requests before `initialize`, cancellations in the same write as their request."""

from __future__ import annotations

import json
import os
import queue
import subprocess
import sys
import threading


def frame(payload: bytes | dict) -> bytes:
    if isinstance(payload, dict):
        payload = json.dumps(payload).encode()
    return b"Content-Length: %d\r\n\r\n" % len(payload) + payload


class RawServer:
    def __init__(self, *args: str, env: dict | None = None):
        self.proc = subprocess.Popen([sys.executable, "-m", "plxtools", "lsp", *args], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     env={**os.environ, **(env or {})})
        self.out: queue.Queue = queue.Queue()
        self.pending: list[dict] = []
        self.server_requests: list[dict] = []
        self.next_id = 1000
        threading.Thread(target=self._read, daemon=True).start()
        self.stderr: list[bytes] = []
        threading.Thread(target=self._read_err, daemon=True).start()

    def _read(self) -> None:
        stream = self.proc.stdout
        while True:
            header = b""
            while not header.endswith(b"\r\n\r\n"):
                ch = stream.read(1)
                if not ch:
                    return
                header += ch
            length = int(header.split(b"Content-Length:")[1].split(b"\r\n")[0])
            self.out.put(json.loads(stream.read(length)))

    def _read_err(self) -> None:
        for line in self.proc.stderr:
            self.stderr.append(line)

    def write(self, data: bytes) -> None:
        self.proc.stdin.write(data)
        self.proc.stdin.flush()

    def send(self, msg: dict) -> None:
        self.write(frame(msg))

    def notify(self, method: str, params) -> None:
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request_bytes(self, method: str, params, msg_id=None) -> tuple[int, bytes]:
        if msg_id is None:
            self.next_id += 1
            msg_id = self.next_id
        msg = {"jsonrpc": "2.0", "id": msg_id, "method": method}
        if params is not ...:
            msg["params"] = params
        return msg_id, frame(msg)

    def request(self, method: str, params=None, timeout: float = 30) -> dict:
        msg_id, data = self.request_bytes(method, params)
        self.write(data)
        return self.response(msg_id, timeout)

    def response(self, msg_id, timeout: float = 30) -> dict:
        for i, m in enumerate(self.pending):
            if m.get("id") == msg_id and "method" not in m:
                return self.pending.pop(i)
        while True:
            m = self.out.get(timeout=timeout)
            if "method" in m and "id" in m:  # a server request: answer it, keep it for the test
                self._answer(m)
                continue
            if m.get("id") == msg_id and "method" not in m:
                return m
            self.pending.append(m)

    def notification(self, method: str, timeout: float = 30, where=lambda p: True) -> dict:
        for i, m in enumerate(self.pending):
            if m.get("method") == method and where(m.get("params")):
                return self.pending.pop(i)["params"]
        while True:
            m = self.out.get(timeout=timeout)
            if "method" in m and "id" in m:
                self._answer(m)
                continue
            if m.get("method") == method and where(m.get("params")):
                return m["params"]
            self.pending.append(m)

    def _answer(self, m: dict) -> None:
        """Answer a request from the server as an editor would, and remember it."""
        if m["method"] == "workspace/configuration":
            result = [{} for _ in (m.get("params") or {}).get("items", [])]
        else:
            result = None
        self.send({"jsonrpc": "2.0", "id": m["id"], "result": result})
        self.server_requests.append(m)

    def notification_request(self, method: str, timeout: float = 30) -> dict:
        """The params of the first request `method` the server sent (answered already)."""
        import time

        deadline = time.monotonic() + timeout
        while True:
            for m in self.server_requests:
                if m["method"] == method:
                    return m.get("params")
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"the server sent no {method} request")
            try:
                m = self.out.get(timeout=left)
            except queue.Empty:
                continue
            if "method" in m and "id" in m:
                self._answer(m)
            else:
                self.pending.append(m)

    def initialize(self, capabilities: dict | None = None, options: dict | None = None) -> dict:
        got = self.request("initialize", {"processId": None, "rootUri": None, "capabilities": capabilities or {},
                                          "initializationOptions": options or {}}, timeout=60)
        self.notify("initialized", {})
        return got

    def open(self, uri: str, text: str, version: int = 1) -> None:
        self.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "openplx",
                                                              "version": version, "text": text}})

    def close(self) -> int:
        try:
            self.request("shutdown", None, timeout=30)
            self.notify("exit", None)
            return self.proc.wait(timeout=30)
        finally:
            if self.proc.poll() is None:
                self.proc.kill()
