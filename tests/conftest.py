"""Session-wide settings of the test suite: the numpy portability checks.

A test marked ``compiled_vs_numpy`` compares results of two computational paths that call different
math libraries (numpy's ufuncs against numba-compiled code or :mod:`math`); its comparison holds
within a stated budget of units in the last place (``tests/_tolerances.py``), whatever CPU numpy
dispatches to. Two ways to see that it does, on any machine (README, "Development"):

* ``NPY_DISABLE_CPU_FEATURES="X86_V3 X86_V4 AVX512_ICL AVX512_SPR"`` switches numpy's SIMD dispatch
  off (numpy >= 2.4 names; the header below prints what numpy found and uses);
* ``VEHDYN_TEST_PERTURB_ULPS=N`` moves every float64 result of numpy's transcendental ufuncs by
  +-1..N ulps (``tests/_perturb/sitecustomize.py``), as a CPU whose numpy kernels differ from the
  C library's would: N = 2 stands in for an AVX-512 machine.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

import pytest

_PERTURB_DIR = Path(__file__).resolve().parent / "_perturb"

# backend="auto" compiles before it runs, as it always did, unless a test turns background builds on
# (tests/core/test_background_build.py): the suite's numbers and timings do not depend on a build's progress,
# and no builder outlives a test. Subprocesses of the tests (the CLI, process pools) inherit it.
os.environ["VEHDYN_BACKGROUND_COMPILE"] = "0"


def _load_perturbation():
    """tests/_perturb/sitecustomize.py as a module (the one a subprocess imports as ``sitecustomize``)."""
    if "sitecustomize" in sys.modules and hasattr(sys.modules["sitecustomize"], "install_from_environment"):
        return sys.modules["sitecustomize"]
    spec = importlib.util.spec_from_file_location("vehdyn_tests_numpy_perturbation", _PERTURB_DIR / "sitecustomize.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


_perturbation = _load_perturbation()
if os.environ.get(_perturbation.ENV, "").strip() not in ("", "0"):
    if "vehdyn" in sys.modules and not _perturbation.installed():
        raise pytest.UsageError(f"{_perturbation.ENV} is set but vehdyn was imported before tests/conftest.py: "
                                "its array namespaces bound the unperturbed numpy functions")
    _perturbation.install_from_environment()
    # Python subprocesses of the tests (CLI, process pools, Dask workers) perturb their numpy too
    os.environ["PYTHONPATH"] = os.pathsep.join(filter(None, [str(_PERTURB_DIR), os.environ.get("PYTHONPATH")]))


def pytest_report_header(config):
    import numpy as np

    try:
        from numpy._core import _multiarray_umath as umath
    except ImportError:  # numpy < 2
        from numpy.core import _multiarray_umath as umath
    found = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    lines = [f"numpy {np.__version__} SIMD: baseline {' '.join(umath.__cpu_baseline__)}; dispatched "
             f"{' '.join(found) or 'none'}"
             + (f" (NPY_DISABLE_CPU_FEATURES={os.environ['NPY_DISABLE_CPU_FEATURES']!r})"
                if os.environ.get("NPY_DISABLE_CPU_FEATURES") else "")]
    ulps = _perturbation.installed()
    if ulps:
        lines.append(f"numpy transcendental ufuncs perturbed by +-1..{ulps} ulps ({_perturbation.ENV}): "
                     + " ".join(np._vehdyn_perturbed_names))
    return lines
