"""The Helix set-up of docs/editors.md, run for real in Helix 25.01 (Debian 13) and 25.07 (Debian
unstable) inside tmux: the `languages.toml` block is taken from the page as written, keys are typed
with `send-keys` and the screen is read with `capture-pane`, as a person would see it. Helix is
fetched from Debian's archive by `debian_editors.py` when PLX_EDITOR_TESTS=1 (as `.ci/run` sets).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import time
from pathlib import Path

import pytest

from tests.editors.common import REQUIRED, debian_editor, doc_blocks, editor_env, make_project

SETUPS = {"hx-25.01": ("trixie", "helix 25.01"), "hx-25.07": ("sid", "helix 25.07")}


class Screen:
    """One tmux session with Helix in it, on a socket of its own."""

    def __init__(self, tmp_path: Path, hx: Path, project: Path, env: dict[str, str]):
        self.sock = str(tmp_path / "tmux.sock")
        command = f"exec '{hx}' model.openplx"
        self.tmux("new-session", "-d", "-x", "150", "-y", "45", "-c", str(project), command, env=env)

    def tmux(self, *args: str, env: dict[str, str] | None = None) -> str:
        return subprocess.run(["tmux", "-S", self.sock, *args], capture_output=True, text=True, check=True,
                              env=env, timeout=30).stdout

    def keys(self, *keys: str, literal: str | None = None) -> None:
        if keys:
            self.tmux("send-keys", *keys)
        if literal is not None:
            self.tmux("send-keys", "-l", literal)
        time.sleep(0.3)

    def normal_mode(self) -> None:
        """Escape until the status line says NOR (a completion popup takes one Escape of its own)."""
        for _ in range(6):
            if re.search(r"^\s*NOR\b", self.text(), re.M):
                return
            self.keys("Escape")
        raise AssertionError(f"Helix did not return to normal mode:\n{self.text()}")

    def text(self) -> str:
        return self.tmux("capture-pane", "-p")

    def wait(self, pattern: str, seconds: float = 30) -> str:
        end = time.monotonic() + seconds
        while True:
            screen = self.text()
            if re.search(pattern, screen, re.M):
                return screen
            if time.monotonic() > end:
                raise AssertionError(f"waited {seconds} s for {pattern!r}; the screen:\n{screen}")
            time.sleep(0.2)

    def servers(self) -> int:
        """How many `plx lsp` processes Helix has started (its children)."""
        hx_pid = self.tmux("display-message", "-p", "#{pane_pid}").strip()
        children = subprocess.run(["pgrep", "-P", hx_pid, "-f", "plx lsp"], capture_output=True, text=True)
        return len(children.stdout.split())

    def close(self) -> None:
        subprocess.run(["tmux", "-S", self.sock, "kill-server"], capture_output=True)


@pytest.fixture
def tmux_available():
    if shutil.which("tmux") is None:
        if REQUIRED:
            pytest.fail("PLX_EDITOR_TESTS=1 but tmux is not installed")
        pytest.skip("tmux not installed")


@pytest.mark.parametrize("setup", sorted(SETUPS))
def test_the_documented_helix_setup(tmp_path, setup, tmux_available):
    suite, version = SETUPS[setup]
    hx = debian_editor(suite, "hx")
    project = make_project(tmp_path)
    home = tmp_path / "home"
    (home / ".config" / "helix").mkdir(parents=True)
    (home / ".config" / "helix" / "languages.toml").write_text(doc_blocks("Helix", "toml")[0], encoding="utf-8")
    env = editor_env(home)
    assert version in subprocess.run([str(hx), "--version"], capture_output=True, text=True, env=env).stdout
    health = subprocess.run([str(hx), "--health", "openplx"], capture_output=True, text=True, env=env).stdout
    assert re.search(r"plx: .*/plx\b", health), health

    screen = Screen(tmp_path, hx, project, env)
    try:
        # the diagnostic: a mark in the gutter of line 4, then the message in the diagnostics picker
        screen.wait(r"^●\s+4\s+raduis", 60)
        screen.keys("Space", "d")
        picker = screen.wait(r"N002 'raduis' is not an attribute")
        assert re.search(r"ERROR\s+(plx\s+)?N002 'raduis' is not an attribute", picker), picker
        screen.keys("Escape")

        # hover (space k) on RigidBody
        screen.keys("/", literal="RigidBody")
        screen.keys("Enter", "Space", "k")
        screen.wait(r"Physics3D\.Bodies\.RigidBody is Physics3D\.Bodies\.Body")
        screen.keys("Escape")

        # completion pops up after `inertia.` typed on a new line
        screen.keys("g", "g", "j", "A", "Enter", literal="inertia.")
        popup = screen.wait(r"\bmass\b.*\n.*\btensor\b")
        assert "field" in popup, popup

        screen.normal_mode()
        screen.keys("u")

        # go to definition (gd) into the official bundle: no second server
        screen.keys("/", literal="RigidBody")
        screen.keys("Enter", "g", "d")
        screen.wait(r"openplxbundles/Physics3D/Bodies/RigidBody\.openplx")
        time.sleep(1.5)
        assert screen.servers() == 1, screen.text()

        # back (ga) and reload three times: still one server
        screen.keys("g", "a")
        for _ in range(3):
            screen.keys(":", literal="reload")
            screen.keys("Enter")
        time.sleep(1.5)
        assert screen.servers() == 1, screen.text()

        # fix the typo: the mark goes away
        screen.keys("/", literal="raduis")
        screen.keys("Enter", "c", literal="radius")
        screen.normal_mode()
        end = time.monotonic() + 30
        while re.search(r"^●", screen.text(), re.M) and time.monotonic() < end:
            time.sleep(0.2)
        assert not re.search(r"^●", screen.text(), re.M), screen.text()

        # write: auto-format = true formats on save
        screen.keys("g", "g", "O", literal="Extra:")
        screen.keys("Enter", literal="    a is Real:   1")
        screen.keys("Enter")
        screen.normal_mode()
        screen.keys(":", literal="write")
        screen.keys("Enter")
        end = time.monotonic() + 30
        model = project / "model.openplx"
        while not model.read_text(encoding="utf-8").startswith("Extra:") and time.monotonic() < end:
            time.sleep(0.2)
        assert model.read_text(encoding="utf-8").startswith("Extra:\n    a is Real: 1\n\nBall is"), \
            model.read_text(encoding="utf-8") + "\n--- screen ---\n" + screen.text()
        assert "        radius: 0.5\n" in model.read_text(encoding="utf-8")
    finally:
        screen.close()
