"""pytest plugin (entry point ``plx_scenarios``): pytest collects ``*.scenario.toml`` files and runs
each as one test through ``plx test``'s runner, so a model's scenarios sit beside its unit tests.

A failing scenario reports the same located lines as ``plx test`` (scenario line, expected and
measured value); an invalid scenario file fails its item with the A141 messages.  Nothing heavy
is imported until a scenario file is collected.
"""

from __future__ import annotations

from pathlib import Path

import pytest

SUFFIX = ".scenario.toml"


def pytest_addoption(parser) -> None:
    group = parser.getgroup("plx", "OpenPLX scenario files")
    group.addoption("--plx-bundle-path", action="append", default=[], metavar="DIR",
                    help="bundle folder for the models of *.scenario.toml files (repeatable)")
    group.addoption("--plx-no-scenarios", action="store_true", help="do not collect *.scenario.toml files")


def pytest_collect_file(file_path: Path, parent):
    if file_path.name.endswith(SUFFIX) and not parent.config.getoption("plx_no_scenarios"):
        return ScenarioFile.from_parent(parent, path=file_path)
    return None


class ScenarioFile(pytest.File):
    def collect(self):
        name = self.path.name[: -len(SUFFIX)]
        yield ScenarioItem.from_parent(self, name=name)


class ScenarioFailed(Exception):
    def __init__(self, result):
        super().__init__(result.status)
        self.result = result


class ScenarioItem(pytest.Item):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # no fixtures; an empty mapping keeps wrapper hooks that look for fixtures (pytest-lsp's) working
        self.funcargs: dict = {}

    def runtest(self) -> None:
        from importlib.util import find_spec

        missing = [m for m in ("numpy", "mujoco") if find_spec(m) is None]
        if missing:  # the `sim` extra is not installed: said plainly, before any work
            pytest.fail(f"scenario files need {' and '.join(missing)}, not installed: pip install 'plxtools[sim]' "
                        "(or '-p no:plx_scenarios' to leave them out)", pytrace=False)
        from plxtools.check.testrun import PASSED, run_scenario  # here: it needs numpy and MuJoCo

        result = run_scenario(self.path, bundle_path=self.config.getoption("plx_bundle_path"))
        self.user_properties.append(("simulated_time", result.simulated_time))
        if result.status != PASSED:
            raise ScenarioFailed(result)

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, ScenarioFailed):
            r = excinfo.value.result
            lines = [f"scenario {r.name} {r.status}:"]
            for d in r.diagnostics:
                lines.append(f"{d.file}:{d.span.start.line + 1}:{d.span.start.column + 1}: {d.code} {d.message}")
                if d.help:
                    lines.append(f"  help: {d.help}")
            return "\n".join(lines)
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self):
        return self.path, 0, f"scenario: {self.name}"
