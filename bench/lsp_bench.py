"""Language-server latency and memory: `plx lsp` side by side with Red Hat's yaml-language-server.

Both servers are driven over stdio by the same small JSON-RPC client (below), on a generated file
of about 2,000 lines: OpenPLX models built from bundle types for plx, and a YAML document of the
same shape validated against a JSON schema (modeline) for yaml-language-server.

Measured per server:
- diagnostics: time from sending `didChange` to receiving the `publishDiagnostics` for that edit
  (the edits alternately add and fix a misspelt attribute in a random model), raw and minus the
  server's debounce (plx: none, it checks as soon as no message waits; yaml-language-server: its fixed 200 ms);
- completion while typing: a half-typed line is inserted and completion requested at once, before
  the debounced check has run (what an editor does on `.`);
- completion, hover and definition round trips on a checked file (median and p95 over >= 30
  requests each);
- memory: the server process's resident set (VmRSS) and peak (VmHWM) from /proc.

Run:  python bench/lsp_bench.py [--requests 40] [--edits 40] [--lines 2000]
The peer is installed with `npm install` in bench/lsp_yaml (node_modules is git-ignored); without
it only plx is measured.
"""

from __future__ import annotations

import argparse
import json
import os
import queue
import random
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _common import machine, table  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
YAML_LS = REPO / "bench" / "lsp_yaml" / "node_modules" / "yaml-language-server" / "bin" / "yaml-language-server"
PLX_DEBOUNCE_MS = 0  # no fixed delay any more: a check runs as soon as no message is waiting
YAML_DEBOUNCE_MS = 200  # yaml-language-server's validationDelayMs (fixed)


# ------------------------------------------------------------------ a minimal LSP client


class Client:
    def __init__(self, cmd: list[str], cwd: str, config: dict):
        self.proc = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)
        self.config = config
        self.next_id = 0
        self.pending: dict[int, queue.Queue] = {}
        self.notes: queue.Queue = queue.Queue()
        self.lock = threading.Lock()
        threading.Thread(target=self._read, daemon=True).start()

    def _send(self, msg: dict) -> None:
        data = json.dumps(msg).encode()
        with self.lock:
            self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(data) + data)
            self.proc.stdin.flush()

    def _read(self) -> None:
        out = self.proc.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                if line in (b"\r\n", b"\n"):
                    break
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            msg = json.loads(out.read(length))
            if "id" in msg and "method" in msg:  # a request from the server
                self._answer(msg)
            elif "id" in msg:
                q = self.pending.pop(msg["id"], None)
                if q is not None:
                    q.put((time.perf_counter(), msg))
            else:
                self.notes.put((time.perf_counter(), msg))

    def _answer(self, msg: dict) -> None:
        result = None
        if msg["method"] == "workspace/configuration":
            result = [self.config.get(item.get("section") or "", None) for item in msg["params"]["items"]]
        self._send({"jsonrpc": "2.0", "id": msg["id"], "result": result})

    def request(self, method: str, params: dict, timeout: float = 60) -> tuple[float, dict]:
        self.next_id += 1
        q: queue.Queue = queue.Queue()
        self.pending[self.next_id] = q
        t0 = time.perf_counter()
        self._send({"jsonrpc": "2.0", "id": self.next_id, "method": method, "params": params})
        t1, msg = q.get(timeout=timeout)
        return t1 - t0, msg

    def notify(self, method: str, params: dict) -> float:
        t0 = time.perf_counter()
        self._send({"jsonrpc": "2.0", "method": method, "params": params})
        return t0

    def wait_diagnostics(self, uri: str, since: float, timeout: float = 60, version: int | None = None
                         ) -> tuple[float, dict]:
        """The first diagnostics for `uri` after `since`; of `version` or newer when the server says
        which version they are for (a late publication for an older version does not count)."""
        deadline = time.perf_counter() + timeout
        while True:
            t, msg = self.notes.get(timeout=max(0.01, deadline - time.perf_counter()))
            if msg.get("method") == "textDocument/publishDiagnostics" and msg["params"]["uri"] == uri and t >= since:
                got = msg["params"].get("version")
                if version is not None and isinstance(got, int) and got < version:
                    continue
                return t, msg["params"]

    def drain(self) -> None:
        while True:
            try:
                self.notes.get_nowait()
            except queue.Empty:
                return

    def memory_kb(self) -> tuple[int, int]:
        rss = hwm = 0
        try:
            for line in Path(f"/proc/{self.proc.pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    rss = int(line.split()[1])
                elif line.startswith("VmHWM:"):
                    hwm = int(line.split()[1])
        except OSError:
            pass
        return rss, hwm

    def close(self) -> None:
        try:
            self.request("shutdown", None, timeout=10)
            self.notify("exit", None)
            self.proc.wait(timeout=10)
        except Exception:  # noqa: BLE001
            self.proc.kill()


# ------------------------------------------------------------------ the two corpora


def openplx_text(lines: int) -> str:
    out = ["# generated for bench/lsp_bench.py: many models built from bundle types", ""]
    i = 0
    while len(out) < lines - 25:
        out += f"""const Mat{i} is Physics.Geometries.Material:
    unique_name: "mat_{i}"
    density: {1000 + i}

Wheel{i} is Physics3D.Bodies.RigidBody:
    inertia.mass: {10 + i}
    geometry is Physics3D.Geometries.Cylinder:
        radius: 0.26
        height: 0.165
        material: Mat{i}
    connector is Physics3D.Interactions.MateConnector:
        main_axis: {{0, -1, 0}}
        normal: {{1, 0, 0}}

Chassis{i} is Physics3D.Bodies.RigidBody:
    inertia.mass: 1000
    geometry is Physics3D.Geometries.Box:
        size:
            x: 3.3
            y: 1.7
            z: 1.44
    hub_offset is Math.Vec3:
        x: geometry.size.x * 0.31
        y: geometry.size.y * 0.44
        z: geometry.size.z * 0.48
    left_hub is Physics3D.Interactions.MateConnector:
        position: {{-hub_offset.x, -hub_offset.y, -hub_offset.z}}
        main_axis: {{0, -1, 0}}
        normal: {{1, 0, 0}}

Truck{i} is Physics3D.System:
    chassis is Chassis{i}:
        kinematics.local_transform.position.z: 1.1
    left_wheel is Wheel{i}
    hinge is Physics3D.Interactions.Hinge:
        connectors: [chassis.left_hub, left_wheel.connector]
    motor is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: hinge.connectors
        target_speed: 1

""".splitlines()
        i += 1
    out += ["Scene is Physics3D.System:"] + [f"    truck_{k} is Truck{k}" for k in range(i)]
    return "\n".join(out) + "\n"


def yaml_text(lines: int) -> str:
    out = ["# yaml-language-server: $schema=./bench-schema.json", "models:"]
    i = 0
    while len(out) < lines - 5:
        out += f"""  mat_{i}:
    kind: Material
    unique_name: mat_{i}
    density: {1000 + i}
  wheel_{i}:
    kind: RigidBody
    inertia:
      mass: {10 + i}
    geometry:
      type: Cylinder
      radius: 0.26
      height: 0.165
      material: mat_{i}
    connector:
      main_axis: [0, -1, 0]
      normal: [1, 0, 0]
  chassis_{i}:
    kind: RigidBody
    inertia:
      mass: 1000
    geometry:
      type: Box
      size: {{x: 3.3, y: 1.7, z: 1.44}}
    hub_offset: {{x: 1.0, y: 0.7, z: 0.6}}
    left_hub:
      position: [-1.0, -0.7, -0.6]
      main_axis: [0, -1, 0]
      normal: [1, 0, 0]
  truck_{i}:
    kind: System
    chassis: chassis_{i}
    left_wheel: wheel_{i}
    hinge:
      connectors: [chassis_{i}.left_hub, wheel_{i}.connector]
    motor:
      connectors: [chassis_{i}.left_hub, wheel_{i}.connector]
      target_speed: 1
""".splitlines()
        i += 1
    return "\n".join(out) + "\n"


def yaml_schema() -> dict:
    vec = {"type": "array", "items": {"type": "number"}, "minItems": 3, "maxItems": 3,
           "description": "A 3D vector [x, y, z]."}
    xyz = {"type": "object", "properties": {k: {"type": "number"} for k in "xyz"}, "additionalProperties": False}
    model = {
        "type": "object",
        "additionalProperties": False,
        "properties": {
            "kind": {"enum": ["Material", "RigidBody", "System"], "description": "What the model is."},
            "unique_name": {"type": "string", "description": "A name unique among materials."},
            "density": {"type": "number", "description": "Mass per volume, kg/m^3."},
            "inertia": {"type": "object", "additionalProperties": False, "description": "Mass properties.",
                        "properties": {"mass": {"type": "number", "default": 0.0, "description": "Mass in kg."}}},
            "geometry": {"type": "object", "additionalProperties": False, "description": "Contact geometry.",
                         "properties": {"type": {"enum": ["Box", "Cylinder", "Sphere", "Capsule"]},
                                        "radius": {"type": "number"}, "height": {"type": "number"},
                                        "size": xyz, "material": {"type": "string"}}},
            "connector": {"type": "object", "properties": {"main_axis": vec, "normal": vec}},
            "hub_offset": xyz,
            "left_hub": {"type": "object", "properties": {"position": vec, "main_axis": vec, "normal": vec}},
            "chassis": {"type": "string"}, "left_wheel": {"type": "string"},
            "hinge": {"type": "object", "properties": {"connectors": {"type": "array", "items": {"type": "string"}}}},
            "motor": {"type": "object", "properties": {
                "connectors": {"type": "array", "items": {"type": "string"}},
                "target_speed": {"type": "number", "description": "Target speed in rad/s."}}},
        },
    }
    return {"$schema": "http://json-schema.org/draft-07/schema#", "type": "object",
            "properties": {"models": {"type": "object", "additionalProperties": model}}}


# ------------------------------------------------------------------ measuring


def positions(text: str, needle: str, delta: int, limit: int) -> list[dict]:
    out = []
    lines = text.split("\n")
    for n, line in enumerate(lines):
        i = line.find(needle)
        if i >= 0:
            out.append({"line": n, "character": i + delta})
    random.Random(len(out)).shuffle(out)
    return out[:limit]


def stats(samples: list[float]) -> tuple[float, float]:
    s = sorted(samples)
    p95 = s[min(len(s) - 1, int(round(0.95 * (len(s) - 1))))]
    return statistics.median(s) * 1000, p95 * 1000


def run(name: str, cmd: list[str], folder: Path, filename: str, text: str, language: str, config: dict,
        init_options: dict, debounce_ms: float, typo: tuple[str, str], typing: tuple[str, str], probes: dict,
        n_req: int, n_edits: int, settle: float) -> dict:
    path = folder / filename
    path.write_text(text)
    uri = path.resolve().as_uri()
    t0 = time.perf_counter()
    client = Client(cmd, str(folder), config)
    caps = {"general": {"positionEncodings": ["utf-16"]},
            "workspace": {"configuration": True, "didChangeConfiguration": {"dynamicRegistration": False}},
            "textDocument": {"synchronization": {"didSave": True},
                             "hover": {"contentFormat": ["markdown", "plaintext"]},
                             "completion": {"completionItem": {"documentationFormat": ["markdown", "plaintext"]}},
                             "publishDiagnostics": {"versionSupport": True}}}
    client.request("initialize", {"processId": os.getpid(), "rootUri": folder.resolve().as_uri(),
                                  "capabilities": caps, "initializationOptions": init_options})
    client.notify("initialized", {})
    client.notify("workspace/didChangeConfiguration", {"settings": config})
    startup = time.perf_counter() - t0
    item = {"uri": uri, "languageId": language, "version": 1, "text": text}
    since = client.notify("textDocument/didOpen", {"textDocument": item})
    t_open, _ = client.wait_diagnostics(uri, since, timeout=120)
    first = t_open - since
    time.sleep(0.5)
    client.drain()

    # diagnostics after edits: alternately misspell and fix an attribute in a random model
    rng = random.Random(7)
    lines = text.split("\n")
    candidates = [n for n, ln in enumerate(lines) if typo[0] in ln]
    diag_times = []
    version = 1
    for k in range(n_edits):
        n = rng.choice(candidates)
        col = lines[n].index(typo[0])
        for word, repl in ((typo[0], typo[1]), (typo[1], typo[0])):
            version += 1
            rng_ = {"start": {"line": n, "character": col}, "end": {"line": n, "character": col + len(word)}}
            since = client.notify("textDocument/didChange", {
                "textDocument": {"uri": uri, "version": version},
                "contentChanges": [{"range": rng_, "text": repl}]})
            t, params = client.wait_diagnostics(uri, since, version=version)
            if k % 2 == 0 or word == typo[1]:
                diag_times.append(t - since)
            time.sleep(settle)
    client.drain()

    # completion while typing: insert a half-typed line, ask for completion at once (before the
    # debounced check has run), then undo it and let the server settle
    typing_times = []
    ins_lines = [n for n, ln in enumerate(lines) if typing[0] in ln]
    for k in range(n_req):
        n = ins_lines[k % len(ins_lines)]
        end = len(lines[n])
        version += 1
        client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version}, "contentChanges": [
            {"range": {"start": {"line": n, "character": end}, "end": {"line": n, "character": end}},
             "text": "\n" + typing[1]}]})
        dt, msg = client.request("textDocument/completion", {
            "textDocument": {"uri": uri}, "position": {"line": n + 1, "character": len(typing[1])}})
        typing_times.append(dt)
        out_items = msg.get("result")
        version += 1
        since = client.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": version},
                                                         "contentChanges": [{"range": {
                                                             "start": {"line": n, "character": end},
                                                             "end": {"line": n + 1, "character": len(typing[1])}},
                                                             "text": ""}]})
        client.wait_diagnostics(uri, since, version=version)
        time.sleep(settle)
    client.drain()

    out = {"name": name, "startup": startup * 1000, "first": first * 1000, "diag": diag_times,
           "debounce": debounce_ms, "typing": typing_times, "typing:sample": out_items}
    for method, (needle, delta) in probes.items():
        pts = positions(text, needle, delta, n_req)
        times = []
        k = 0
        while len(times) < n_req:
            p = pts[k % len(pts)]
            k += 1
            dt, msg = client.request(method, {"textDocument": {"uri": uri}, "position": p})
            if "error" in msg:
                raise SystemExit(f"{name} {method} failed: {msg['error']}")
            times.append(dt)
        out[method] = times
        out[method + ":sample"] = msg.get("result")
    out["rss"], out["hwm"] = client.memory_kb()
    if name.startswith("plx"):
        _dt, msg = client.request("plx/stats", {})
        out["server"] = msg.get("result") or {}
    client.close()
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", type=int, default=2000)
    ap.add_argument("--requests", type=int, default=40)
    ap.add_argument("--edits", type=int, default=20, help="typo/fix pairs: 2 diagnostics rounds each")
    ap.add_argument("--settle", type=float, default=0.02, metavar="S",
                    help="pause after each published check before the next edit or typing probe (default "
                         "0.02 s: the next request may meet the server still collecting garbage after the check)")
    ap.add_argument("--json", metavar="FILE", help="also write the raw figures as JSON")
    args = ap.parse_args()
    results = []
    with tempfile.TemporaryDirectory(prefix="plx-lsp-bench-") as tmp:
        folder = Path(tmp)
        ptext = openplx_text(args.lines)
        results.append(run(
            "plx lsp", [sys.executable, "-m", "plxtools", "lsp"], folder, "bench.openplx", ptext, "openplx",
            {"openplx": {}}, {"diagnosticsDelayMs": PLX_DEBOUNCE_MS}, PLX_DEBOUNCE_MS,
            ("density", "densty"), ("inertia.mass", "    inertia."),
            {"textDocument/completion": ("inertia.mass", len("inertia.")),
             "textDocument/hover": ("inertia.mass", len("inertia.m")),
             "textDocument/definition": ("is Physics3D.Bodies.RigidBody", len("is Physics3D.Bodies.Ri"))},
            args.requests, args.edits, args.settle))
        if YAML_LS.exists():
            (folder / "bench-schema.json").write_text(json.dumps(yaml_schema()))
            ytext = yaml_text(args.lines)
            cfg = {"yaml": {"validate": True, "hover": True, "completion": True, "schemaStore": {"enable": False},
                            "format": {"enable": True}}}
            results.append(run(
                "yaml-language-server", ["node", str(YAML_LS), "--stdio"], folder, "bench.yaml", ytext, "yaml",
                cfg, {}, YAML_DEBOUNCE_MS, ("density", "densty"), ("      radius:", "      "),
                {"textDocument/completion": ("    mass:", 4),
                 "textDocument/hover": ("    mass:", 5),
                 "textDocument/definition": ("chassis: chassis_", len("chassis: chassis_"))},
                args.requests, args.edits, args.settle))
        else:
            print(f"(peer not installed: run `npm install` in {YAML_LS.parents[2]})")
    lines = len(ptext.splitlines())
    print(f"LSP latency, {lines}-line file ({machine()}); {args.requests} requests each, "
          f"{2 * args.edits} edits; times in ms")
    rows = []
    for r in results:
        d_med, d_p95 = stats(r["diag"])
        row = [r["name"], f"{r['startup']:.0f}", f"{r['first']:.0f}",
               f"{d_med:.0f} / {d_p95:.0f}", f"{d_med - r['debounce']:.0f} / {d_p95 - r['debounce']:.0f}"]
        for m in ("typing", "textDocument/completion", "textDocument/hover", "textDocument/definition"):
            med, p95 = stats(r[m])
            row.append(f"{med:.1f} / {p95:.1f}")
        row.append(f"{r['rss'] / 1024:.0f} / {r['hwm'] / 1024:.0f}")
        rows.append(tuple(row))
    print(table(rows, ("server", "start", "open->diag", "edit->diag med/p95", "minus debounce",
                       "completion while typing", "completion", "hover", "definition", "RSS/peak MB")))
    for r in results:
        srv = r.get("server") or {}
        for kind, vals in srv.items():
            if not isinstance(vals, list) or not vals:
                continue  # "counters": background checks started / finished
            wall = statistics.median(v[0] for v in vals)
            cpu = statistics.median(v[1] for v in vals)
            p95 = sorted(v[0] for v in vals)[max(0, int(len(vals) * 0.95) - 1)]
            print(f"{r['name']} server-side {kind}: median {wall:.0f} ms wall (p95 {p95:.0f}), {cpu:.0f} ms CPU "
                  f"({len(vals)} runs)")
    print(f"debounce: plx {PLX_DEBOUNCE_MS} ms (diagnosticsDelayMs), yaml-language-server {YAML_DEBOUNCE_MS} ms "
          "(validationDelayMs, fixed)")
    for r in results:
        typed = r.get("typing:sample")
        typed_items = typed.get("items", typed) if isinstance(typed, dict) else typed
        print(f"{r['name']}: completion while typing returned {len(typed_items or [])} items")
        comp = r.get("textDocument/completion:sample")
        items = comp.get("items", comp) if isinstance(comp, dict) else comp
        print(f"{r['name']}: last completion returned {len(items or [])} items; "
              f"hover {'has' if r.get('textDocument/hover:sample') else 'has no'} content; "
              f"definition {'found' if r.get('textDocument/definition:sample') else 'found nothing'}")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1, default=str))


if __name__ == "__main__":
    main()
