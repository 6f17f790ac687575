"""The package's imports run one way: foundation -> robot -> errormodel -> linear -> diagnose -> allocate
-> montecarlo -> verify -> report -> cli. Walks every module's imports (top-level and inside functions)."""

import ast
from pathlib import Path

import pytest

import tolalloc

PKG = Path(tolalloc.__file__).parent
#: Stages in pipeline order; a module may import only from its own stage or an earlier one.
ORDER = ["foundation", "robot", "errormodel", "linear", "diagnose", "calibration", "allocate", "montecarlo",
         "verify", "report", "cli"]
FOUNDATION = {"exceptions", "engine", "units"}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(PKG.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def stage(module: str) -> str:
    parts = module.split(".")
    if len(parts) == 1 or parts[1] == "__main__":  # the pipeline API and the entry point, above everything
        return "api"
    return "foundation" if parts[1] in FOUNDATION else parts[1]


def imports_of(path: Path) -> set[str]:
    """Every tolalloc module imported by ``path`` (absolute or relative, at any depth in the file)."""
    mod = module_name(path)
    base = mod.split(".") if path.name == "__init__.py" else mod.split(".")[:-1]
    out = set()
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):  # imports only for type checkers do not run
        if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING":
            node.body = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name.startswith("tolalloc")}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                target = ".".join(base[: len(base) - node.level + 1] + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("tolalloc"):
                out.add(target)
                out |= {f"{target}.{a.name}" for a in node.names
                        if (PKG.parent / f"{target}.{a.name}".replace(".", "/")).with_suffix(".py").exists()}
    return out


MODULES = {module_name(p): p for p in PKG.rglob("*.py")}
EDGES = {m: {i for i in imports_of(p) if i != m} for m, p in MODULES.items()}


@pytest.mark.parametrize("module", sorted(MODULES))
def test_imports_run_one_way(module):
    src = stage(module)
    if src == "api":
        return  # the pipeline API and the entry point sit above every stage
    bad = []
    for target in sorted(EDGES[module]):
        dst = stage(target)
        assert dst != "api", f"{module} imports the top-level package ({target}); import the stage instead"
        if ORDER.index(dst) > ORDER.index(src):
            bad.append(f"{module} ({src}) -> {target} ({dst})")
    assert not bad, "imports against the pipeline order: " + "; ".join(bad)


def find_cycle(edges: dict[str, set[str]]) -> list[str] | None:
    """A cycle in ``edges`` (depth-first search) or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m):
        state[m] = 1
        stack.append(m)
        for t in sorted(edges.get(m, ())):
            if t not in edges:
                continue
            if state.get(t) == 1:
                return stack[stack.index(t):] + [t]
            if t not in state and (c := visit(t)):
                return c
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(edges):
        if m not in state and (c := visit(m)):
            return c
    return None


def test_no_import_cycle_between_modules():
    """Module graph, lazy imports inside functions included; a package's ``__init__`` only re-exports."""
    edges = {m: {t for t in ts if t in MODULES and MODULES[t].name != "__init__.py"}
             for m, ts in EDGES.items() if MODULES[m].name != "__init__.py"}
    cycle = find_cycle(edges)
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_no_import_cycle_between_stages():
    stages = {}
    for m, ts in EDGES.items():
        stages.setdefault(stage(m), set()).update(stage(t) for t in ts if stage(t) != stage(m))
    stages.pop("api", None)
    for v in stages.values():
        v.discard("api")
    cycle = find_cycle(stages)
    assert cycle is None, "import cycle between sub-packages: " + " -> ".join(cycle or [])


def test_cycle_finder_on_known_graphs():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"x": {"y"}, "y": {"y2"}, "y2": {"y"}}) == ["y", "y2", "y"]
