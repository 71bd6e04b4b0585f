"""The ide layer called directly: no server, no LSP types."""

from __future__ import annotations

from pathlib import Path

import pytest

from plxtools.ide import AnalysisHost

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = str((REPO / "examples" / "boxtruck" / "boxtruck.openplx").resolve())


@pytest.fixture(scope="session")
def host() -> AnalysisHost:
    return AnalysisHost()


class Doc:
    """A document opened in the host, with offsets found by text."""

    def __init__(self, host: AnalysisHost, path: str, text: str):
        self.host = host
        self.path = path
        self.text = text
        host.open_document(path, text, 1)

    @property
    def st(self):
        return self.host.state(self.path)

    def at(self, needle: str, delta: int = 0, nth: int = 0) -> int:
        i = -1
        for _ in range(nth + 1):
            i = self.text.index(needle, i + 1)
        return i + delta

    def end_of(self, needle: str, nth: int = 0) -> int:
        return self.at(needle, len(needle), nth)

    def close(self) -> None:
        self.host.close_document(self.path)


@pytest.fixture
def example(host):
    doc = Doc(host, EXAMPLE, Path(EXAMPLE).read_text(encoding="utf-8"))
    yield doc
    doc.close()


@pytest.fixture
def scratch(host, tmp_path):
    """Open any text as a loose file; closed after the test."""
    docs = []

    def make(text: str, name: str = "scratch.openplx") -> Doc:
        d = Doc(host, str((tmp_path / name).resolve()), text)
        docs.append(d)
        return d

    yield make
    for d in docs:
        d.close()


def write_bundle(root: Path, name: str, files: dict[str, str], deps: tuple[str, ...] = ("Physics3D",)) -> Path:
    b = root / name
    b.mkdir(parents=True, exist_ok=True)
    dep_list = ", ".join(f'"{d}"' for d in deps)
    (b / "config.openplx").write_text(
        f'config is BundleConfig:\n    name: "{name}"\n    version: "0.1.0"\n    dependencies: [{dep_list}]\n')
    for rel, text in files.items():
        p = b / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return b
