"""The house rules a newcomer relies on, checked on the source tree: packages small enough to
see their structure, modules of one idea, functions that fit on a screen, no import circle."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "kitchen_tamp"

MAX_MODULES_PER_PACKAGE = 15
MAX_MODULE_LINES = 400
MAX_FUNCTION_LINES = 80
MAX_PARAMETERS = 7


def _modules() -> Iterator[Path]:
    return (path for path in sorted(PACKAGE.rglob("*.py")) if "__pycache__" not in path.parts)


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_numba_kernel(function: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Compiled kernels take their arrays explicitly; the size rules exempt them."""
    return any("jit" in ast.unparse(decorator) for decorator in function.decorator_list)


def _functions(tree: ast.AST) -> Iterator[ast.FunctionDef | ast.AsyncFunctionDef]:
    return (node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef))


def _parameter_count(function: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    arguments = function.args
    names = [*arguments.posonlyargs, *arguments.args, *arguments.kwonlyargs]
    count = len(names) + (arguments.vararg is not None) + (arguments.kwarg is not None)
    return count - (1 if names and names[0].arg in ("self", "cls") else 0)


def test_no_package_level_holds_more_than_fifteen_modules() -> None:
    crowded = []
    for folder in [PACKAGE, *(p for p in PACKAGE.rglob("*") if p.is_dir() and p.name != "__pycache__")]:
        modules = [p for p in folder.glob("*.py") if p.name not in ("__init__.py", "__main__.py")]
        if len(modules) > MAX_MODULES_PER_PACKAGE:
            crowded.append(f"{folder.relative_to(PACKAGE)} ({len(modules)})")
    assert not crowded, f"package levels with more than {MAX_MODULES_PER_PACKAGE} modules: {crowded}"


def test_no_module_is_over_four_hundred_lines() -> None:
    long = [f"{p.relative_to(PACKAGE)} ({n})" for p in _modules()
            if (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES]
    assert not long, f"modules over {MAX_MODULE_LINES} lines: {long}"


def test_functions_outside_numba_kernels_are_short_and_take_few_parameters() -> None:
    offenders = []
    for path in _modules():
        for function in _functions(ast.parse(path.read_text())):
            if _is_numba_kernel(function):
                continue
            lines = (function.end_lineno or function.lineno) - function.lineno + 1
            parameters = _parameter_count(function)
            if lines > MAX_FUNCTION_LINES or parameters > MAX_PARAMETERS:
                offenders.append(f"{path.relative_to(PACKAGE)}:{function.lineno} {function.name} "
                                 f"({lines} lines, {parameters} parameters)")
    assert not offenders, offenders


def _imports_at_load(tree: ast.Module, known: set[str]) -> set[str]:
    """Our modules a module imports when it is loaded (not inside functions, nor for type checking)."""
    found: set[str] = set()

    def visit(body: list[ast.stmt]) -> None:
        for node in body:
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                continue
            if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
                continue
            if isinstance(node, ast.Import):
                found.update(alias.name for alias in node.names if alias.name in known)
            elif isinstance(node, ast.ImportFrom) and node.module:
                for alias in node.names:
                    full = f"{node.module}.{alias.name}"
                    found.add(full if full in known else node.module)
            for field in ("body", "orelse", "finalbody", "handlers"):
                inner = getattr(node, field, None)
                if isinstance(inner, list):
                    visit(inner)

    visit(tree.body)
    return found & known


def test_no_import_circle() -> None:
    paths = {_module_name(path): path for path in _modules()}
    known = set(paths)
    graph = {name: _imports_at_load(ast.parse(path.read_text()), known) for name, path in paths.items()}
    circles: list[list[str]] = []
    state: dict[str, int] = {}  # 1: on the current path, 2: done

    def walk(name: str, trail: list[str]) -> None:
        state[name] = 1
        for target in sorted(graph[name]):
            if state.get(target) == 1:
                circles.append([*trail[trail.index(target):], target])
            elif target not in state:
                walk(target, [*trail, target])
        state[name] = 2

    for name in sorted(graph):
        if name not in state:
            walk(name, [name])
    assert not circles, [" -> ".join(circle) for circle in circles]


def test_type_checking_is_typings() -> None:
    shadowed = [str(p.relative_to(PACKAGE)) for p in _modules() if "TYPE_CHECKING = False" in p.read_text()]
    assert not shadowed, f"use typing.TYPE_CHECKING, not a constant of our own: {shadowed}"
