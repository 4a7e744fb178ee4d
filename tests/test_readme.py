"""The documentation's example outputs are what the code prints today: every fenced block of
README.md and of the pages under docs/ whose first line is a ``$ mcrun ...`` line is run (in a
folder where ``scenarios/`` is the library and ``tests/data/`` the tests' data, so that the
default output folders land there) and its lines are compared with what it prints.

In an example, ``...`` stands for any text within a line, and a line of ``...`` alone for any
number of lines; the time and rate of a run (a number before `` s`` or ``shots/s``) are the
machine's and are not compared. Everything else, every digit of a result included, is.

A block may hold several commands, each a ``$ mcrun ...`` line followed by what it prints; they
run in turn in the same folder (a run, then its pictures). A block fenced as ```` ```text ````
is shown but not run: the way to show a command too slow for the tests. The same commands shown
in more than one place (a README example that a page of docs/ shows in full) run once, and
every copy is compared with what they printed.
"""

import re
import shlex
from pathlib import Path

import pytest

from mcrun.cli import main

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
PAGES = [README, *sorted((ROOT / "docs").rglob("*.md"))]
PROMPT = "$ mcrun "
# A timing: a number (with thousands' commas) before " s" or " shots/s" (the machine's).
TIMING = re.compile(r"\d[\d,]*(?:\.\d+)?(?= s\b| shots/s)")
# What each block's commands printed, by the commands: (exit code, output) of each.
PRINTED = {}


def blocks(page):
    """[(line number, [(argv after ``mcrun``, expected lines)])] of a page's example blocks."""
    found = []
    lines = page.read_text(encoding="utf-8").splitlines()
    k = 0
    while k < len(lines):
        if not (lines[k].startswith("```") and k + 1 < len(lines)):
            k += 1
            continue
        end = next(j for j in range(k + 1, len(lines)) if lines[j].startswith("```"))
        if lines[k + 1].startswith(PROMPT) and lines[k][3:].strip() != "text":
            steps = []
            for line in lines[k + 1 : end]:
                if line.startswith(PROMPT):
                    steps.append((shlex.split(line[len(PROMPT) :]), []))
                else:
                    steps[-1][1].append(line)
            found.append((k + 2, steps))
        k = end + 1
    return found


def examples():
    """pytest params of every page's example blocks, with ids like ``docs/putting.md:42``."""
    return [
        pytest.param(steps, id=f"{page.relative_to(ROOT).as_posix()}:{line}")
        for page in PAGES
        for line, steps in blocks(page)
    ]


def pattern(expected):
    """A regular expression of the example's lines: ``...`` any text, ``...`` alone any lines,
    the timings any number."""
    parts = []
    for line in expected:
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
            continue
        pieces = [TIMING.sub("#", piece) for piece in line.split("...")]
        parts.append("[^\n]*".join(re.escape(p).replace("\\#", "#") for p in pieces) + "\n")
    return re.compile("".join(parts).replace("#", r"\d[\d,]*(?:\.\d+)?"))


def run_commands(steps, folder, capsys):
    """Each command of a block run in turn in ``folder``: [(exit code, output)]."""
    (folder / "scenarios").symlink_to(ROOT / "scenarios")
    (folder / "tests").mkdir()
    (folder / "tests" / "data").symlink_to(ROOT / "tests" / "data")
    printed = []
    for argv, _ in steps:
        code = main(argv)
        printed.append((code, capsys.readouterr().out))
        if code != 0:
            break
    return printed


def test_the_readme_and_the_docs_have_examples():
    assert len(blocks(README)) >= 5
    assert sum(len(blocks(page)) for page in PAGES[1:]) >= 10
    assert len(scenario_blocks()) >= 1


def test_a_block_fenced_as_text_is_not_run(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("```text\n$ mcrun play pga-tour-bag par4-tee-shot\n...\n```\n\n"
                    "```\n$ mcrun turfs\n...\n$ mcrun models\n...\n```\n")  # fmt: skip
    assert blocks(page) == [(7, [(["turfs"], ["..."]), (["models"], ["..."])])]


@pytest.mark.parametrize("steps", examples())
def test_an_example_prints_what_it_shows(steps, request, tmp_path, monkeypatch, capsys):
    where = request.node.callspec.id
    key = tuple(tuple(argv) for argv, _ in steps)
    if key not in PRINTED:
        monkeypatch.chdir(tmp_path)
        PRINTED[key] = run_commands(steps, tmp_path, capsys)
    for (argv, expected), (code, out) in zip(steps, PRINTED[key], strict=False):
        command = f"mcrun {' '.join(argv)}"
        assert code == 0, f"{where}: {command} exited {code}"
        assert pattern(expected).fullmatch(out), f"{where}: {command} printed:\n{out}"
    assert len(PRINTED[key]) == len(steps)


def scenario_blocks():
    """(page:line, text) of every ```toml block of the pages that is a whole scenario (it has a
    ``[scenario]`` table; the others are parts of one)."""
    found = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for match in re.finditer(r"^```toml\n(.*?)^```", text, re.S | re.M):
            if re.search(r"^\[scenario\]", match[1], re.M):
                line = text.count("\n", 0, match.start()) + 1
                found.append(pytest.param(match[1], id=f"{page.relative_to(ROOT)}:{line}"))
    return found


@pytest.mark.parametrize("text", scenario_blocks())
def test_a_scenario_the_docs_show_validates(text, tmp_path, capsys):
    """A scenario written out in the documentation loads as it is (``mcrun validate``)."""
    path = tmp_path / "shown.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["validate", str(path)]) == 0, capsys.readouterr().err
