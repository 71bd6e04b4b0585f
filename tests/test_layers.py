"""The layers hold at run time too: lint and fmt load neither the simulator nor the server's stack,
and the import contracts in pyproject.toml are what CI checks."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "mujoco", "pygls", "lsprotocol")


def _loaded_after(argv: list[str], tmp_path) -> list[str]:
    code = ("import sys\nfrom plxtools.cli import main\ntry:\n    main(%r)\nexcept SystemExit:\n    pass\n"
            "print('loaded:', *(m for m in %r if m in sys.modules))" % (argv, HEAVY))
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120)
    last = r.stdout.strip().splitlines()[-1]
    assert last.startswith("loaded:"), r.stdout + r.stderr
    return last.split()[1:]


def test_lint_and_fmt_load_no_simulator_or_server(tmp_path):
    f = tmp_path / "scene.openplx"
    f.write_text("Scene is Physics3D.System:\n    b is Physics3D.Bodies.RigidBody\n", encoding="utf-8")
    assert _loaded_after(["lint", str(f)], tmp_path) == []
    assert _loaded_after(["fmt", "--check", str(f)], tmp_path) == []


def test_the_documented_layers_are_the_contracted_ones():
    """docs/architecture.md lists the layers in the order the import contract enforces."""
    contracts = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]
    layers = next(c for c in contracts if c["type"] == "layers")["layers"]
    doc = (REPO / "docs" / "architecture.md").read_text(encoding="utf-8")
    start = doc.index("<!-- layers -->")
    block = doc[start:doc.index("<!-- /layers -->")]
    listed = [ln.strip("`- ").split("`")[0] for ln in block.splitlines() if ln.startswith("- `")]
    assert listed == layers, "docs/architecture.md's layer list differs from [tool.importlinter] in pyproject.toml"


def test_no_circle_inside_check_and_no_model_constant_in_the_server():
    """dev/import_graph.py over every import, top-level or inside a function (issue 38): the
    modules of plxtools.check import each other one way only, and the server names a rule through
    the registry, not by a constant of the model or check layers."""
    r = subprocess.run([sys.executable, str(REPO / "dev" / "import_graph.py"), "--inside", "check"],
                       capture_output=True, text=True, check=True)
    assert "circles inside plxtools.check: 0" in r.stdout, r.stdout
    assert "circle:" not in r.stdout, r.stdout
    assert "lsp reads a constant" not in r.stdout, r.stdout
    # the script does see circles and constants: it finds a real one elsewhere
    whole = subprocess.run([sys.executable, str(REPO / "dev" / "import_graph.py")], capture_output=True, text=True,
                           check=True).stdout
    assert "circle: plxtools.model.program <-> plxtools.model.resolve" in whole, whole
