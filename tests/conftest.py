"""Shared fixtures: every test starts with the same mpmath precision, whatever the previous one did."""

from __future__ import annotations

import os

# One BLAS thread per process under pytest-xdist. The suite runs on two workers on two cores (README,
# .ci/run): OpenBLAS's own threads on top oversubscribe the cores and spin, about half again as much CPU for
# the same tests (measured on test_car.py and test_finite_beam_tr.py: 94 s against 62 s of user time). The
# main process has imported numpy by now (a plugin does), but it runs no test under -n; the workers it
# starts next, and the subprocesses of the tests (CLI runs, notebook kernels, derivations), inherit the
# variables. A value already set wins.
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

# Compiled bytecode. Where PYTHONDONTWRITEBYTECODE is set (some machines set it for every process), every
# process of the suite (the two workers, each command-line subprocess, each notebook kernel, each later run)
# compiles the package and the tests from source again: about half of a worker's collection time. The suite
# writes its bytecode under .pytest_cache/bytecode instead, never beside the sources, and every later
# process reads it there. A PYTHONPYCACHEPREFIX already set wins.
if os.environ.pop("PYTHONDONTWRITEBYTECODE", None):
    import sys
    from pathlib import Path

    _prefix = str(Path(__file__).resolve().parent.parent / ".pytest_cache" / "bytecode")
    os.environ.setdefault("PYTHONPYCACHEPREFIX", _prefix)
    sys.pycache_prefix = os.environ["PYTHONPYCACHEPREFIX"]
    sys.dont_write_bytecode = False

# Interrupted long jobs (maps) keep their finished parts in a cache folder: the suite's own, never the
# user's (the commands run in this process and in subprocesses both read the variable).
if "MOVING_BOGIE_CACHE" not in os.environ:
    import tempfile

    os.environ["MOVING_BOGIE_CACHE"] = tempfile.mkdtemp(prefix="moving-bogie-cache-")

import mpmath  # noqa: E402
import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

# The property tests judge values, not speed: no per-example deadline, which a loaded machine exceeds
# (Hypothesis's default is 200 ms per example). In CI (CI set) they draw the same examples at every run, so
# that CI judges the change and not the draw; a developer's runs draw anew and explore (a case found goes
# into the test's corpus or an @example).
settings.register_profile("moving-bogie", deadline=None, derandomize=bool(os.environ.get("CI")))
settings.load_profile("moving-bogie")


@pytest.fixture(autouse=True)
def _restore_mp_dps():
    """Save ``mpmath.mp.dps`` before each test and restore it after, so no test leaks a changed global."""
    dps = mpmath.mp.dps
    yield
    mpmath.mp.dps = dps


@pytest.fixture
def compute_once(monkeypatch):
    """``compute_once(module, name)`` replaces ``module.name`` by a version that computes on its first call
    and hands every later call that same result; returns the list of results (one entry once called)."""

    def patch(module, name):
        results, compute = [], getattr(module, name)

        def once(*args, **kwargs):
            if not results:
                results.append(compute(*args, **kwargs))
            return results[0]

        monkeypatch.setattr(module, name, once)
        return results

    return patch


@pytest.fixture(scope="session")
def table1_search():
    """``table1_search(case, vehicle=None)``: ``induced_frequencies(table1_case(case), dps=30)`` (the default
    options; another vehicle by name), searched once per process for every module that asks for it and
    reads the roots. Under ``-n 2`` those modules run on one worker (``xdist_balance.TOGETHER``)."""
    from moving_bogie.api import induced_frequencies
    from moving_bogie.model.cases import table1_case

    found = {}

    def search(case: int, vehicle: str | None = None):
        if (case, vehicle) not in found:
            params = table1_case(case) if vehicle is None else table1_case(case).replace(vehicle=vehicle)
            found[case, vehicle] = induced_frequencies(params, dps=30)
        return found[case, vehicle]

    return search


@pytest.fixture(scope="module")
def same_search_once():
    """For the module that asks for it (``pytestmark = pytest.mark.usefixtures("same_search_once")``): a root
    search (``roots.frequencies.induced_frequencies``) of the same parameters on their own track with the
    same options runs once, and every later call gets that result (a search on another track, given as a
    foundation beside the parameters, runs anew). Only for modules whose tests check what is made of the
    roots (a command's output), not the search itself, and that patch no part of the search. Returns the
    dict of the searches run, by key."""
    import moving_bogie.roots.frequencies as fq
    from moving_bogie.kernels.bound import bind

    search, found = fq.induced_frequencies, {}

    def once(bound, *, progress=None, **options):
        own = bind(bound.params)
        if bound.foundation is not own.foundation or bound.foundation_floats() != own.foundation_floats():
            return search(bound, progress=progress, **options)
        key = (bound.params, repr(sorted(options.items())))
        if key not in found:
            found[key] = search(bound, progress=progress, **options)
        return found[key]

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(fq, "induced_frequencies", once)
        yield found


@pytest.fixture
def ctrl_c_raises():
    """SIGINT raises KeyboardInterrupt in this process, as in a terminal, even when the suite was started as a
    background job (which starts Python with SIGINT ignored); the previous handler comes back afterwards."""
    import signal

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """Under ``-n N --dist=loadscope`` (pyproject.toml): :class:`xdist_balance.BalancedScopes`."""
    if config.getoption("dist") != "loadscope":
        return None
    from xdist_balance import BalancedScopes

    return BalancedScopes(config, log)
