"""A long random-edit campaign against a live `plx lsp` over stdio, with interleaved requests.

Random incremental edits (insert, delete, replace; ASCII, unicode beyond the BMP, CRLF, lone CR,
tabs, line separators) on the boxtruck example, tracked by a client-side model of the text (LSP
counts only \\n, \\r\\n and \\r as line breaks; positions in UTF-16). Between edits: hover,
completion, definition, formatting, semantic tokens, document symbols and pull diagnostics.
Checked: the server never dies, every request is answered (a result or a JSON-RPC error, never
silence), every range it returns lies inside the document, and the server's text
(`plx/documentText`) equals the client's after every batch. Prints counts.

Run:  python bench/lsp_fuzz.py --minutes 5 --seed 1
"""

from __future__ import annotations

import argparse
import random
import re
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
from tests.lsp.rawclient import RawServer  # noqa: E402

SMALL = REPO / "examples" / "boxtruck" / "boxtruck.openplx"
PIECES = ["a", " ", "\t", "\n", "\r\n", "\r", ":", ".", "is ", "{", "}", "[", "]", "(", ")", "\"", "#", "é", "😀",
          "\u2028", "\x0c", "Physics3D.", "inertia.mass: 1\n", "    x: 1\n", "Box is Physics3D.Geometries.Box\n",
          "ñ", "\U0001d11e", "0.5", "-", "*", "    ", "fn ", "const "]
_BREAK = re.compile(r"\r\n|\r|\n")


def lines_of(text: str) -> list[tuple[int, int]]:
    """(start, end) offsets of each line's content, LSP's line breaks only."""
    out, start = [], 0
    for m in _BREAK.finditer(text):
        out.append((start, m.start()))
        start = m.end()
    out.append((start, len(text)))
    return out


def utf16_len(s: str) -> int:
    return len(s.encode("utf-16-le")) // 2


def position(text: str, offset: int) -> dict:
    for i, (a, b) in enumerate(lines_of(text)):
        if a <= offset <= b:
            return {"line": i, "character": utf16_len(text[a:offset])}
    raise ValueError(offset)


def snap(text: str, offset: int) -> int:
    """Never split a \\r\\n pair (the client would not either)."""
    if 0 < offset < len(text) and text[offset - 1] == "\r" and text[offset] == "\n":
        return offset - 1
    return offset


def in_range(text: str, rng: dict) -> bool:
    ls = lines_of(text)
    for p in (rng["start"], rng["end"]):
        if not (0 <= p["line"] <= len(ls)):
            return False
        if p["line"] < len(ls):
            a, b = ls[p["line"]]
            if p["character"] > utf16_len(text[a:b]):
                return False
        elif p["character"] != 0:
            return False
    return True


def ranges_in(obj, uri: str):
    """Ranges in a result that refer to the document `uri` (a location in a bundle file does not)."""
    if isinstance(obj, dict):
        if obj.get("uri", uri) != uri or obj.get("targetUri", uri) != uri:
            return
        if set(obj) >= {"start", "end"} and isinstance(obj["start"], dict) and "line" in obj["start"]:
            yield obj
        for k, v in obj.items():
            yield from ranges_in(v, uri)
    elif isinstance(obj, list):
        for v in obj:
            yield from ranges_in(v, uri)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--minutes", type=float, default=1.0)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rnd = random.Random(args.seed)
    text = SMALL.read_text(encoding="utf-8")
    uri = "untitled:fuzz.openplx"  # a buffer in no folder: definitions in it stay in it or go to bundles
    s = RawServer()
    s.initialize({"general": {"positionEncodings": ["utf-16"]}, "textDocument": {"diagnostic": {}}},
                 {"diagnosticMode": "pull"})
    s.open(uri, text)
    version = 1
    counts = {"edits": 0, "requests": 0, "errors": 0, "out of range": 0, "text mismatches": 0, "sync checks": 0,
              "resets": 0}
    problems: list[str] = []
    deadline = time.monotonic() + args.minutes * 60
    methods = ["textDocument/hover", "textDocument/completion", "textDocument/definition",
               "textDocument/formatting", "textDocument/semanticTokens/full", "textDocument/documentSymbol",
               "textDocument/diagnostic", "textDocument/foldingRange", "textDocument/inlayHint"]
    while time.monotonic() < deadline:
        if s.proc.poll() is not None:
            problems.append(f"the server exited with {s.proc.returncode}")
            break
        changes = []
        for _ in range(rnd.randint(1, 4)):
            a = snap(text, rnd.randint(0, len(text)))
            b = snap(text, min(len(text), a + rnd.choice([0, 0, 1, 2, 5, 20])))
            new = "".join(rnd.choice(PIECES) for _ in range(rnd.choice([0, 1, 1, 2, 3])))
            rng = {"start": position(text, a), "end": position(text, b)}
            text = text[:a] + new + text[b:]
            changes.append({"range": rng, "text": new})
            counts["edits"] += 1
        if len(text) > 20_000 or rnd.random() < 0.01:  # back to the example now and then
            text = SMALL.read_text(encoding="utf-8")
            changes.append({"text": text})
            counts["resets"] += 1
        version += 1
        s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                            "contentChanges": changes})
        for _ in range(rnd.randint(0, 3)):
            method = rnd.choice(methods)
            at = position(text, snap(text, rnd.randint(0, len(text))))
            params: dict = {"textDocument": {"uri": uri}}
            if method in ("textDocument/hover", "textDocument/completion", "textDocument/definition"):
                params["position"] = at
            elif method == "textDocument/formatting":
                params["options"] = {"tabSize": 4, "insertSpaces": True}
            elif method == "textDocument/inlayHint":
                params["range"] = {"start": {"line": 0, "character": 0}, "end": position(text, len(text))}
            counts["requests"] += 1
            try:
                reply = s.request(method, params, timeout=60)
            except Exception:  # noqa: BLE001 - no answer in 60 s
                problems.append(f"no answer to {method} at version {version}")
                break
            if "error" in reply:
                counts["errors"] += 1
                if reply["error"].get("code") not in (-32803, -32802):
                    problems.append(f"{method}: {reply['error']}")
                continue
            bad = [r for r in ranges_in(reply.get("result"), uri) if not in_range(text, r)]
            if bad:
                counts["out of range"] += 1
                problems.append(f"{method} at version {version}: range out of the document: {bad[0]}")
        if rnd.random() < 0.3:
            counts["sync checks"] += 1
            got = s.request("plx/documentText", {"uri": uri}, timeout=60).get("result") or {}
            if got.get("text") != text or got.get("version") != version:
                counts["text mismatches"] += 1
                problems.append(f"server text differs at version {version}")
                s.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version + 1},
                                                    "contentChanges": [{"text": text}]})
                version += 1
    alive = s.proc.poll() is None
    if alive:
        s.close()
    print(f"# seed {args.seed}, {args.minutes:g} minutes, server alive at the end: {alive}")
    for k, v in counts.items():
        print(f"{k:>16}: {v:,}")
    print(f"{'problems':>16}: {len(problems)}")
    for p in problems[:20]:
        print("  -", p)
    return 1 if problems or not alive else 0


if __name__ == "__main__":
    sys.exit(main())
