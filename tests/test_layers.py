"""The package reads like the pipeline: every import (function-level ones included) runs down the layers.

docs/architecture.md shows the same table with each package's job; an import that runs backwards, or a
module that belongs to no layer, fails here with the edge that broke the rule."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "morsec"
FACADE = PACKAGE.parent / "morse"  # MORSE's names for users' files: an edge over morsec, never imported by it

# the order data flows in; a module may import its own layer and the layers before it
LAYERS = [
    ("foundation", ("morsec", "morsec.errors", "morsec.constants", "morsec.resources")),
    ("components", ("morsec.kits", "morsec.component", "morsec.modifiers")),
    ("middlewares", ("morsec.middleware",)),
    ("scene IR", ("morsec.scene",)),
    ("front ends", ("morsec.frontends",)),
    ("compiler", ("morsec.compiler",)),
    ("runtime", ("morsec.runtime",)),
    ("application", ("morsec.app", "morsec.testing", "morsec.pymorse_compat", "morsec.client")),
    ("command line", ("morsec.cli",)),
    ("edges", ("morsec.builder", "morsec.__main__", "morse")),
]


def layer_of(module: str) -> int | None:
    best, best_len = None, -1
    for index, (_, prefixes) in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best_len:
                best, best_len = index, len(prefix)
    return best


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imported(path: Path, module: str) -> set[str]:
    """Every morsec module `path` imports, wherever the import statement stands."""
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(up + ([base] if base else []))
            found.add(base)
    return {name for name in found if name.split(".")[0] in ("morsec", "morse")}


MODULES = sorted(PACKAGE.rglob("*.py")) + sorted(FACADE.rglob("*.py"))


def test_every_module_has_a_layer():
    orphans = [module_name(p) for p in MODULES if layer_of(module_name(p)) is None]
    assert not orphans, f"modules in no layer (add them to LAYERS and docs/architecture.md): {orphans}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: module_name(p))
def test_imports_run_down_the_pipeline(path):
    module = module_name(path)
    own = layer_of(module)
    backwards = []
    for target in sorted(imported(path, module)):
        if path.name == "__init__.py" and target.startswith(module + "."):
            continue  # a package re-exporting its own modules
        there = layer_of(target)
        if there is not None and own is not None and there > own:
            backwards.append(f"{module} ({LAYERS[own][0]}) imports {target} ({LAYERS[there][0]})")
    assert not backwards, "imports that run backwards:\n" + "\n".join(backwards)


def test_morsec_never_imports_the_morse_facade():
    """`morse` is MORSE users' name for morsec; morsec's own code (morsec.builder included) does not use it."""
    users = [f"{module_name(p)} imports {target}" for p in sorted(PACKAGE.rglob("*.py"))
             for target in sorted(imported(p, module_name(p))) if target.split(".")[0] == "morse"]
    assert not users, "morsec modules importing the morse façade:\n" + "\n".join(users)


def test_the_layer_check_sees_a_backward_import(tmp_path):
    """The check itself: a runtime module importing the compiler is allowed, the reverse is not."""
    assert layer_of("morsec.runtime.simulation") > layer_of("morsec.compiler.build")
    assert layer_of("morsec.kits.geometry") < layer_of("morsec.scene.models")
    fake = tmp_path / "probe.py"
    fake.write_text("def f():\n    from morsec.cli import app\n")
    assert imported(fake, "morsec.compiler.probe") == {"morsec.cli"}


def test_architecture_page_names_every_package_of_the_table():
    page = (PACKAGE.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    missing = [prefix for _, prefixes in LAYERS for prefix in prefixes if f"`{prefix}`" not in page]
    assert not missing, f"docs/architecture.md does not describe: {missing}"


def test_component_folders_import_nothing_after_the_components_layer():
    """A component folder (component.py and its helper modules) uses the contract, the kits and the
    modifiers: the runtime, the compiler and the rest come after it."""
    components = layer_of("morsec.component")
    backwards = []
    for path in sorted((PACKAGE.parent / "components").rglob("*.py")):
        for target in sorted(imported(path, "morsec_components.folder.component")):
            there = layer_of(target)
            if there is not None and there > components:
                backwards.append(f"{path.relative_to(PACKAGE.parent)} imports {target} ({LAYERS[there][0]})")
    assert not backwards, "component folders importing past the components layer:\n" + "\n".join(backwards)


def import_graph(paths) -> dict[str, set[str]]:
    """module -> the modules of `paths` it imports (a name imported from a module counts as that module; a
    package's __init__ importing its own modules is a re-export, not an edge)."""
    names = {module_name(p): p for p in paths}
    graph = {}
    for module, path in names.items():
        edges = set()
        for target in imported(path, module):
            while target and target not in names:
                target = target.rpartition(".")[0]
            if target and target != module and not (path.name == "__init__.py" and target.startswith(module + ".")):
                edges.add(target)
        graph[module] = edges
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import circles: each strongly connected set of two modules or more, sorted."""
    found, order, low, stack, counter = [], {}, {}, [], [0]

    def visit(v):
        order[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        for w in sorted(graph.get(v, ())):
            if w not in order:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], order[w])
        if low[v] == order[v]:
            part = []
            while True:
                w = stack.pop()
                part.append(w)
                if w == v:
                    break
            if len(part) > 1:
                found.append(sorted(part))

    for v in sorted(graph):
        if v not in order:
            visit(v)
    return found


def test_no_module_imports_itself_round_a_circle():
    """Imports run one way inside a layer too: two modules that import each other (even inside a function)
    are one module split in two, or a piece in the wrong one."""
    circles = cycles(import_graph(sorted(PACKAGE.rglob("*.py"))))
    assert not circles, "import circles:\n" + "\n".join(" <-> ".join(c) for c in circles)


def test_the_circle_check_sees_a_circle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []
