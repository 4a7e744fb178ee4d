"""The README's example outputs are what the code prints today: every fenced block that starts
with a ``$ mcrun ...`` line is run (in a folder where ``scenarios/`` is the library, so that the
default output folders land there) and its lines are compared with what it prints.

In an example, ``...`` stands for any text within a line, and a line of ``...`` alone for any
number of lines; the time and rate of a run (a number before `` s`` or ``shots/s``) are the
machine's and are not compared. Everything else, every digit of a result included, is.
"""

import re
import shlex
from pathlib import Path

import pytest

from mcrun.cli import main

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
# A timing: a number (with thousands' commas) before " s" or " shots/s" (the machine's).
TIMING = re.compile(r"\d[\d,]*(?:\.\d+)?(?= s\b| shots/s)")


def examples():
    """[(line number, argv after ``mcrun``, expected lines)] of the README's example blocks."""
    found = []
    lines = README.read_text(encoding="utf-8").splitlines()
    for k, line in enumerate(lines):
        if line.startswith("$ mcrun ") and k > 0 and lines[k - 1].startswith("```"):
            end = next(j for j in range(k + 1, len(lines)) if lines[j].startswith("```"))
            found.append((k + 1, shlex.split(line[len("$ mcrun ") :]), lines[k + 1 : end]))
    return found


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


def test_the_readme_has_examples():
    assert len(examples()) >= 5


@pytest.mark.parametrize("line, argv, expected", examples(), ids=lambda v: str(v)[:40])
def test_a_readme_example_prints_what_it_shows(line, argv, expected, tmp_path, monkeypatch,
                                               capsys):  # fmt: skip
    (tmp_path / "scenarios").symlink_to(ROOT / "scenarios")
    monkeypatch.chdir(tmp_path)
    code = main(argv)
    out = capsys.readouterr().out
    assert code == 0, f"README line {line}: mcrun {' '.join(argv)} exited {code}"
    assert pattern(expected).fullmatch(out), (
        f"README line {line}: mcrun {' '.join(argv)} printed:\n{out}"
    )
