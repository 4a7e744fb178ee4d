"""The layers of the package (docs/code-layout.md): every import of a module of mcrun goes down
the layers, never up and never round in a circle, including the imports inside functions."""

import ast
from pathlib import Path

import mcrun

PACKAGE = Path(mcrun.__file__).parent

# Lowest first. A module may import modules of its own layer or of the layers below.
LAYERS = (
    (
        "mcrun.errors",
        "mcrun.status",
        "mcrun.units",
        "mcrun.trajectory",
        "mcrun.exits",
        "mcrun.executor",
    ),
    ("mcrun.physics",),
    ("mcrun.ground",),
    ("mcrun.hole",),
    ("mcrun.strokes",),
    ("mcrun.engine",),
    ("mcrun.quantities",),
    ("mcrun.api", "mcrun.putting"),
    ("mcrun.results",),
    ("mcrun.run",),
    ("mcrun.play",),
    ("mcrun.report", "mcrun.paper", "mcrun.calibrate"),
    ("mcrun.cli",),
)


def modules():
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = path
    return found


def imports(path, known):
    """The modules of mcrun that the file at ``path`` imports, anywhere in it."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mcrun"):
            for alias in node.names:
                name = f"{node.module}.{alias.name}"
                found.add(name if name in known else node.module)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("mcrun."))
    return {name for name in found if name in known}


def layer(name):
    for k, prefixes in enumerate(LAYERS):
        if any(name == p or name.startswith(p + ".") for p in prefixes):
            return k
    return None


def test_every_module_has_a_layer():
    assert [name for name in modules() if name != "mcrun" and layer(name) is None] == []


def test_no_module_imports_one_above_it():
    known = modules()
    upward = [
        (name, other)
        for name, path in known.items()
        if name != "mcrun"  # the package's public face imports the API
        for other in imports(path, known)
        if other != "mcrun" and layer(other) > layer(name)
    ]
    assert upward == []


def test_no_import_circles():
    known = modules()
    graph = {name: imports(path, known) - {name, "mcrun"} for name, path in known.items()}
    state = {}

    def visit(name, path):
        state[name] = "open"
        for other in graph[name]:
            assert state.get(other) != "open", " -> ".join([*path, other])
            if other not in state:
                visit(other, [*path, other])
        state[name] = "done"

    for name in graph:
        if name not in state:
            visit(name, [name])


def test_the_layout_page_names_every_module():
    """docs/code-layout.md's table names every module of the package (and of the benchmark
    suite's figures), so that a newcomer finds each in it: ``name`` or ``name.py`` in its
    layer's row, ``dir/`` for a package."""
    page = (PACKAGE.parent / "docs" / "code-layout.md").read_text(encoding="utf-8")
    named = {word.removesuffix(".py").rstrip("/") for word in page.split("`")[1::2]}
    figures = PACKAGE.parent / "benchmarks" / "figures"
    paths = [*PACKAGE.rglob("*.py"), *figures.glob("*.py")]
    missing = sorted(
        str(path.relative_to(PACKAGE.parent))
        for path in paths
        if path.stem != "__init__" and path.stem not in named
    )
    assert missing == []
