"""Every public callable documents every parameter, with its unit, and what it returns.

As python-control's ``docstrings_test.py`` holds its API to its docstrings: every function and
class named in the ``__all__`` of a public module of vehdyn (a module path without a component that
starts with an underscore), and every public method those classes define, is read with numpydoc.
A parameter of the signature must be described in the ``Parameters`` section (or, for a class, in
its own or its ``__init__``'s docstring, or as a parameter field with a description); a number or
array parameter names its unit in brackets (``[m/s]``, ``[-]`` for a ratio); a function that
returns a value says what in a ``Returns`` (or ``Yields``) section. A method that overrides a
documented method of a vehdyn base class (``rhs``, ``output``, ``linearize``, ...) inherits its
documentation.

``test_every_model_and_law_cites_its_source`` asks more of the classes that are models or laws
(subclasses of :class:`vehdyn.Model` and :class:`vehdyn.tire.TireModel` with equations of their
own): a ``References`` section and the equations in ``.. math::``.
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import pkgutil
import re
import warnings
from pathlib import Path

import pytest

numpydoc = pytest.importorskip("numpydoc.docscrape", reason='the docstring test needs pip install -e ".[test]"')

import vehdyn  # noqa: E402
from vehdyn.model import Model  # noqa: E402

#: Parameters that never need a description: the model contract's (t, x, u) is documented once
#: in :class:`vehdyn.Model`, ``self``/``cls`` are not parameters.
CONTRACT = {"self", "cls"}

#: Words of a numpydoc type that mean the parameter is a physical number (needs a unit).
NUMBER_TYPES = re.compile(r"\b(float|array_like|ndarray|array)\b")
UNIT = re.compile(r"\[[^\]]*\]")


def public_modules():
    names = ["vehdyn"]
    for info in pkgutil.walk_packages(vehdyn.__path__, "vehdyn."):
        if not any(part.startswith("_") for part in info.name.split(".")[1:]) and not info.name.endswith("__main__"):
            names.append(info.name)
    return names


def public_callables():
    """{qualified name: object} of every public function, class and method defined in vehdyn."""
    found = {}
    for module_name in public_modules():
        module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or not obj.__module__.startswith("vehdyn"):
                continue
            qualified = f"{obj.__module__}.{obj.__qualname__}"
            found.setdefault(qualified, obj)
            if inspect.isclass(obj):
                for attr, member in vars(obj).items():
                    if attr.startswith("_"):
                        continue
                    function = member.__func__ if isinstance(member, (classmethod, staticmethod)) else member
                    if inspect.isfunction(function):
                        found.setdefault(f"{qualified}.{attr}", function)
    return found


def _inherited_doc(owner, name):
    """The docstring of a vehdyn base class's method ``name`` that ``owner`` overrides, if any."""
    for base in owner.__mro__[1:]:
        member = vars(base).get(name)
        if member is not None and base.__module__.startswith("vehdyn") and getattr(member, "__doc__", None):
            return member.__doc__
    return None


def _owner(function):
    qualname = function.__qualname__.split(".")
    if len(qualname) < 2:
        return None
    module = importlib.import_module(function.__module__)
    obj = module
    for part in qualname[:-1]:
        obj = getattr(obj, part, None)
    return obj if inspect.isclass(obj) else None


def _parameters_section(doc: str):
    parsed = numpydoc.NumpyDocString(doc or "")
    out = {}
    for section in ("Parameters", "Other Parameters", "Attributes"):
        for item in parsed[section]:
            for name in item.name.replace("*", "").split(","):
                out[name.strip()] = (item.type, " ".join(item.desc))
    return out, parsed


def problems_of(qualified, obj):
    """What the docstring of ``obj`` lacks (a list of strings; empty when complete)."""
    problems = []
    if inspect.isclass(obj):
        try:
            signature = inspect.signature(obj)
        except (TypeError, ValueError):
            return []
        documented, parsed = _parameters_section(obj.__doc__ or "")
        init_doc = vars(obj).get("__init__").__doc__ if "__init__" in vars(obj) else None
        if init_doc:
            documented.update(_parameters_section(init_doc)[0])
        if dataclasses.is_dataclass(obj):
            for f in dataclasses.fields(obj):
                if f.metadata.get("description"):
                    unit = f.metadata.get("unit")
                    documented.setdefault(f.name, ("float" if unit else "", f"[{unit}] " if unit else "x"))
        returns = False
        if not (obj.__doc__ or "").strip():
            problems.append("no docstring")
    else:
        owner = _owner(obj)
        doc = obj.__doc__
        if owner is not None and (not doc or not doc.strip()):
            doc = _inherited_doc(owner, obj.__name__)
            if doc:
                return []  # an override of a documented vehdyn method
        elif owner is not None and _inherited_doc(owner, obj.__name__) and "Parameters" not in (doc or ""):
            return []
        if not (doc or "").strip():
            return ["no docstring"]
        signature = inspect.signature(obj)
        documented, parsed = _parameters_section(doc)
        returns = True
    for name, parameter in signature.parameters.items():
        if name in CONTRACT or parameter.kind in (parameter.VAR_POSITIONAL, parameter.VAR_KEYWORD) \
                and (f"*{name}" in (obj.__doc__ or "") or f"**{name}" in (obj.__doc__ or "")):
            continue
        if name not in documented:
            problems.append(f"parameter {name!r} undocumented")
            continue
        kind, description = documented[name]
        if NUMBER_TYPES.search(kind or "") and "bool" not in (kind or "") and not UNIT.search(description + kind):
            problems.append(f"parameter {name!r} has no unit in brackets")
    if returns and not inspect.isclass(obj) and obj.__name__ != "__init__":
        source_returns = _returns_a_value(obj)
        if source_returns and not (parsed["Returns"] or parsed["Yields"]):
            problems.append("no Returns section")
    return problems


def _returns_a_value(function) -> bool:
    import ast
    import textwrap

    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):
        return False
    top = tree.body[0]
    pending = list(ast.iter_child_nodes(top))
    while pending:  # the function's own statements: a nested function's returns are not its own
        node = pending.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            continue
        if isinstance(node, ast.Return) and node.value is not None and not (
                isinstance(node.value, ast.Constant) and node.value.value is None):
            return True
        pending.extend(ast.iter_child_nodes(node))
    return False


with warnings.catch_warnings():
    warnings.simplefilter("ignore", UserWarning)  # numpydoc: the models' "Signals" sections
    CALLABLES = public_callables()

BACKLOG = Path(__file__).with_name("docstring_backlog.txt")


def _backlog(kind):
    """Names still on the backlog of ``kind`` ("parameters" or "references"): the list only shrinks
    (a test fails when an entry is complete, so that it is struck off)."""
    lines = BACKLOG.read_text(encoding="utf-8").splitlines() if BACKLOG.exists() else []
    return {line.split()[1] for line in lines if line.startswith(kind + " ")}


KNOWN_INCOMPLETE = _backlog("parameters")


@pytest.mark.parametrize("qualified", sorted(CALLABLES))
def test_every_parameter_is_documented(qualified):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        problems = problems_of(qualified, CALLABLES[qualified])
    if qualified in KNOWN_INCOMPLETE:
        assert problems, f"{qualified} is documented now: strike it off KNOWN_INCOMPLETE"
        pytest.xfail("; ".join(problems))
    assert problems == [], f"{qualified}: " + "; ".join(problems)


def test_the_checker_finds_what_is_missing():
    def documented(speed, gain=1.0):
        """A function.

        Parameters
        ----------
        speed : float
            Forward speed [m/s].
        gain : float
            A gain [-].

        Returns
        -------
        float
            The product [m/s].
        """
        return speed * gain

    def undocumented(speed, mass):
        """A function.

        Parameters
        ----------
        speed : float
            Forward speed, no unit.
        """
        return speed * mass

    def checks(speed):
        """A function that returns nothing; its helper returns a value.

        Parameters
        ----------
        speed : float
            Forward speed [m/s].
        """
        def positive(value):
            return value > 0

        assert positive(speed)

    assert problems_of("documented", documented) == []
    assert problems_of("checks", checks) == []
    assert problems_of("undocumented", undocumented) == [
        "parameter 'speed' has no unit in brackets", "parameter 'mass' undocumented", "no Returns section"]


def models_and_laws():
    """{qualified name: class} of the public model and tire-law classes with equations of their own."""
    from vehdyn.tire import TireModel

    bases = (Model, TireModel)
    return {q: obj for q, obj in CALLABLES.items() if inspect.isclass(obj) and issubclass(obj, bases)
            and obj not in bases and obj.__module__ not in ("vehdyn.model.linear",)}


MODELS = models_and_laws()
KNOWN_UNCITED = _backlog("references")


@pytest.mark.parametrize("qualified", sorted(MODELS))
def test_every_model_and_law_cites_its_source(qualified):
    doc = MODELS[qualified].__doc__ or ""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        parsed = numpydoc.NumpyDocString(doc)
    problems = (["no References section"] if not parsed["References"] else []) + (
        ["no .. math:: equations"] if ".. math::" not in doc else [])
    if qualified in KNOWN_UNCITED:
        assert problems, f"{qualified} cites its source now: strike it off the backlog"
        pytest.xfail("; ".join(problems))
    assert problems == [], f"{qualified}: " + "; ".join(problems)


def test_the_backlog_names_only_what_exists():
    assert sorted((KNOWN_INCOMPLETE - set(CALLABLES)) | (KNOWN_UNCITED - set(MODELS))) == []
