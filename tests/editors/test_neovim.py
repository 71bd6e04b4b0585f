"""The Neovim set-ups of docs/editors.md, run for real in Neovim 0.10 (Debian 13) and 0.12 (Debian
unstable): the `init.lua` block for the version is taken from the page as written, and
`nvim_drive.lua` uses it as a person would (see that script). Neovim is fetched from Debian's archive
by `debian_editors.py` when PLX_EDITOR_TESTS=1 (as `.ci/run` sets); otherwise a Neovim fetched
before is used, or the test is skipped.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from tests.editors.common import debian_editor, doc_blocks, editor_env, make_project

DRIVER = Path(__file__).with_name("nvim_drive.lua")

# (Debian suite, which block of the page: 0 is the Neovim 0.11+ form, 1 the Neovim 0.10 form)
SETUPS = {"nvim-0.10": ("trixie", 1, "v0.10."), "nvim-0.12": ("sid", 0, "v0.12.")}


@pytest.mark.parametrize("setup", sorted(SETUPS))
def test_the_documented_neovim_setup(tmp_path, setup):
    suite, block, version = SETUPS[setup]
    nvim = debian_editor(suite, "neovim")
    assert version in subprocess.run([str(nvim), "--version"], capture_output=True, text=True).stdout
    project = make_project(tmp_path)
    home = tmp_path / "home"
    (home / ".config" / "nvim").mkdir(parents=True)
    (home / ".config" / "nvim" / "init.lua").write_text(doc_blocks("Neovim", "lua")[block], encoding="utf-8")
    results_file = tmp_path / "results.txt"
    env = editor_env(home)
    env.update(PLX_RESULTS=str(results_file), PLX_MODEL=str(project / "model.openplx"))
    run = subprocess.run([str(nvim), "--headless", "-c", f"luafile {DRIVER}"], cwd=project, env=env,
                         capture_output=True, text=True, timeout=300)
    text = results_file.read_text(encoding="utf-8") if results_file.exists() else ""
    results: dict[str, list[str]] = {}
    for line in text.splitlines():
        key, _, value = line.partition(": ")
        results.setdefault(key, []).append(value)
    out = f"{text}\n--- nvim stdout/stderr ---\n{run.stdout}{run.stderr}"
    assert "error" not in results, out
    assert results["filetype"] == ["openplx"], out
    assert results["clients"] == ["1"], out
    assert Path(results["root"][0]).resolve() == project.resolve(), out
    assert results["diagnostic"] == ["4 N002 'raduis' is not an attribute of Physics3D.Geometries.Sphere"], out
    assert "Physics3D.Bodies.RigidBody is Physics3D.Bodies.Body" in results["hover"][0], out
    # the second argument is the one Neovim highlights
    assert results["signature"] == ["static fn from_xyz(x: Real, y: Real, z: Real) -> Vec3 => y: Real"], out
    assert results["completion"] == ["mass tensor"], out
    assert results["definition"][0].replace("\\", "/").endswith("openplxbundles/Physics3D/Bodies/RigidBody.openplx:1"), out
    # one server for the project: the bundle file and five reloads join it
    assert results["clients after definition"] == ["1"], out
    assert results["bundle buffer attached"] == ["1"], out
    assert results["clients after reloads"] == ["1"], out
    assert results["model buffer attached"] == ["1"], out
    assert results["diagnostics after fix"] == ["0"], out
    assert results["formatted"] == ["Extra:|    a is Real: 1||Ball is Physics3D.Bodies.RigidBody:"], out
