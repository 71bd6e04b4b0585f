"""A differential campaign: random sequences of what users and tools do to a project, each
followed by a cached `plx lint` (and `plx fmt --check`) compared with a fresh run on an empty
cache folder. Any difference is a cache that lied.

The project lints against a tiny base set of its own (bundles named Math and Physics replace the
official ones), so each run takes milliseconds and a campaign of thousands of steps fits in a
test. The actions: edit a file; edit it keeping its size and mtime; replace it by rename (as
editors save); replace it by a symbolic link and back; create or delete plx.toml / pyproject.toml
in the file's folder and in parent folders; change the environment variable a `$"..."` import
reads; create or delete the imported file; edit, add or remove a file of a user bundle (also
keeping size and mtime); save a file while plx runs.

Time: a file's stat is trusted only two seconds after its last change (`cache.reads`, racy-clean
rule). To exercise that fast path too, some steps move the recorder's clock forward (as if the
user came back later) after waiting a moment, so that the next change gets a new ctime.
"""

from __future__ import annotations

import os
import random
import shutil
import tempfile
import time
from pathlib import Path

from tests.cache import inproc

BASE = {
    "Math/config.openplx": 'config is BundleConfig:\n    name: "Math"\n    version: "0.19.0"\n',
    "Math/Vec.openplx": "Vec:\n    x is Real: 0.0\n",
    "Physics/config.openplx": 'config is BundleConfig:\n    name: "Physics"\n    version: "0.19.0"\n'
                              '    dependencies: ["Math"]\n',
    "Physics/Body.openplx": "Body:\n    mass is Real: 1.0\n    size is Real: 1.0\n",
}
LIB_CONFIG = 'config is BundleConfig:\n    name: "Lib"\n    version: "0.1.0"\n    dependencies: ["Physics"]\n'
# user bundle file variants; the first two have the same length (a rename keeping size and mtime)
WHEELS = ["Wheel is Physics.Body:\n    mass: 2.0\n", "Wheal is Physics.Body:\n    mass: 2.0\n",
          "Wheel is Physics.Body:\n    mass: 2.0\n    size: 0.5\n", "Wheel is Physics.Body:\n    mas: 2.0\n"]
# lint targets: same-length groups let an edit keep the size
TARGETS = [
    "Scene is Lib.Parts.Wheel:\n    mass: 3.0\n",
    "Scene is Lib.Parts.Wheel:\n    mass: 4.0\n",
    "Scene is Lib.Parts.Wheel:\n    mas: 3.00\n",
    'Scene is Lib.Parts.Wheel:\n    mass: "3"\n',
    "Scene is  Lib.Parts.Wheel:\n    mass: 3.0\n",
    'import @"m.obj" as M\n\nScene is Lib.Parts.Wheel:\n    v is M\n',
    '\ufeffimport @"m.obj" as M\n\nScene is Lib.Parts.Wheel:\n    v is M\n',
    '# c\rimport @"m.obj" as M\r\rScene is Lib.Parts.Wheel:\r    v is M\r',
    '\fimport @"m.obj" as M\n\nScene is Lib.Parts.Wheel:\n    v is M\n',
    'import $"{MODELS}/m.obj" as M\n\nScene is Lib.Parts.Wheel:\n    v is M\n',
    '# c\rimport $"{MODELS}/m.obj" as M\r\rScene is Physics.Body:\r    v is M\r',
    "Scene is Physics.Body:\n    size: 2.0\n",
    "Scene is Physics.Body:\n    sise: 2.0\n",
    "Scene is Lib.Parts.Extra:\n    mass: 3.0\n",
]
CONFIGS = ['bundle-path = ["."]\n', 'bundle-path = ["."]\nignore = ["N006"]\n', 'bundle-path = ["."]\nignore = ["N002"]\n',
           'bundle-path = ["."]\nignore = ["T001"]\n']
SUB_CONFIGS = ['bundle-path = [".."]\nignore = ["N006"]\n', 'bundle-path = [".."]\nignore = ["N002"]\n', "", 'ignore = ["N006"]\n']
PYPROJECTS = ['[tool.plx]\nbundle-path = [".."]\nignore = ["N002"]\n', '[project]\nname = "x"\n',
              '[tool.plx]\nbundle-path = [".."]\nselect = ["N"]\n']
OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


class Campaign:
    def __init__(self, seed: int, top: Path) -> None:
        self.rng = random.Random(seed)
        self.top = top
        self.base = top / "base"
        self.proj = top / "work" / "proj"
        self.sub = self.proj / "sub"
        self.cache = top / "cache"
        self.env = {"OPENPLX_BUNDLE_PATH": str(self.base), "MODELS": str(self.sub), "NO_COLOR": "1"}
        self.clock = 0  # ns added to the recorder's clock (the user "coming back later")
        self.log: list[str] = []
        for rel, text in BASE.items():
            self.write(self.base / rel, text)
        self.write(self.proj / "Lib" / "config.openplx", LIB_CONFIG)
        self.write(self.proj / "Lib" / "Parts" / "Wheel.openplx", WHEELS[0])
        self.write(self.proj / "plx.toml", CONFIGS[0])
        self.write(self.sub / "a.openplx", TARGETS[5])
        self.write(self.sub / "b.openplx", TARGETS[0])
        self.write(self.sub / "m.obj", OBJ)
        self.write(self.top / "work" / "other" / "x.openplx", TARGETS[2])
        (self.top / "alt").mkdir()
        self.write(self.top / "alt" / "m.obj", OBJ)

    @staticmethod
    def write(path: Path, text: str) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)

    # ------------------------------------------------------------------ actions

    def _target(self) -> Path:
        return self.sub / self.rng.choice(["a.openplx", "b.openplx"])

    def edit(self) -> str:
        f = self._target()
        if f.is_symlink():
            f.unlink()
        self.write(f, self.rng.choice(TARGETS))
        return f"edit {f.name}"

    def edit_same_size_and_mtime(self) -> str:
        f = self._target()
        if f.is_symlink() or not f.exists():
            return self.edit()
        old = f.read_text(encoding="utf-8")
        same = [t for t in TARGETS if len(t.encode()) == len(old.encode()) and t != old]
        if not same:
            return self.edit()
        st = f.stat()
        self.write(f, self.rng.choice(same))
        os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))
        return f"edit {f.name} keeping size and mtime"

    def replace_by_rename(self) -> str:
        f = self._target()
        tmp = f.with_name(f".{f.name}.swp")
        self.write(tmp, self.rng.choice(TARGETS))
        os.replace(tmp, f)
        return f"save {f.name} by rename"

    def symlink(self) -> str:
        f = self._target()
        if f.is_symlink():
            f.unlink()
            self.write(f, self.rng.choice(TARGETS))
            return f"{f.name}: symlink back to a file"
        f.unlink(missing_ok=True)
        other = self.top / "work" / "other" / "x.openplx"
        if self.rng.random() < 0.5:
            self.write(other, self.rng.choice(TARGETS))
        f.symlink_to(other)
        return f"{f.name}: replaced by a symlink"

    def config(self) -> str:
        where = self.rng.choice(["proj", "sub", "subpy", "workpy", "toppy", "projsame"])
        if where == "proj":
            p, choices = self.proj / "plx.toml", CONFIGS
        elif where == "projsame":  # same size and mtime
            p = self.proj / "plx.toml"
            if p.exists():
                old = p.read_text()
                same = [c for c in CONFIGS if len(c) == len(old) and c != old]
                if same:
                    st = p.stat()
                    self.write(p, self.rng.choice(same))
                    os.utime(p, ns=(st.st_atime_ns, st.st_mtime_ns))
                    return "plx.toml edited keeping size and mtime"
            p, choices = self.proj / "plx.toml", CONFIGS
        elif where == "sub":
            p, choices = self.sub / "plx.toml", SUB_CONFIGS
        elif where == "subpy":
            p, choices = self.sub / "pyproject.toml", PYPROJECTS
        elif where == "workpy":
            p, choices = self.top / "work" / "pyproject.toml", PYPROJECTS
        else:
            p, choices = self.top / "pyproject.toml", PYPROJECTS
        if p.exists() and self.rng.random() < 0.5:
            p.unlink()
            return f"delete {p.relative_to(self.top)}"
        self.write(p, self.rng.choice(choices))
        return f"write {p.relative_to(self.top)}"

    def envvar(self) -> str:
        self.env["MODELS"] = self.rng.choice([str(self.sub), str(self.top / "alt"), str(self.top / "none"), None])
        return f"MODELS={self.env['MODELS']}"

    def obj(self) -> str:
        p = self.rng.choice([self.sub / "m.obj", self.top / "alt" / "m.obj"])
        if p.exists():
            p.unlink()
            return f"delete {p.relative_to(self.top)}"
        self.write(p, OBJ)
        return f"create {p.relative_to(self.top)}"

    def bundle(self) -> str:
        lib = self.proj / "Lib" / "Parts"
        choice = self.rng.random()
        if choice < 0.2:
            extra = lib / "Extra.openplx"
            if extra.exists():
                extra.unlink()
                return "delete Lib/Parts/Extra.openplx"
            self.write(extra, "Extra is Physics.Body:\n    mass: 1.0\n")
            return "add Lib/Parts/Extra.openplx"
        f = lib / "Wheel.openplx"
        old = f.read_text()
        if choice < 0.6:
            same = [w for w in WHEELS if len(w) == len(old) and w != old]
            if same:
                st = f.stat()
                self.write(f, self.rng.choice(same))
                os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))
                return "edit Lib/Parts/Wheel.openplx keeping size and mtime"
        self.write(f, self.rng.choice(WHEELS))
        return "edit Lib/Parts/Wheel.openplx"

    def save_during_run(self) -> str:
        """A cached run during which the file it lints is saved (right after plx read it)."""
        from plxtools.cache import reads

        f = self._target()
        if f.is_symlink():
            return self.edit()
        real = reads.read_bytes
        new = self.rng.choice(TARGETS)
        fired = []

        def read_then_save(path):
            data = real(path)
            if not fired and os.path.abspath(os.fspath(path)) == str(f):
                fired.append(1)
                self.write(f, new)
            return data

        reads.read_bytes = read_then_save
        try:
            self.run_cached(["lint", str(f.relative_to(self.proj))])
        finally:
            reads.read_bytes = real
        return f"{f.name} saved during a run"

    ACTIONS = ("edit", "edit_same_size_and_mtime", "replace_by_rename", "symlink", "config", "envvar", "obj",
               "bundle", "save_during_run")

    # ------------------------------------------------------------------ runs

    def run_cached(self, argv):
        return inproc.run(argv, self.proj, {**self.env, "PLX_CACHE_DIR": str(self.cache)})

    def run_fresh(self, argv):
        fresh = Path(tempfile.mkdtemp(dir=self.top, prefix="fresh-"))
        try:
            return inproc.run(argv, self.proj, {**self.env, "PLX_CACHE_DIR": str(fresh)})
        finally:
            shutil.rmtree(fresh, ignore_errors=True)

    def step(self) -> list[str]:
        """One action, then the comparisons; returns the differences found."""
        from plxtools.cache import reads

        if self.rng.random() < 0.3:  # the user comes back later: the stat fast path is trusted
            time.sleep(0.012)  # past the file system's clock tick: a later change gets a new ctime
            self.clock += 3 * 10**9
        self.log.append(getattr(self, self.rng.choice(self.ACTIONS))())
        diffs = []
        commands = [["lint", "sub/a.openplx"], ["lint", "-q", "sub/b.openplx"], ["lint", "sub/a.openplx", "sub/b.openplx"],
                    ["fmt", "--check", "sub/b.openplx"], ["lint", "--output-format", "json", "sub/b.openplx"]]
        real_time = reads.time.time_ns
        for argv in self.rng.sample(commands, 1):
            reads.time.time_ns = lambda: real_time() + self.clock
            try:
                runs = [("cached", self.run_cached(argv))]
                if self.rng.random() < 0.3:
                    runs.append(("replayed", self.run_cached(argv)))  # the entry just written, replayed
            finally:
                reads.time.time_ns = real_time
            fresh = self.run_fresh(argv)
            for name, got in runs:
                if got != fresh:
                    diffs.append(f"after {self.log[-3:]}: {name} {argv} gave {got!r}, fresh gave {fresh!r}")
        return diffs


def campaign(steps: int, seed: int = 0, top: Path | None = None) -> tuple[int, list[str]]:
    """Run `steps` steps; (steps run, differences)."""
    own = top is None
    top = Path(tempfile.mkdtemp(prefix="plx-campaign-")) if own else top
    try:
        c = Campaign(seed, top)
        for i in range(steps):
            diffs = c.step()
            if diffs:
                return i + 1, diffs
        return steps, []
    finally:
        if own:
            shutil.rmtree(top, ignore_errors=True)
