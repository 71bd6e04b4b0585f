"""Per-file result caches of `plx lint` and `plx fmt`: an unchanged file gets the same answer
without being checked again; any change to what the answer depends on is a miss."""

from tests.conftest import plx_here, run_plx

CLEAN = ("Wheel is Physics3D.Bodies.RigidBody:\n    inertia.mass: 10\n\n"
         "Scene is Physics3D.System:\n    wheel is Wheel\n")
BROKEN = CLEAN.replace("inertia.mass", "inertia.mas")
UNKNOWN = CLEAN.replace("Physics3D.Bodies.RigidBody", "Physics3D.Bodies.RigidBodee")


def _entries(cache, name):
    return sorted(p for p in (cache / "plxtools" / name).rglob("*")) if (cache / "plxtools" / name).is_dir() \
        else []


def test_lint_results_are_reused_until_the_file_or_config_changes(tmp_path, warm_cache):
    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    proj = tmp_path / "proj"
    proj.mkdir()
    f = proj / "w.openplx"
    f.write_text(BROKEN)
    first = run_plx("lint", str(f), env=env)
    assert first.returncode == 1 and "N002" in first.stdout
    assert len(_entries(cache, "results")) == 1
    again = run_plx("lint", str(f), env=env)
    assert (again.returncode, again.stdout, again.stderr) == (first.returncode, first.stdout, first.stderr)
    assert len(_entries(cache, "results")) == 1  # a hit: nothing new stored

    f.write_text(CLEAN)  # the file changed: checked again
    clean = run_plx("lint", str(f), env=env)
    assert clean.returncode == 0 and "All checks passed" in clean.stdout

    f.write_text(BROKEN)
    (proj / "plx.toml").write_text('ignore = ["N002"]\n')  # the config changed: checked again
    ignored = run_plx("lint", str(f), env=env)
    assert ignored.returncode == 0, ignored.stdout
    (proj / "plx.toml").unlink()
    assert run_plx("lint", str(f), env=env).returncode == 1  # back to the first run's answer
    ignored = run_plx("lint", str(f), "--ignore", "N002", env=env)  # the command's own options count too
    assert ignored.returncode == 0, ignored.stdout

    nocache = plx_here("lint", "--no-cache", str(f), env={"PLX_CACHE_DIR": str(tmp_path / "other")})
    assert nocache.returncode == 1 and not _entries(tmp_path / "other", "results")


def test_results_that_depend_on_the_surroundings_are_not_stored(tmp_path, warm_cache):
    cache = warm_cache
    f = tmp_path / "u.openplx"
    f.write_text(UNKNOWN)
    r = run_plx("lint", str(f), env={"PLX_CACHE_DIR": str(cache)})
    assert "N001" in r.stdout
    assert not _entries(cache, "results")  # its help may name a bundle folder found nearby


def test_files_in_a_user_bundle_are_always_checked(tmp_path, warm_cache):
    cache = warm_cache
    b = tmp_path / "MyBundle"
    b.mkdir()
    (b / "config.openplx").write_text('config is Bundle:\n    name: "MyBundle"\n    version: "0.1"\n')
    (b / "Part.openplx").write_text("Part is Physics3D.Bodies.RigidBody:\n    inertia.mass: 1\n")
    r = run_plx("lint", str(b / "Part.openplx"), env={"PLX_CACHE_DIR": str(cache)})
    assert r.returncode in (0, 1)
    assert not _entries(cache, "results")


def test_fmt_remembers_formatted_files_only(tmp_path, warm_cache):
    cache = warm_cache
    env = {"PLX_CACHE_DIR": str(cache)}
    f = tmp_path / "w.openplx"
    f.write_text(CLEAN)
    assert run_plx("fmt", "--check", str(f), env=env).returncode == 0
    assert len(_entries(cache, "formatted")) == 1
    again = run_plx("fmt", "--check", str(f), env=env)
    assert again.returncode == 0 and "1 file would be left unchanged" in again.stderr
    f.write_text(CLEAN.replace("    inertia", "  inertia"))  # not formatted: checked, and not stored
    changed = run_plx("fmt", "--check", str(f), env=env)
    assert changed.returncode == 1 and "would reformat" in changed.stderr
    assert len(_entries(cache, "formatted")) == 1
    assert run_plx("fmt", "--no-cache", "--check", str(f), env=env).returncode == 1


def test_many_files_in_parallel_report_what_one_by_one_runs_do(tmp_path, warm_cache):
    """Enough loose files to use the worker pool (8 files, over 256 KB): the same diagnostics in
    the same order as linting each file on its own."""
    import json

    part = ("Part{i} is Physics3D.Bodies.RigidBody:\n    inertia.mass: {i}.5\n"
            "    geometry is Physics3D.Geometries.Box:\n        size: Math.Vec3.from_xyz(0.1, 1.0, 2.0)\n\n")
    files = []
    for k in range(8):
        body = "".join(part.format(i=i) for i in range(300))
        if k % 3 == 0:
            body += "Bad is Physics3D.Bodies.RigidBody:\n    inertia.mas: 1\n\n"
        body += "Scene is Physics3D.System:\n" + "".join(f"    p{i} is Part{i}\n" for i in range(300))
        f = tmp_path / f"f{k}.openplx"
        f.write_text(body)
        files.append(f)
    assert sum(f.stat().st_size for f in files) > 256 * 1024
    env = {"PLX_CACHE_DIR": str(warm_cache)}
    together = run_plx("lint", "--no-cache", "--output-format", "json", str(tmp_path), env=env)
    alone = []
    for f in files:
        r = plx_here("lint", "--no-cache", "--output-format", "json", str(f), env=env)  # the reference
        alone += json.loads(r.stdout)
    assert json.loads(together.stdout) == alone
    assert together.returncode == 1 and any(d["code"] == "N002" for d in alone)
    # with the result cache: filled by the workers, then read back (it once crashed the first time)
    for _ in range(2):
        cached = run_plx("lint", "--output-format", "json", *map(str, files), env=env)
        assert (cached.returncode, json.loads(cached.stdout)) == (1, alone), cached.stderr
