"""`plx bundles install` where plx's interpreter has no pip (pipx, `uv tool install`, a `uv venv`):
the wheel comes from the package index pip is configured for, over HTTP (here a file:// index laid
out as the simple repository API), and its sha256 is checked. .ci/smoke-wheel does it for real in a
venv made --without-pip, against the registry."""

from __future__ import annotations

import hashlib
import io
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from plxtools.model import index_fetch

NO_PIP = "import sys; sys.modules['pip'] = None\nfrom plxtools.cli import main; sys.exit(main(sys.argv[1:]))\n"
VERSION = "0.16.3"  # a real release number (plx checks the form), with fake contents of our own


def _wheel_bytes() -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("openplxbundles/Math/config.openplx", "# a stand-in bundle\n")
        zf.writestr("openplxbundles/Math/Vec.openplx", "Vec3 is Real:\n")
        zf.writestr(f"openplx_bundles-{VERSION}.dist-info/METADATA", f"Name: openplx-bundles\nVersion: {VERSION}\n")
    return buf.getvalue()


def _index(tmp_path: Path, *, sha: str | None = None, versions=(VERSION,)) -> Path:
    """simple/openplx-bundles/index.html linking to ../../files/<wheel>#sha256=..."""
    files = tmp_path / "index" / "files"
    page = tmp_path / "index" / "simple" / "openplx-bundles"
    files.mkdir(parents=True)
    page.mkdir(parents=True)
    links = []
    data = _wheel_bytes()
    for v in versions:
        name = f"openplx_bundles-{v}-py3-none-any.whl"
        (files / name).write_bytes(data)
        digest = sha or hashlib.sha256(data).hexdigest()
        links.append(f'<a href="../../files/{name}#sha256={digest}">{name}</a>')
    (page / "index.html").write_text("<html><body>\n" + "\n".join(links) + "\n</body></html>\n", encoding="utf-8")
    return tmp_path / "index" / "simple"


def _plx(tmp_path: Path, index: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PIP_CONFIG_FILE": os.devnull, "PIP_INDEX_URL": index.as_uri() + "/",
           "PLX_CACHE_DIR": str(tmp_path / "cache"), "PLX_NO_PROGRESS": "1"}
    for k in ("PIP_EXTRA_INDEX_URL", "PIP_FIND_LINKS", "PIP_NO_INDEX", "UV_INDEX", "UV_EXTRA_INDEX_URL",
              "UV_DEFAULT_INDEX", "UV_INDEX_URL"):
        env.pop(k, None)
    return subprocess.run([sys.executable, "-c", NO_PIP, *args], capture_output=True, text=True, env=env,
                          timeout=120, cwd=tmp_path)


def test_bundles_install_fetches_from_the_configured_index_without_pip(tmp_path):
    index = _index(tmp_path, versions=("0.16.2", VERSION, "0.16.4"))
    r = _plx(tmp_path, index, "bundles", "install", VERSION)
    assert r.returncode == 0, r.stderr
    root = tmp_path / "cache" / "plxtools" / "bundles" / VERSION / "openplxbundles"
    assert r.stdout.strip() == f"openplx-bundles {VERSION}: {root}"
    assert (root / "Math" / "Vec.openplx").read_text() == "Vec3 is Real:\n"
    assert (tmp_path / "cache" / "plxtools" / "wheels" / f"openplx_bundles-{VERSION}-py3-none-any.whl").is_file()
    listed = _plx(tmp_path, index, "bundles", "list")
    assert any(ln.split()[:2] == [VERSION, "cached"] for ln in listed.stdout.splitlines()), listed.stdout


def test_a_version_the_index_does_not_have_is_a_clear_error(tmp_path):
    index = _index(tmp_path)
    r = _plx(tmp_path, index, "bundles", "install", "0.16.9")
    assert r.returncode == 2
    assert "openplx-bundles 0.16.9 is not on the package index" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr and "No module named pip" not in r.stderr
    assert not (tmp_path / "cache" / "plxtools" / "bundles" / "0.16.9").exists()


def test_a_download_that_does_not_match_its_sha256_is_refused_and_leaves_nothing(tmp_path):
    index = _index(tmp_path, sha="0" * 64)
    r = _plx(tmp_path, index, "bundles", "install", VERSION)
    assert r.returncode == 2 and "does not match the index's sha256" in r.stderr, r.stderr
    assert not list((tmp_path / "cache" / "plxtools").rglob("*.whl"))
    assert not (tmp_path / "cache" / "plxtools" / "bundles" / VERSION).exists()


def test_an_unreachable_index_says_so(tmp_path):
    r = _plx(tmp_path, tmp_path / "no-such-index", "bundles", "install", VERSION)
    assert r.returncode == 2 and "not on the package index" in r.stderr, r.stderr
    r = subprocess.run([sys.executable, "-c", NO_PIP, "bundles", "install", VERSION], capture_output=True,
                       text=True, timeout=120, cwd=tmp_path,
                       env={**os.environ, "PIP_CONFIG_FILE": os.devnull, "PIP_INDEX_URL": "http://127.0.0.1:9/simple/",
                            "PLX_CACHE_DIR": str(tmp_path / "cache"), "PLX_PIP_TIMEOUT": "3"})
    assert r.returncode == 2 and "the package index cannot be reached" in r.stderr, r.stderr


def test_sources_follow_pip_environment_and_config_files(tmp_path, monkeypatch):
    conf = tmp_path / "pip.conf"
    conf.write_text("[global]\nindex-url = https://mirror.example/simple\nextra-index-url =\n"
                    "    file:///opt/a/simple\n    file:///opt/b/simple\nfind-links = /opt/wheels\n", encoding="utf-8")
    monkeypatch.setenv("PIP_CONFIG_FILE", str(conf))
    for k in ("PIP_INDEX_URL", "PIP_EXTRA_INDEX_URL", "PIP_FIND_LINKS", "PIP_NO_INDEX"):
        monkeypatch.delenv(k, raising=False)
    s = index_fetch.configured_sources({})
    assert s.indexes == ["https://mirror.example/simple", "file:///opt/a/simple", "file:///opt/b/simple"]
    assert s.find_links == ["/opt/wheels"]
    s = index_fetch.configured_sources({"PIP_INDEX_URL": "https://other/simple/", "PIP_EXTRA_INDEX_URL": ""})
    assert s.indexes[0] == "https://other/simple/"
    monkeypatch.setenv("PIP_CONFIG_FILE", os.devnull)
    assert index_fetch.configured_sources({}).indexes == [index_fetch.DEFAULT_INDEX]
    assert index_fetch.configured_sources({"PIP_NO_INDEX": "1"}).indexes == []


@pytest.mark.parametrize("name, ok", [
    (f"openplx_bundles-{VERSION}-py3-none-any.whl", True),
    (f"openplx.bundles-{VERSION}-py3-none-any.whl", True),
    (f"openplx_bundles-{VERSION}1-py3-none-any.whl", False),
    (f"openplx_bundles-{VERSION}.tar.gz", False),
    (f"openplx_bundles_extra-{VERSION}-py3-none-any.whl", False),
])
def test_only_the_exact_version_wheel_matches(name, ok):
    assert index_fetch._wheel_name_matches(name, "openplx-bundles", VERSION) is ok
