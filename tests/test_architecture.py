"""The package keeps to its layer map (DESIGN.md section 1), read from the code itself with ``ast``.

Every import in ``vehdyn/`` -- at module top and inside functions alike (a function-level import
hides a cycle, it does not remove it), and ``importlib.import_module`` calls with a literal name --
is an edge from the importing module's unit (``vehdyn.<unit>``) to the imported one's. The units
stand in layers, bottom up, and in a rank within their layer:

    foundation    errors < units, _atomic < conventions, signals, piecewise_signal < params
    core          plotting < results < model < simulation < interconnect
    physics       mechanics, tire, road < components
    vehicles      handling, ride < full_vehicle
    controllers   driver, chassis
    procedures    procedures
    applications  scene < sweep
    interfaces    report < cli

An edge may only go down: to a lower layer, or within a layer to a lower rank. Units of the same
rank (handling and ride, driver and chassis, ...) import nothing of each other. So the units form
no cycle. ``vehdyn/__init__.py``, the curated API index, may import anything. Imports under
``if TYPE_CHECKING:`` never run and are not edges.

No private name crosses a unit: a module path with a component that starts with an underscore
below the unit (``vehdyn.tire._mf_numba``), a name that starts with one (``from m import _x``) or an
attribute of an imported module that does (``module._x``) is used only inside its own unit.
(``vehdyn._atomic`` is a unit of its own, private to the package as a whole.)
"""

from __future__ import annotations

import ast
import importlib
import pkgutil
from pathlib import Path

import pytest

import vehdyn

ROOT = Path(vehdyn.__file__).resolve().parent

LAYERS = {
    "foundation": [("errors",), ("units", "_atomic"), ("conventions", "signals", "piecewise_signal"), ("params",)],
    "core": [("plotting",), ("results",), ("symbolic",), ("model",), ("simulation",), ("interconnect",)],
    "physics": [("mechanics", "tire", "road"), ("components",)],
    "vehicles": [("handling", "ride"), ("full_vehicle",)],
    "controllers": [("driver", "chassis")],
    "procedures": [("procedures",)],
    "applications": [("scene", "optimal"), ("sweep",)],
    "interfaces": [("report",), ("cli",)],
}
LEVEL = {unit: (layer_index, rank)
         for layer_index, ranks in enumerate(LAYERS.values()) for rank, units in enumerate(ranks) for unit in units}
MAX_CODE_LINES = 800


def _module_name(path: Path, root: Path = ROOT) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _modules(root: Path = ROOT):
    return {_module_name(p, root): p for p in sorted(root.rglob("*.py"))}


def _type_checking_lines(tree) -> set[int]:
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            for child in node.body:
                lines.update(range(child.lineno, child.end_lineno + 1))
    return lines


def _resolve(module: str, is_package: bool, level: int, target: str | None) -> str:
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[:len(base) - (level - 1)]
    return ".".join(base + ([target] if target else []))


def _edges(root: Path = ROOT):
    """(importing module, imported module, names taken, line) for every internal import."""
    modules = _modules(root)
    edges = []
    for module, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        hidden = _type_checking_lines(tree)
        is_package = path.name == "__init__.py"
        aliases = {}
        for node in ast.walk(tree):
            if getattr(node, "lineno", None) in hidden:
                continue
            if isinstance(node, ast.ImportFrom):
                target = _resolve(module, is_package, node.level, node.module) if node.level else (node.module or "")
                if not target.startswith("vehdyn"):
                    continue
                for alias in node.names:
                    if f"{target}.{alias.name}" in modules:
                        edges.append((module, f"{target}.{alias.name}", [], node.lineno))
                        aliases[alias.asname or alias.name] = f"{target}.{alias.name}"
                    else:
                        edges.append((module, target, [alias.name], node.lineno))
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.startswith("vehdyn"):
                        edges.append((module, alias.name, [], node.lineno))
                        aliases[alias.asname or alias.name.split(".")[0]] = alias.asname and alias.name or "vehdyn"
            elif isinstance(node, ast.Call) and ast.unparse(node.func).endswith("import_module") and node.args \
                    and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str):
                name = node.args[0].value
                if name.startswith("."):
                    level = len(name) - len(name.lstrip("."))
                    name = _resolve(module, is_package, level, name.lstrip(".") or None)
                if name.startswith("vehdyn"):
                    edges.append((module, name, [], node.lineno))
        for node in ast.walk(tree):  # module._private across units
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.attr.startswith("_") \
                    and not node.attr.startswith("__") and node.value.id in aliases:
                edges.append((module, aliases[node.value.id], [node.attr], node.lineno))
    return edges


EDGES = _edges()


def test_every_unit_has_a_place_on_the_map():
    units = {_unit(m) for m in _modules()} - {""}
    assert sorted(units - set(LEVEL)) == []


def test_no_import_goes_up_the_layer_map():
    wrong = []
    for source, target, names, line in EDGES:
        a, b = _unit(source), _unit(target)
        if not a or not b or a == b:
            continue
        if not LEVEL[b] < LEVEL[a]:
            wrong.append(f"{source}:{line} imports {target} {names or ''} "
                         f"({a} at {LEVEL[a]}, {b} at {LEVEL[b]} (layer, rank))")
    assert wrong == []


def test_no_private_name_crosses_a_unit():
    wrong = []
    for source, target, names, line in EDGES:
        a, b = _unit(source), _unit(target)
        if not b or a == b:
            continue
        private_path = any(part.startswith("_") for part in target.split(".")[2:])
        private_names = [n for n in names if n.startswith("_") and not n.startswith("__")]
        if private_path or private_names:
            wrong.append(f"{source}:{line} uses {target} {private_names}")
    assert wrong == []


def test_units_form_no_cycle():
    graph: dict[str, set[str]] = {}
    for source, target, _, _ in EDGES:
        a, b = _unit(source), _unit(target)
        if a and b and a != b:
            graph.setdefault(a, set()).add(b)
    seen, stack = set(), []

    def visit(unit):
        if unit in stack:
            pytest.fail("cycle: " + " -> ".join(stack[stack.index(unit):] + [unit]))
        if unit in seen:
            return
        stack.append(unit)
        for nxt in sorted(graph.get(unit, ())):
            visit(nxt)
        stack.pop()
        seen.add(unit)

    for unit in sorted(graph):
        visit(unit)


def test_no_attribute_shadows_its_submodule():
    wrong = []
    for info in pkgutil.walk_packages(vehdyn.__path__, "vehdyn."):
        if not info.ispkg:
            continue
        package = importlib.import_module(info.name)
        for sub in pkgutil.iter_modules(package.__path__):
            full = f"{info.name}.{sub.name}"
            importlib.import_module(full)
            value = package.__dict__.get(sub.name)
            if value is not None and getattr(value, "__name__", None) != full:
                wrong.append(f"{info.name}.{sub.name} is {value!r}, not the module {full}")
    top = [name for name in ("simulate", "sweep", "scene") if getattr(vehdyn, name, None) is not None
           and (ROOT / name).is_dir() and getattr(getattr(vehdyn, name), "__name__", "") != f"vehdyn.{name}"]
    assert wrong == [] and top == []


def _code_lines(path: Path) -> int:
    """Lines of code without docstrings, comments and blank lines."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    doc = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            doc.update(range(body[0].lineno, body[0].end_lineno + 1))
    count = 0
    for k, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        text = line.strip()
        if text and not text.startswith("#") and k not in doc:
            count += 1
    return count


def test_no_module_is_a_thousand_line_smell():
    big = {m: _code_lines(p) for m, p in _modules().items()}
    assert {m: n for m, n in big.items() if n > MAX_CODE_LINES} == {}


def test_the_reader_finds_hidden_edges(tmp_path):
    """The reader itself, on a small package: a function-level upward import, a private module, a
    private name, a private attribute of an imported module, a relative import and import_module."""
    pkg = tmp_path / "vehdyn"
    for sub in ("tire", "handling", "scene"):
        (pkg / sub).mkdir(parents=True)
        (pkg / sub / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "tire" / "_kernels.py").write_text("def _forces():\n    return 0\n")
    (pkg / "handling" / "model.py").write_text(
        "import vehdyn.tire._kernels as k\n"
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n    from vehdyn.scene import plan\n"
        "def f():\n    from ..scene import run\n    from vehdyn.tire._kernels import _forces\n"
        "    import importlib\n    importlib.import_module('vehdyn.scene')\n    return k._forces\n")
    edges = {(s, t, tuple(n)) for s, t, n, _ in _edges(pkg)}
    assert ("vehdyn.handling.model", "vehdyn.scene", ("run",)) in edges          # relative, in a function
    assert ("vehdyn.handling.model", "vehdyn.scene", ()) in edges                # import_module
    assert ("vehdyn.handling.model", "vehdyn.tire._kernels", ("_forces",)) in edges   # private name and attribute
    assert not any(n == ("plan",) for _, _, n in edges)                          # TYPE_CHECKING: not an edge
