"""The scenario library: its folder, its scenarios and the question each answers."""

import os
from pathlib import Path

from mcrun.results import output
from mcrun.run.scenario.specs import ScenarioError

ENV_LIBRARY = "MCRUN_SCENARIOS"


def library_folder():
    """The folder of the scenario library.

    ``$MCRUN_SCENARIOS`` when set (an explicit choice wins), else the ``scenarios/`` folder
    shipped beside the package (the repository root for a source checkout or an editable
    install). Raises ScenarioError if neither is a folder.
    """
    env = os.environ.get(ENV_LIBRARY)
    if env:
        folder = Path(env)
        if not folder.is_dir():
            raise ScenarioError(f"{ENV_LIBRARY}={env}: not a folder of scenario files")
        return folder
    folder = Path(__file__).resolve().parents[3] / "scenarios"
    if folder.is_dir():
        return folder
    raise ScenarioError(
        f"no scenario library found: {folder} does not exist; set {ENV_LIBRARY} to the folder "
        "that holds the *.toml scenarios"
    )


# The question a scenario's text asks: one rule, with the run's recorded provenance.
question_of = output.question_in


def list_library(folder=None):
    """[(name, path, question)] of the ``*.toml`` files of ``folder`` (default: the library),
    sorted by name. The name is the file's stem; the question its ``[scenario] question``, else
    its ``# Question:`` line (``output.question_in``)."""
    folder = library_folder() if folder is None else Path(folder)
    entries = []
    for path in sorted(folder.glob("*.toml")):
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            text = ""
        entries.append((path.stem, path, question_of(text)))
    return entries


def find(name_or_path):
    """The path of a scenario: a file that exists, or the name of a library scenario
    (``"pga-driver"`` or ``"pga-driver.toml"``). ScenarioError if neither."""
    path = Path(name_or_path)
    if path.is_file():
        return path
    if path.parent == Path(".") and path.suffix in ("", ".toml"):
        try:
            folder = library_folder()
        except ScenarioError:
            folder = None
        if folder is not None:
            candidate = folder / (path.stem + ".toml")
            if candidate.is_file():
                return candidate
    if path.exists():
        raise ScenarioError(f"{name_or_path}: not a file")
    if path.is_symlink():  # (exists() follows it: a link to nothing, or a loop of links)
        raise ScenarioError(f"{name_or_path}: a link that leads to no file")
    raise ScenarioError(
        f"{name_or_path}: no such file, nor a scenario of the library (mcrun scenarios lists it)"
    )
