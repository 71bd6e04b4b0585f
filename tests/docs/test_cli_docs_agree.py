"""Issue 32.7: the docs' option tables and exit-code table say what `plx ... --help` and the real
commands do. Each command section of docs/cli.md (and the flag table of docs/check.md) lists
exactly the options of its `--help`; the exit-code table gives each command the codes its help
names, and a file with syntax errors makes `plx fmt` exit with the code the table says."""

from __future__ import annotations

import re

import pytest

from tests.conftest import REPO, run_plx

COMMANDS = ["lint", "fmt", "check", "test", "lsp", "rule", "bundles", "migrate"]
OPTION = re.compile(r"^  (?:(-\w)(?: \S+)?, )?(--[\w-]+)|^  (-\w)\b", re.M)
ROW_FLAGS = re.compile(r"`(--?[\w-]+)")


def help_text(cmd: str) -> str:
    r = run_plx(cmd, "--help", env={"COLUMNS": "100"})
    assert r.returncode == 0, r.stderr
    return r.stdout


def help_options(cmd: str) -> set[str]:
    text = help_text(cmd)
    text = text[text.index("options:"):]
    found = set()
    for m in OPTION.finditer(text):
        found.update(x for x in m.groups() if x)
    return found - {"-h", "--help"}


def table_options(section: str) -> set[str]:
    """Options named in the first cell of the rows of the tables in `section` of a page."""
    found = set()
    for line in section.splitlines():
        if line.startswith("| `"):
            found.update(ROW_FLAGS.findall(line.split("|")[1]))
    return found


def cli_section(cmd: str) -> str:
    page = (REPO / "docs" / "cli.md").read_text(encoding="utf-8")
    start = page.index(f"\n## plx {cmd}")
    end = page.find("\n## ", start + 1)
    return page[start: end if end != -1 else None]


@pytest.mark.parametrize("cmd", [c for c in COMMANDS if c not in ("lsp", "rule", "bundles")])
def test_cli_page_option_table_matches_help(cmd):
    assert table_options(cli_section(cmd)) == help_options(cmd)


def test_check_page_flag_table_matches_help():
    page = (REPO / "docs" / "check.md").read_text(encoding="utf-8")
    start = page.index("| flag | meaning |")
    end = page.index("\n\n", start)
    assert table_options(page[start:end]) == help_options("check")


def exit_table() -> dict[str, dict[int, str]]:
    page = (REPO / "docs" / "cli.md").read_text(encoding="utf-8")
    start = page.index("**Exit codes**")
    rows = {}
    for line in page[start: page.index("\n\n", page.index("| command |", start))].splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 4 and cells[0].startswith("`"):
            for name in re.findall(r"`(\w+)`", cells[0]):
                rows[name] = {0: cells[1], 1: cells[2], 2: cells[3]}
    return rows


def test_exit_code_table_has_every_command_and_the_codes_its_help_names():
    rows = exit_table()
    assert set(rows) == set(COMMANDS)
    for cmd in COMMANDS:
        desc = help_text(cmd).split("positional arguments:")[0].split("options:")[0]
        sentence = re.search(r"Exit .*", " ".join(desc.split()))
        if sentence is None:
            continue
        named = {int(n) for n in re.findall(r"\b([012])\b", sentence.group(0))}
        for code in (1, 2):
            assert (rows[cmd][code] != "-") == (code in named), (cmd, code, rows[cmd][code])


def test_fmt_exit_code_on_a_syntax_error_is_the_documented_one(tmp_path):
    f = tmp_path / "broken.openplx"
    f.write_text("A is Physics3D.System:\n    x: (\n", encoding="utf-8")
    r = run_plx("fmt", str(f))
    row = exit_table()["fmt"]
    code = next(c for c, text in row.items() if "syntax error" in text)
    assert r.returncode == code, r.stdout + r.stderr
    assert f.read_text(encoding="utf-8") == "A is Physics3D.System:\n    x: (\n"  # refused, untouched


def test_docs_site_url_is_the_projects():
    import tomllib

    from plxtools import DOCS_BASE_URL

    site = re.search(r"^site_url:\s*(\S+)", (REPO / "mkdocs.yml").read_text(encoding="utf-8"), re.M).group(1)
    project = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))["project"]["urls"]
    assert site == project["Documentation"] == DOCS_BASE_URL
