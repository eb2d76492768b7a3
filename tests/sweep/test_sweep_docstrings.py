"""The contract of ``vehdyn.sweep``: every public callable documents every parameter and what it
returns (numpydoc, read by numpydoc's own parser); the entry points have examples and references."""

import importlib
import inspect
import pkgutil

import pytest

import vehdyn.sweep

docscrape = pytest.importorskip("numpydoc.docscrape")

MODULES = ["vehdyn.sweep"] + [f"vehdyn.sweep.{m.name}" for m in pkgutil.iter_modules(vehdyn.sweep.__path__)]


def _public_callables():
    seen = set()
    for module_name in MODULES:
        module = importlib.import_module(module_name)
        for name in module.__all__:
            obj = getattr(module, name)
            if not callable(obj) or id(obj) in seen:
                continue
            seen.add(id(obj))
            yield f"{module_name}.{name}", obj
            if inspect.isclass(obj):
                for attr, member in vars(obj).items():
                    if attr.startswith("_") and attr != "__call__":
                        continue
                    function = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
                    if inspect.isfunction(function):
                        yield f"{module_name}.{name}.{attr}", function


CALLABLES = dict(_public_callables())


def _documented(doc, section) -> set:
    return {n.strip() for p in doc[section] for n in p.name.split(",")}


@pytest.mark.parametrize("path", sorted(CALLABLES))
def test_every_parameter_and_the_return_value_are_documented(path):
    obj = CALLABLES[path]
    assert inspect.getdoc(obj), f"{path} has no docstring"
    if inspect.isclass(obj):
        doc = docscrape.ClassDoc(obj, config={"show_class_members": False})
        signature = inspect.signature(obj)
        documented = _documented(doc, "Parameters") | _documented(doc, "Attributes")
    else:
        doc = docscrape.FunctionDoc(obj)
        signature = inspect.signature(obj)
        documented = _documented(doc, "Parameters")
        assert doc["Returns"] or doc["Yields"], f"{path}: no Returns section"
    wanted = [p.name for p in signature.parameters.values() if p.name not in ("self", "cls")
              and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    missing = [p for p in wanted if p not in documented]
    assert not missing, f"{path}: parameters not documented: {missing}"
    for p in doc["Parameters"]:
        assert p.desc or p.type, f"{path}: parameter {p.name} has neither a type nor a description"


def test_the_entry_points_have_examples_and_references():
    for function in (vehdyn.sweep.run, vehdyn.sweep.sensitivity):
        assert docscrape.FunctionDoc(function)["Examples"], function.__name__
    references = "\n".join(docscrape.FunctionDoc(vehdyn.sweep.sensitivity)["References"])
    for source in ("Saltelli", "2010", "Morris", "1991", "Campolongo", "2007", "Jansen", "1999"):
        assert source in references, source
