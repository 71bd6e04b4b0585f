"""A day of editing, compressed: does `plx lsp`'s memory stay flat? (issue 40.3)

Drives the real server over stdio (the client of bench/lsp_bench.py) with four open documents (the
boxtruck example, tutorial steps 7 and 10, and a generated 600-line file) and, in a loop until
`--minutes` have passed: types a line character by character and deletes it again (waiting for the
diagnostics now and then, as an editor shows them), and asks for completion, hover, definition,
references, document symbols, semantic tokens, inlay hints, code actions, folding ranges, document
links, signature help and formatting at random places. Memory is the server's resident set (VmRSS)
sampled every few seconds; the warm-up is the first `--warmup` fraction of the run. Printed: RSS
after warm-up and at the end, the growth in % and per 1,000 requests. With `--tracemalloc` the
server starts tracing Python's allocations at the end of the warm-up and the script also prints
what was allocated since and is still alive, and the call sites that hold most of it (`plx/memory`
with `growth`); the RSS figures of such a run include tracemalloc's own tables.

The peer is the same server on a ref before the fix (`--peer-ref REF`, a temporary git worktree),
run alternately with this tree.

Run:  python bench/lsp_soak.py [--minutes 30] [--warmup 0.2] [--tracemalloc] [--peer-ref REF]
(the default is 2 minutes; the issue's figure is the 30-minute run)
"""

from __future__ import annotations

import argparse
import os
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, table  # noqa: E402
from lsp_bench import Client, openplx_text  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
SOURCES = [REPO / "examples" / "boxtruck" / "boxtruck.openplx",
           REPO / "examples" / "tutorial" / "step07-boxtruck" / "boxtruck.openplx",
           REPO / "examples" / "tutorial" / "step10-materials" / "boxtruck.openplx"]
CAPS = {"general": {"positionEncodings": ["utf-16"]},
        "workspace": {"configuration": True},
        "textDocument": {"hover": {"contentFormat": ["markdown"]},
                         "completion": {"completionItem": {"documentationFormat": ["markdown"],
                                                           "resolveSupport": {"properties": ["documentation"]}}},
                         "documentSymbol": {"hierarchicalDocumentSymbolSupport": True},
                         "codeAction": {"codeActionLiteralSupport": {"codeActionKind": {"valueSet": [
                             "quickfix", "source", "source.fixAll"]}}},
                         "publishDiagnostics": {"versionSupport": True}}}
REQUESTS = ["textDocument/completion", "textDocument/hover", "textDocument/definition", "textDocument/references",
            "textDocument/documentSymbol", "textDocument/semanticTokens/full", "textDocument/inlayHint",
            "textDocument/codeAction", "textDocument/foldingRange", "textDocument/documentLink",
            "textDocument/signatureHelp", "textDocument/formatting"]
TYPED = "    extra_mass is Real: inertia.mass * 2"


def params_for(method: str, uri: str, text: str, rng: random.Random) -> dict:
    lines = text.split("\n")
    n = rng.randrange(len(lines))
    col = rng.randrange(len(lines[n]) + 1)
    doc = {"uri": uri}
    whole = {"start": {"line": 0, "character": 0}, "end": {"line": len(lines), "character": 0}}
    if method in ("textDocument/documentSymbol", "textDocument/semanticTokens/full", "textDocument/foldingRange",
                  "textDocument/documentLink"):
        return {"textDocument": doc}
    if method == "textDocument/inlayHint":
        return {"textDocument": doc, "range": whole}
    if method == "textDocument/formatting":
        return {"textDocument": doc, "options": {"tabSize": 4, "insertSpaces": True}}
    if method == "textDocument/codeAction":
        return {"textDocument": doc, "range": {"start": {"line": n, "character": 0}, "end": {"line": n, "character": 0}},
                "context": {"diagnostics": []}}
    out = {"textDocument": doc, "position": {"line": n, "character": col}}
    if method == "textDocument/references":
        out["context"] = {"includeDeclaration": True}
    return out


def soak(cwd: Path, minutes: float, warmup: float, trace: bool, seed: int = 3) -> dict:
    rng = random.Random(seed)
    env_before = dict(os.environ)
    with tempfile.TemporaryDirectory(prefix="plx-soak-") as tmp:
        folder = Path(tmp)
        docs = {}
        for i, src in enumerate(SOURCES):
            p = folder / f"doc{i}.openplx"
            p.write_text(src.read_text(encoding="utf-8"), encoding="utf-8")
            docs[p.resolve().as_uri()] = p.read_text(encoding="utf-8")
        gen = folder / "generated.openplx"
        gen.write_text(openplx_text(600), encoding="utf-8")
        docs[gen.resolve().as_uri()] = gen.read_text(encoding="utf-8")
        try:
            client = Client([sys.executable, "-m", "plxtools", "lsp"], str(cwd), {"openplx": {}})
        finally:
            os.environ.clear()
            os.environ.update(env_before)
        client.request("initialize", {"processId": os.getpid(), "rootUri": folder.as_uri(), "capabilities": CAPS,
                                      "initializationOptions": {"diagnosticMode": "push"}}, timeout=120)
        client.notify("initialized", {})
        versions = {}
        for uri, text in docs.items():
            versions[uri] = 1
            since = client.notify("textDocument/didOpen", {"textDocument": {"uri": uri, "languageId": "openplx",
                                                                            "version": 1, "text": text}})
            client.wait_diagnostics(uri, since, timeout=120)
        t_start = time.monotonic()
        t_end = t_start + minutes * 60
        t_warm = t_start + warmup * minutes * 60
        samples = []  # (seconds, requests so far, RSS KB)
        requests = edits = 0
        warm_rss = warm_req = None
        warm_py = None
        growth = None
        next_sample = t_start
        while time.monotonic() < t_end:
            uri = rng.choice(list(docs))
            text = docs[uri]
            lines = text.split("\n")
            # type a line into a model, a character at a time, asking for completion as an editor does
            anchor = next((k for k, ln in enumerate(lines) if "inertia.mass" in ln), 1)
            typed = ""
            for ch in TYPED[:rng.randrange(8, len(TYPED) + 1)]:
                versions[uri] += 1
                pos = {"line": anchor + 1, "character": len(typed)}
                change = {"range": {"start": pos, "end": pos}, "text": ("\n" if not typed else "") + ch}
                if not typed:
                    change["range"] = {"start": {"line": anchor, "character": len(lines[anchor])},
                                       "end": {"line": anchor, "character": len(lines[anchor])}}
                client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": versions[uri]},
                                                         "contentChanges": [change]})
                typed += ch
                edits += 1
                if ch in ". :":
                    client.request("textDocument/completion", {"textDocument": {"uri": uri},
                                                               "position": {"line": anchor + 1, "character": len(typed)}})
                    requests += 1
            since = client.notify("textDocument/didChange", {
                "textDocument": {"uri": uri, "version": versions[uri] + 1},
                "contentChanges": [{"range": {"start": {"line": anchor, "character": len(lines[anchor])},
                                              "end": {"line": anchor + 1, "character": len(typed)}}, "text": ""}]})
            versions[uri] += 1
            edits += 1
            client.wait_diagnostics(uri, since, version=versions[uri], timeout=120)
            for _ in range(12):
                method = rng.choice(REQUESTS)
                client.request(method, params_for(method, uri, text, rng), timeout=120)
                requests += 1
            client.drain()
            now = time.monotonic()
            if now >= next_sample:
                samples.append((now - t_start, requests, client.memory_kb()[0]))
                next_sample = now + 5
            if warm_rss is None and now >= t_warm:
                warm_rss, warm_req = client.memory_kb()[0], requests
                if trace:
                    _dt, msg = client.request("plx/memory", {"growth": "start"}, timeout=300)
                    warm_py = (msg.get("result") or {}).get("python_kb")
        end_rss = client.memory_kb()[0]
        end_py = None
        if trace:
            _dt, msg = client.request("plx/memory", {"growth": "diff"}, timeout=300)
            got = msg.get("result") or {}
            end_py, growth = got.get("python_kb"), got.get("growth")
        client.close()
    return {"samples": samples, "requests": requests, "edits": edits, "warm_rss": warm_rss, "warm_req": warm_req,
            "end_rss": end_rss, "warm_py": warm_py, "end_py": end_py, "growth": growth}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--minutes", type=float, default=2.0)
    ap.add_argument("--warmup", type=float, default=0.2, help="fraction of the run before the baseline (default 0.2)")
    ap.add_argument("--tracemalloc", action="store_true", help="trace Python's allocations (slower)")
    ap.add_argument("--peer-ref", metavar="REF", help="also run this git ref, after this tree")
    args = ap.parse_args()
    servers = [("this tree", REPO)]
    tmp_wt = None
    if args.peer_ref:
        tmp_wt = Path(tempfile.mkdtemp(prefix="plx-peer-")) / "wt"
        subprocess.run(["git", "-C", str(REPO), "worktree", "add", "--detach", str(tmp_wt), args.peer_ref],
                       check=True, capture_output=True)
        servers.append((args.peer_ref, tmp_wt))
    rows = []
    try:
        for name, cwd in servers:
            subprocess.run([sys.executable, "-m", "compileall", "-q", str(cwd / "plxtools")], check=False)
            r = soak(cwd, args.minutes, args.warmup, args.tracemalloc)
            grow = (r["end_rss"] - r["warm_rss"]) / r["warm_rss"] * 100
            per_k = (r["end_rss"] - r["warm_rss"]) / max(1, r["requests"] - r["warm_req"]) * 1000
            py = f"{r['end_py'] / 1024:.1f}" if r["end_py"] is not None else "-"
            rows.append((name, f"{r['requests']:,} / {r['edits']:,}", f"{r['samples'][0][2] / 1024:.0f}",
                         f"{r['warm_rss'] / 1024:.1f}", f"{r['end_rss'] / 1024:.1f}", f"{grow:+.1f} %",
                         f"{per_k:.0f} KB", py))
            if r["growth"]:
                print(f"{name}: allocations that grew most after warm-up (KB, count, innermost frames first):")
                for g in r["growth"][:12]:
                    print(f"  {g['kb']:9.1f} KB {g['count']:+7d}  {' <- '.join(g['where'])}")
    finally:
        if tmp_wt is not None:
            subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force", str(tmp_wt)], check=False)
    print(f"plx lsp soak: {args.minutes:g} minutes of typing and requests over 4 documents ({machine()}); "
          f"baseline after {args.warmup:.0%} of the run; RSS in MB")
    print(table(rows, ("server", "requests / edits", "RSS at start", "after warm-up", "at end", "growth",
                       "per 1,000 requests", "alive of what was allocated after warm-up (MB)")))


if __name__ == "__main__":
    main()
