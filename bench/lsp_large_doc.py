"""Large documents in `plx lsp`: responsiveness, cancellation, the size limit and memory.

Drives the real server over stdio (the client of bench/lsp_bench.py) with a generated OpenPLX file
of `--lines` lines (models built from bundle types, as in lsp_bench.py) and the boxtruck example as
a small document open beside it. Measured:

- hover on the small document sent right after the big one is opened (answered while the big one
  is analysed, or before);
- the big document's first diagnostics (or, above the server's size limit, its message);
- a one-character edit of the big document to its diagnostics;
- completion while typing on the big document (`--typing` probes: a half-typed line inserted,
  completion asked at once, the line removed);
- a big document opened and at once replaced by a one-line text: time to the one-line version's
  diagnostics (the big version's analysis is cancelled, not finished);
- the server's resident memory (VmRSS) and peak (VmHWM) after each step: baseline, with the big
  document, after it shrank to one line, after it was closed.

The peer is the same server with the big document never opened (the baseline row), and the
previous session's figures quoted in docs/lsp.md (31.6 s to first diagnostics, 1,020 MB peak,
988 MB kept after close on a 6.7 MB file).

Run:  python bench/lsp_large_doc.py [--lines 200000] [--max-size CHARS] [--no-background] [--tracemalloc]
(`--max-size 0` lifts the server's size limit, to measure an analysis of the whole file;
`--no-background` checks it in the server's own process, to measure what the server keeps;
`--tracemalloc` adds Python-level memory beside RSS.)
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine  # noqa: E402
from lsp_bench import Client, openplx_text  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
SMALL = REPO / "examples" / "boxtruck" / "boxtruck.openplx"


def mb(kb: int) -> str:
    return f"{kb / 1024:.0f}"


def held(client: Client) -> str:
    """RSS / peak, and what plx/memory reports: syntax trees alive (their characters), Python's
    traced allocations when the server runs with PYTHONTRACEMALLOC."""
    rss, hwm = client.memory_kb()
    _, reply = client.request("plx/memory", {})
    got = reply.get("result") or {}
    chars = sum(t["chars"] for t in got.get("trees", []))
    py = got.get("python_kb")
    return (f"{mb(rss)} / {mb(hwm)} MB; trees alive: {len(got.get('trees', []))} ({chars:,} chars)"
            + (f"; Python-level {mb(py)} MB" if py is not None else ""))


def wait_note(client: Client, method: str, pred, timeout: float):
    deadline = time.perf_counter() + timeout
    while True:
        t, msg = client.notes.get(timeout=max(0.01, deadline - time.perf_counter()))
        if msg.get("method") == method and pred(msg["params"]):
            return t, msg["params"]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--lines", type=int, default=200_000)
    ap.add_argument("--max-size", type=int, default=None, help="the server's maxDocumentSize (bytes); 0: no limit")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--no-background", action="store_true", help="check large documents in the server's own "
                    "process (as before background checks), to measure its memory")
    ap.add_argument("--tracemalloc", action="store_true", help="run the server under tracemalloc (slower) to "
                    "report Python-level memory beside RSS")
    ap.add_argument("--typing", type=int, default=10, help="completion-while-typing probes on the big document")
    args = ap.parse_args()

    big_text = openplx_text(args.lines)
    folder = Path(tempfile.mkdtemp(prefix="plx-large-"))
    big = folder / "big.openplx"
    big_uri = big.as_uri()
    small_uri = SMALL.resolve().as_uri()
    small_text = SMALL.read_text(encoding="utf-8")
    options = {"diagnosticMode": "push"}
    if args.max_size is not None:
        options["maxDocumentSize"] = args.max_size
    env_cmd = [sys.executable, "-m", "plxtools", "lsp"]
    if args.no_background:
        os.environ["PLX_LSP_BACKGROUND_SIZE"] = str(1 << 40)
    if args.tracemalloc:
        os.environ["PYTHONTRACEMALLOC"] = "1"
    client = Client(env_cmd, str(folder), {"openplx": options})
    caps = {"general": {"positionEncodings": ["utf-16"]}, "window": {"showMessage": {}},
            "textDocument": {"hover": {"contentFormat": ["markdown"]},
                             "publishDiagnostics": {"versionSupport": True}}}
    client.request("initialize", {"processId": os.getpid(), "rootUri": folder.as_uri(), "capabilities": caps,
                                  "initializationOptions": options})
    client.notify("initialized", {})
    rows: list[tuple[str, str]] = []
    print(f"# {machine()}")
    print(f"# big document: {len(big_text.encode()) / 1e6:.1f} MB, {big_text.count(chr(10)):,} lines")

    since = client.notify("textDocument/didOpen", {"textDocument": {
        "uri": small_uri, "languageId": "openplx", "version": 1, "text": small_text}})
    client.wait_diagnostics(small_uri, since, timeout=120)
    time.sleep(1.0)
    rows.append(("baseline (small document open): RSS / peak", held(client)))
    hover_at = {"line": small_text[:small_text.index("inertia.mass")].count("\n"), "character": 14}

    client.drain()
    since = client.notify("textDocument/didOpen", {"textDocument": {
        "uri": big_uri, "languageId": "openplx", "version": 1, "text": big_text}})
    dt, reply = client.request("textDocument/hover", {"textDocument": {"uri": small_uri}, "position": hover_at})
    rows.append(("hover on the small document right after opening the big one: s", f"{dt:.3f}"
                 + ("" if reply.get("result") else " (no result!)")))
    worst = 0.0
    for _ in range(10):  # more hovers on the small document while the big one is being checked
        time.sleep(0.2)
        dt, _ = client.request("textDocument/hover", {"textDocument": {"uri": small_uri}, "position": hover_at})
        worst = max(worst, dt)
    rows.append(("10 more hovers on the small document, 0.2 s apart, during the big one's check: worst s",
                 f"{worst:.3f}"))
    t, params = wait_first(client, big_uri, since, args.timeout)
    rows.append(("big document: open to first diagnostics (or the size message): s", f"{t - since:.2f} ({params})"))
    rows.append(("with the big document: RSS / peak", held(client)))

    line = big_text.count("\n") // 2
    since = client.notify("textDocument/didChange", {"textDocument": {"uri": big_uri, "version": 2}, "contentChanges": [
        {"range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}}, "text": "#"}]})
    t, params = wait_first(client, big_uri, since, args.timeout, version=2)
    rows.append(("big document: one-character edit to diagnostics: s", f"{t - since:.2f} ({params})"))

    # completion while typing on the big document: a half-typed line inserted, completion asked at
    # once, the line removed again (each probe starts from the text the server analysed last)
    lines = big_text.split("\n")
    lines[line] = "#" + lines[line]
    spots = [n for n, ln in enumerate(lines) if "inertia.mass" in ln]
    times = []
    version = 2
    for k in range(args.typing):
        n = spots[(k * 37) % len(spots)]
        end = len(lines[n])
        version += 1
        client.notify("textDocument/didChange", {"textDocument": {"uri": big_uri, "version": version},
                                                 "contentChanges": [{"range": {
                                                     "start": {"line": n, "character": end},
                                                     "end": {"line": n, "character": end}}, "text": "\n    inertia."}]})
        dt, msg = client.request("textDocument/completion", {
            "textDocument": {"uri": big_uri}, "position": {"line": n + 1, "character": len("    inertia.")}})
        times.append(dt * 1000)
        version += 1
        client.notify("textDocument/didChange", {"textDocument": {"uri": big_uri, "version": version},
                                                 "contentChanges": [{"range": {
                                                     "start": {"line": n, "character": end},
                                                     "end": {"line": n + 1, "character": len("    inertia.")}},
                                                     "text": ""}]})
        time.sleep(0.2)
    if times:
        times.sort()
        rows.append((f"big document: completion while typing, {len(times)} probes: median / p95 ms",
                     f"{times[len(times) // 2]:.0f} / {times[max(0, int(len(times) * 0.95) - 1)]:.0f}"))
    client.drain()

    since = client.notify("textDocument/didChange", {"textDocument": {"uri": big_uri, "version": 3},
                                                     "contentChanges": [{"text": "X is Real: 1\n"}]})
    t, _ = client.wait_diagnostics(big_uri, since, timeout=args.timeout)
    time.sleep(1.0)
    rows.append(("after the big document shrank to one line: RSS / peak", held(client)))
    client.notify("textDocument/didClose", {"textDocument": {"uri": big_uri}})
    client.request("textDocument/hover", {"textDocument": {"uri": small_uri}, "position": hover_at})
    time.sleep(1.0)
    rows.append(("after it was closed: RSS / peak", held(client)))

    # a newer version arrives while the big one is being analysed: the old analysis is dropped
    client.drain()
    other = (folder / "big2.openplx").as_uri()
    t0 = client.notify("textDocument/didOpen", {"textDocument": {
        "uri": other, "languageId": "openplx", "version": 1, "text": big_text}})
    time.sleep(0.3)
    since = client.notify("textDocument/didChange", {"textDocument": {"uri": other, "version": 2},
                                                     "contentChanges": [{"text": "Y is Real: 2\n"}]})
    t, params = wait_first(client, other, since, args.timeout, version=2)
    rows.append(("big document replaced by one line 0.3 s after opening: to the new version's diagnostics: s",
                 f"{t - since:.2f}"))
    client.notify("textDocument/didClose", {"textDocument": {"uri": other}})
    client.request("textDocument/hover", {"textDocument": {"uri": small_uri}, "position": hover_at})
    time.sleep(1.0)
    rows.append(("after that one was closed too: RSS / peak", held(client)))
    _, reply = client.request("plx/stats", {})
    rows.append(("background checks (plx/stats counters)", str((reply.get("result") or {}).get("counters"))))
    client.close()
    del t0

    width = max(len(r[0]) for r in rows)
    for name, value in rows:
        print(f"{name:<{width}}  {value}")
    print("# previous session (docs/lsp.md), 6.7 MB: first diagnostics 31.6 s, RSS 61 -> 1,020 MB, 988 MB after close")


def wait_first(client: Client, uri: str, since: float, timeout: float, version: int | None = None):
    """The first publishDiagnostics (of `version`) or showMessage about `uri` after `since`."""
    name = uri.rsplit("/", 1)[-1]
    deadline = time.perf_counter() + timeout
    while True:
        t, msg = client.notes.get(timeout=max(0.01, deadline - time.perf_counter()))
        if t < since:
            continue
        p = msg.get("params") or {}
        if msg.get("method") == "textDocument/publishDiagnostics" and p.get("uri") == uri and (
                version is None or p.get("version") == version):
            return t, f"{len(p['diagnostics'])} diagnostics"
        if msg.get("method") == "window/showMessage" and name in p.get("message", ""):
            return t, "message: " + p["message"][:90]


if __name__ == "__main__":
    main()
