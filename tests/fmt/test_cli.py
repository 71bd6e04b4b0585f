"""`plx fmt` through the real command line (`python -m plxtools fmt ...` in a subprocess)."""

from __future__ import annotations

import argparse

from plxtools.fmt import api as fmt_api
from plxtools.fmt.cli import run_fmt
from plxtools.fmt.document import Layout
from tests.fmt.helpers import run_fmt as plx_fmt

UGLY = b"Wheel is Physics3D.Bodies.RigidBody:\n  radius:   0.26\n  connector: [a,b]\n"
PRETTY = b"Wheel is Physics3D.Bodies.RigidBody:\n    radius: 0.26\n    connector: [a, b]\n"
BROKEN = b"Wheel is Physics3D.Bodies.RigidBody:\n  radius: = 0.26\n    x:   1\n"


def _files(tmp_path, **contents: bytes):
    paths = {}
    for name, data in contents.items():
        p = tmp_path / f"{name}.openplx"
        p.write_bytes(data)
        paths[name] = p
    return paths


def test_check_lists_files_that_would_change_and_exits_1(tmp_path):
    f = _files(tmp_path, ugly=UGLY, pretty=PRETTY)
    proc = plx_fmt("--check", str(tmp_path))
    err = proc.stderr.decode()
    assert proc.returncode == 1, err
    assert f"would reformat {f['ugly']}" in err
    assert str(f["pretty"]) not in err
    assert "1 file would be reformatted, 1 file would be left unchanged." in err
    assert proc.stdout == b""
    assert f["ugly"].read_bytes() == UGLY


def test_check_exits_0_when_everything_is_formatted(tmp_path):
    f = _files(tmp_path, pretty=PRETTY)
    proc = plx_fmt("--check", str(f["pretty"]))
    assert proc.returncode == 0
    assert b"1 file would be left unchanged." in proc.stderr


def test_in_place_reports_like_black_and_a_second_run_changes_nothing(tmp_path):
    f = _files(tmp_path, ugly=UGLY, pretty=PRETTY)
    proc = plx_fmt(str(tmp_path))
    err = proc.stderr.decode()
    assert proc.returncode == 0, err
    assert f"reformatted {f['ugly']}" in err
    assert "1 file reformatted, 1 file left unchanged." in err
    assert f["ugly"].read_bytes() == PRETTY
    again = plx_fmt(str(tmp_path))
    assert again.returncode == 0 and b"2 files left unchanged." in again.stderr


def test_quiet_prints_nothing_on_success(tmp_path):
    _files(tmp_path, ugly=UGLY)
    proc = plx_fmt("-q", str(tmp_path))
    assert proc.returncode == 0 and proc.stderr == b"" and proc.stdout == b""


def test_diff_prints_a_unified_diff_and_writes_nothing(tmp_path):
    f = _files(tmp_path, ugly=UGLY)
    proc = plx_fmt("--diff", str(f["ugly"]))
    out = proc.stdout.decode()
    assert proc.returncode == 0
    assert f"--- a/{f['ugly']}" in out and f"+++ b/{f['ugly']}" in out
    assert "-  radius:   0.26\n" in out and "+    radius: 0.26\n" in out
    assert f["ugly"].read_bytes() == UGLY
    assert plx_fmt("--diff", "--check", str(f["ugly"])).returncode == 1


def test_stdin_to_stdout_with_stdin_filename(tmp_path):
    proc = plx_fmt("-", "--stdin-filename", str(tmp_path / "x.openplx"), stdin=UGLY)
    assert proc.returncode == 0 and proc.stdout == PRETTY
    crlf = plx_fmt("-", stdin=b"\xef\xbb\xbf" + UGLY.replace(b"\n", b"\r\n"))
    assert crlf.stdout == b"\xef\xbb\xbf" + PRETTY.replace(b"\n", b"\r\n")
    check = plx_fmt("-", "--check", "--stdin-filename", "x.openplx", stdin=UGLY)
    assert check.returncode == 1 and check.stdout == b"" and b"would reformat x.openplx" in check.stderr


def test_stdin_with_a_syntax_error_prints_nothing_and_exits_2():
    proc = plx_fmt("-", "--stdin-filename", "model.openplx", stdin=BROKEN)
    assert proc.returncode == 2 and proc.stdout == b""
    assert b"model.openplx:2:11: error S008 unexpected '='" in proc.stderr


def test_a_file_with_a_syntax_error_is_refused_and_left_untouched(tmp_path):
    f = _files(tmp_path, broken=BROKEN, ugly=UGLY)
    before = f["broken"].stat().st_mtime_ns
    proc = plx_fmt(str(tmp_path))
    err = proc.stderr.decode()
    assert proc.returncode == 2
    assert f"{f['broken']}:2:11: error S008 unexpected '='" in err
    assert "1 failed to reformat" in err or "1 file failed to reformat" in err
    assert f["broken"].read_bytes() == BROKEN and f["broken"].stat().st_mtime_ns == before
    assert f["ugly"].read_bytes() == PRETTY  # the other file is still formatted


def test_crlf_and_bom_are_kept_in_place(tmp_path):
    data = b"\xef\xbb\xbf" + UGLY.replace(b"\n", b"\r\n")
    f = _files(tmp_path, crlf=data)
    assert plx_fmt(str(f["crlf"])).returncode == 0
    assert f["crlf"].read_bytes() == b"\xef\xbb\xbf" + PRETTY.replace(b"\n", b"\r\n")


def test_tabs_are_a_warning_not_a_refusal(tmp_path):
    f = _files(tmp_path, tabs=b"A:\n\tx:  1\n")
    assert plx_fmt(str(f["tabs"])).returncode == 0
    assert f["tabs"].read_bytes() == b"A:\n    x: 1\n"


def test_excluded_files_are_skipped_even_when_named(tmp_path):
    (tmp_path / "plx.toml").write_text('[fmt]\nexclude = ["generated"]\n')
    (tmp_path / "generated").mkdir()
    gen = tmp_path / "generated" / "gen.openplx"
    gen.write_bytes(UGLY)
    f = _files(tmp_path, ugly=UGLY)
    proc = plx_fmt("--check", str(tmp_path))
    assert proc.returncode == 1 and str(gen).encode() not in proc.stderr
    named = plx_fmt("--check", str(gen))
    assert named.returncode == 0 and b"No .openplx files found" in named.stderr
    piped = plx_fmt("-", "--stdin-filename", str(gen), stdin=UGLY)
    assert piped.returncode == 0 and piped.stdout == UGLY  # passed through untouched
    assert gen.read_bytes() == UGLY and f["ugly"].read_bytes() == UGLY


def test_usage_errors_exit_2(tmp_path):
    missing = plx_fmt(str(tmp_path / "nope.openplx"))
    assert missing.returncode == 2 and b"no such file or folder" in missing.stderr
    mixed = plx_fmt("-", str(tmp_path))
    assert mixed.returncode == 2


def test_check_with_refused_and_changed_files_exits_2(tmp_path):
    _files(tmp_path, broken=BROKEN, ugly=UGLY)
    assert plx_fmt("--check", str(tmp_path)).returncode == 2


def test_an_internal_error_writes_nothing_and_exits_2(tmp_path, monkeypatch, capsys):
    f = _files(tmp_path, ugly=UGLY)
    real = fmt_api.layout_tree

    def wrong(tree):
        good = real(tree)
        return Layout(good.text.replace("0.26", "0.27"), good.pieces)

    monkeypatch.setattr(fmt_api, "layout_tree", wrong)
    args = argparse.Namespace(paths=[str(f["ugly"])], check=False, diff=False, stdin_filename=None, quiet=False)
    assert run_fmt(args) == 2
    assert f["ugly"].read_bytes() == UGLY
    err = capsys.readouterr().err
    assert "internal error" in err and "left unchanged" in err
