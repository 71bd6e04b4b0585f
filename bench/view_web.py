"""plx view --web: time to a drawn page, edit-to-update latency, the page's frame rate, the engine's cost.

    python bench/view_web.py [--edits 10] [--shots docs/assets]

Needs Debian's chromium and playwright-core (cd tests/view/browser && npm ci), as the browser
tests.  On a copy of examples/boxtruck/boxtruck.openplx, started paused:
- start: from starting `plx view --web --no-open` to the page's first drawn frame (the browser is
  started before the command);
- save -> drawn: from writing an edit of the chassis length to the page drawing the new scene,
  and the same for the editor's unsaved text sent to api/text (what the VS Code command does);
- frame rate: the page drawing the scene again and again (software WebGL: SwiftShader, no GPU),
  and the pose frames it receives and draws per second while the simulation runs;
- engine: the CPU time plx's stepper (the one `plx check --simulate` takes) needs per simulated
  second, and the bytes of one pose frame: what streaming costs next to stepping in the page.
Peer: `plx view`'s MuJoCo window (bench/view.py) for start and reload.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from tests.view.web_support import Browser, PlxWeb, browser_missing  # noqa: E402


def _bump(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    path.write_text(text.replace(old, new, 1))
    st = os.stat(path)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))


def _pct(xs: list[float], p: float) -> float:
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(round(p * (len(xs) - 1))))]


def _gif(browser: Browser, web: PlxWeb, out: Path, tmp: Path) -> None:
    """Frames of the page at 0.2 s steps of simulated time (seek: the same frames on any machine)."""
    from PIL import Image

    browser.eval("document.getElementById('frames').click()")
    frames = []
    for k in range(21):
        web.post("api/control", {"action": "seek", "time": 0.2 * k})
        browser.wait_for(f"Math.abs(plxPreview.state.time - {0.2 * k}) < 1e-6 && !plxPreview.state.dirty", timeout=30)
        shot = browser.screenshot(tmp / f"frame{k:02d}.png")
        frames.append(Image.open(shot).convert("RGB").resize((640, 400)).quantize(160, Image.Quantize.MEDIANCUT))
    browser.eval("document.getElementById('frames').click()")
    frames[0].save(out, save_all=True, append_images=frames[1:], duration=200, loop=0, optimize=True)
    print(f"gif: {out} ({len(frames)} frames, {out.stat().st_size // 1024} KiB)")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--edits", type=int, default=10)
    ap.add_argument("--shots", help="write the page's screenshots (preview-*.png) into this folder")
    ap.add_argument("--gif", help="write an animated GIF of the page (the truck driving 4 s, needs Pillow)")
    args = ap.parse_args()
    why = browser_missing()
    if why:
        print(f"bench/view_web.py: {why}", file=sys.stderr)
        return 2
    os.environ.setdefault("PLX_CACHE_DIR", str(REPO / ".plx_cache_local"))
    tmp = Path(tempfile.mkdtemp(prefix="plx-view-web-"))
    model = tmp / "boxtruck.openplx"
    shutil.copy(REPO / "examples" / "boxtruck" / "boxtruck.openplx", model)
    browser = Browser()
    web = PlxWeb(model, "--paused")
    try:
        browser.goto(web.url, 960, 600)
        browser.wait_for("window.plxPreview && plxPreview.state.drawnGeneration >= 1", timeout=60)
        start = time.perf_counter() - web.started
        print(f"start: command to the first drawn page            {start:6.2f} s")
        if args.shots:
            browser.eval("document.getElementById('frames').click()")
            browser.wait_for("!plxPreview.state.dirty")
            browser.screenshot(Path(args.shots) / "preview-truck.png")
            browser.eval("document.getElementById('frames').click()")

        saves, texts = [], []
        sizes = ["3.4", "3.3"]
        for i in range(args.edits):
            gen = browser.eval("plxPreview.state.drawnGeneration")
            t0 = time.perf_counter()
            _bump(model, f"x: {sizes[(i + 1) % 2]}", f"x: {sizes[i % 2]}")
            browser.wait_for(f"plxPreview.state.drawnGeneration > {gen}", timeout=30)
            saves.append(time.perf_counter() - t0)
        text = model.read_text()
        for i in range(args.edits):
            gen = browser.eval("plxPreview.state.drawnGeneration")
            t0 = time.perf_counter()
            web.post("api/text", {"file": str(model), "text": text.replace("y: 1.7", f"y: {1.7 + 0.01 * (i + 1):.2f}", 1)})
            browser.wait_for(f"plxPreview.state.drawnGeneration > {gen}", timeout=30)
            texts.append(time.perf_counter() - t0)
        web.post("api/text", {"file": str(model), "text": None})
        for name, xs in (("save -> drawn", saves), ("unsaved text -> drawn", texts)):
            print(f"{name:<22} median {statistics.median(xs):.3f} s  p90 {_pct(xs, 0.9):.3f} s  "
                  f"max {max(xs):.3f} s  ({len(xs)} edits; the issue: 1 s, 2 s on a busy machine)")

        ms = browser.eval("plxPreview.benchDraw(120)")
        print(f"frame rate: one frame drawn in {ms:.2f} ms          {1000 / ms:6.0f} frames/s ceiling")
        web.post("api/control", {"action": "reset"})
        f0, t_0 = browser.eval("[plxPreview.state.frames, plxPreview.state.time]")
        web.post("api/control", {"action": "play"})
        time.sleep(3.0)
        f1, t_1 = browser.eval("[plxPreview.state.frames, plxPreview.state.time]")
        web.post("api/control", {"action": "pause"})
        print(f"running: {(f1 - f0) / 3.0:5.1f} pose frames drawn per second, {t_1 - t_0:.2f} s simulated "
              f"in 3 s (real time 1.0)")
        if args.shots:
            browser.wait_for("!plxPreview.state.dirty")
            browser.screenshot(Path(args.shots) / "preview-driving.png")
        if args.gif:
            _gif(browser, web, Path(args.gif), tmp)
    finally:
        browser.close()
        web.stop()

    from plxtools.check.api import load
    from plxtools.view.web import scene_data

    sim = load(model)
    ids = scene_data.body_ids(sim)
    c0 = time.process_time()
    sim.step(4.0)
    cpu = (time.process_time() - c0) / 4.0
    frame = json.dumps({"t": sim.time, "q": scene_data.poses(sim, ids)}, separators=(",", ":"))
    print(f"engine: plx's stepper {cpu * 1000:.1f} ms CPU per simulated second ({1 / cpu:.0f}x real time); "
          f"one pose frame {len(frame)} bytes, {len(frame) * 30 / 1024:.1f} KiB/s at 30 frames/s")
    print("peer: plx view's MuJoCo window (bench/view.py, docs/benchmarks.md): start to a drawn window and a "
          "saved edit on screen, under Xvfb")
    shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
