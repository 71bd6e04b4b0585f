"""Replayed runs (plxtools/runmemo.py): an unchanged `plx lint FILE` or `plx fmt --check FILE`
prints what the same command printed before, and anything the answer depends on makes it run
again. Each test compares with what a run without any cache (`--no-cache`) prints."""

import time

from tests.conftest import plx_here, run_plx

CLEAN = ("Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10\n\n"
         "Scene is Physics3D.System:\n    wheel is Wheel\n")
BROKEN = CLEAN.replace("inertia.mass", "inertia.mas")
UNKNOWN = CLEAN.replace("Physics3D.Bodies.RigidBody", "Physics3D.Bodies.RigidBodee")


def _runs(cache):
    folder = cache / "plxtools" / "replays"
    return sorted(p for p in folder.rglob("*") if p.is_file()) if folder.is_dir() else []


def _same(a, b):
    return (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)


def _fresh(tmp_path, *args):
    """The answer of a run with no cache at all (in this process: it reads no cache and replays nothing)."""
    return plx_here(*args, "--no-cache", env={"PLX_CACHE_DIR": str(tmp_path / "none")})


def test_an_unchanged_run_is_replayed_with_the_same_output(tmp_path, warm_cache):
    env = {"PLX_CACHE_DIR": str(warm_cache)}
    f = tmp_path / "w.openplx"
    f.write_text(BROKEN)
    for fmt in ("text", "json", "sarif"):
        first = run_plx("lint", "--output-format", fmt, str(f), env=env)
        again = run_plx("lint", "--output-format", fmt, str(f), env=env)
        assert first.returncode == 1 and _same(first, again), fmt
        assert _same(first, _fresh(tmp_path, "lint", "--output-format", fmt, str(f)))
    assert len(_runs(warm_cache)) == 3  # one entry per command line
    quiet = run_plx("lint", "-q", "--exit-zero", str(f), env=env)
    assert quiet.returncode == 0 and _same(quiet, run_plx("lint", "-q", "--exit-zero", str(f), env=env))


def test_a_changed_file_or_config_runs_again(tmp_path, warm_cache):
    env = {"PLX_CACHE_DIR": str(warm_cache)}
    proj = tmp_path / "a" / "b"
    proj.mkdir(parents=True)
    f = proj / "w.openplx"
    f.write_text(BROKEN)
    assert run_plx("lint", str(f), env=env).returncode == 1
    f.write_text(CLEAN)  # same command line, other bytes
    assert run_plx("lint", str(f), env=env).returncode == 0
    f.write_text(BROKEN)
    assert run_plx("lint", str(f), env=env).returncode == 1
    cfg = tmp_path / "a" / "plx.toml"  # a config created two folders up
    cfg.write_text('ignore = ["N002"]\n')
    assert run_plx("lint", str(f), env=env).returncode == 0
    cfg.write_text('ignore = ["N003"]\n')  # edited
    r = run_plx("lint", str(f), env=env)
    assert r.returncode == 1 and _same(r, _fresh(tmp_path, "lint", str(f)))
    cfg.write_text('ignore = ["NOPE"]\n')  # broken: a usage error, never recorded
    assert run_plx("lint", str(f), env=env).returncode == 2
    assert run_plx("lint", str(f), env=env).returncode == 2
    cfg.unlink()
    assert run_plx("lint", str(f), env=env).returncode == 1
    assert run_plx("lint", str(f), env=env | {"NO_COLOR": ""}).returncode == 1  # other environment
    r = run_plx("lint", str(f), env=env, cwd=tmp_path)  # another working folder: paths print otherwise
    assert _same(r, plx_here("lint", str(f), "--no-cache", env=env, cwd=tmp_path))


def test_an_imported_file_is_part_of_the_answer(tmp_path, warm_cache):
    env = {"PLX_CACHE_DIR": str(warm_cache)}
    f = tmp_path / "w.openplx"
    f.write_text('import @"wheel.obj"\n\n' + CLEAN)
    missing = run_plx("lint", str(f), env=env)
    assert _same(missing, run_plx("lint", str(f), env=env))
    (tmp_path / "wheel.obj").write_text("v 0 0 0\n")
    found = run_plx("lint", str(f), env=env)
    assert _same(found, _fresh(tmp_path, "lint", str(f)))
    assert found.stdout != missing.stdout or found.returncode != missing.returncode


def test_what_depends_on_the_surroundings_is_never_replayed(tmp_path, warm_cache):
    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    f = tmp_path / "u.openplx"
    f.write_text(UNKNOWN)  # an unknown name: its help may name a bundle folder found nearby
    assert "N001" in run_plx("lint", str(f), env=env).stdout
    b = tmp_path / "MyBundle"  # a file in a bundle: its neighbours are part of it
    b.mkdir()
    (b / "config.openplx").write_text('config is Bundle:\n    name: "MyBundle"\n    version: "0.1"\n')
    (b / "Part.openplx").write_text("Part is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n")
    assert run_plx("lint", str(b / "Part.openplx"), env=env).returncode in (0, 1)
    g = tmp_path / "w.openplx"
    g.write_text(CLEAN)
    run_plx("lint", str(tmp_path), env=env)  # a folder: its listing is not recorded
    run_plx("lint", "--no-cache", str(g), env=env)
    run_plx("lint", "--fix", str(g), env=env)
    run_plx("lint", "-", stdin=CLEAN, env=env)
    assert not _runs(cache)


def test_fmt_check_is_replayed_while_the_file_is_formatted(tmp_path, warm_cache):
    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    f = tmp_path / "w.openplx"
    f.write_text(CLEAN)
    first = run_plx("fmt", "--check", str(f), env=env)
    assert first.returncode == 0 and len(_runs(cache)) == 1
    assert _same(first, run_plx("fmt", "--check", str(f), env=env))
    f.write_text(CLEAN.replace("    inertia", "  inertia"))
    changed = run_plx("fmt", "--check", str(f), env=env)
    assert changed.returncode == 1 and "would reformat" in changed.stderr
    assert _same(changed, run_plx("fmt", "--check", str(f), env=env))
    assert len(_runs(cache)) == 1  # a file that would change is checked every time
    run_plx("fmt", str(f), env=env)  # without --check it writes: never replayed
    assert f.read_text() == CLEAN and len(_runs(cache)) == 1


def test_a_cold_run_leaves_the_bundle_program_cache_behind(tmp_path):
    """The first run writes the bundle program's cache from a child process after it has checked
    the file; the command's output does not wait for it, and the next run finds the cache."""
    cache = tmp_path / "cache"
    f = tmp_path / "w.openplx"
    f.write_text(BROKEN)
    first = run_plx("lint", str(f), env={"PLX_CACHE_DIR": str(cache)})
    assert _same(first, _fresh(tmp_path, "lint", str(f)))
    folder = cache / "plxtools"
    for _ in range(600):  # the child is done when its temporary file has been renamed
        if list(folder.glob("programs/*")) and not list(folder.glob("programs/.*.tmp")):
            break
        time.sleep(0.1)
    assert list(folder.glob("programs/*"))
    second = run_plx("lint", "--output-format", "json", str(f), env={"PLX_CACHE_DIR": str(cache)})
    assert _same(second, _fresh(tmp_path, "lint", "--output-format", "json", str(f)))


def test_unrelated_files_beside_it_keep_the_run_replayable(tmp_path, warm_cache):
    """An editor's swap file or a new file beside it changes nothing plx reads: the run is replayed
    (seen here by the per-file result, removed in between, not being stored again)."""
    import shutil

    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    f = tmp_path / "w.openplx"
    f.write_text(BROKEN)
    first = run_plx("lint", str(f), env=env)
    shutil.rmtree(cache / "plxtools" / "results")
    (tmp_path / ".w.openplx.swp").write_text("x")
    again = run_plx("lint", str(f), env=env)
    assert _same(first, again)
    assert not (cache / "plxtools" / "results").exists()  # replayed, not checked
    (tmp_path / "plx.toml").write_text("")  # a config, even an empty one: run again
    assert _same(first, run_plx("lint", str(f), env=env))
    assert (cache / "plxtools" / "results").exists()


def test_a_damaged_entry_is_a_miss(tmp_path, warm_cache):
    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    f = tmp_path / "w.openplx"
    f.write_text(BROKEN)
    first = run_plx("lint", str(f), env=env)
    (entry,) = _runs(cache)
    for junk in (b"", b"\x00garbage", b'{"deps": [], "out": "All checks passed in 1 file.\\n", "err": "", "code": 0}',
                 entry.read_bytes()[:-3]):
        entry.write_bytes(junk)
        again = run_plx("lint", str(f), env=env)
        assert _same(first, again) and "Traceback" not in again.stderr
