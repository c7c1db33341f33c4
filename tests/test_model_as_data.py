"""A model added in derivations/ only: regenerated, loaded and analysed with no edit of the runtime.

The scratch model is the paper's track with a viscous (Kelvin-Voigt) shear layer, a new dimensionless group
eta_c = c_s / (2 sqrt(EI m)) declared once in symbols.py. References, independent of the residue machinery:
K(0, q) by adaptive quadrature of 1 / N(p, q) over real p (mpmath.quad), and at eta_c = 0 the paper's model
itself. Notebook 05 does the same at length.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import mpmath
import pytest
from derivation_support import regenerated_copy, require_sympy

from moving_bogie import DimensionlessParams, ParameterError, table1_case
from moving_bogie.api import induced_frequencies
from moving_bogie.kernels.bound import bind
from moving_bogie.kernels.track import TrackKernel
from moving_bogie.model.catalogue import Model, get_model, load_catalogue
from moving_bogie.roots.count.window import far_field_window

require_sympy()

SYMBOLS = """
c_s = sp.Symbol("c_s", positive=True)
eta_c = sp.Symbol("eta_c", positive=True)
declare(eta_c, c_s, 2 * eta_c * sp.sqrt(EI * m), meaning="shear-layer damping c_s/(2 sqrt(EI m))",
        constraint="nonnegative", equation="(1) with k_s -> k_s + c_s d/dt", unit="N s",
        si_meaning="viscous damping of the shear layer", default=0)
"""
FOUNDATIONS = """
from .symbols import c_s  # noqa: E402
TRACKS["kelvin-shear"] = Track("viscous shear layer", k_f + c_f * dt - (k_s + c_s * dt) * dx**2)
"""


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    """A copy of the source tree with the new track, its models regenerated (``--only kelvin-shear``).

    The other models keep their committed modules: the tests below use the new track and the paper's
    model only.
    """
    return regenerated_copy(
        tmp_path_factory.mktemp("model"),
        {"symbols.py": SYMBOLS, "foundations.py": FOUNDATIONS},
        only=("kelvin-shear",),
    )


@pytest.mark.slow
def test_the_new_model_is_in_the_regenerated_catalogue(scratch):
    catalogue = load_catalogue(scratch / "src/moving_bogie/generated")
    names = {m.name for m in catalogue.models()}
    assert {"eb/kelvin-shear/bogie", "tr/kelvin-shear/masses"} <= names
    spec = Model("eb", "kelvin-shear", "bogie", catalogue).specs["eta_c"]
    assert (spec.constraint, spec.default, spec.si, spec.unit, spec.option) == (
        "nonnegative",
        0,
        "c_s",
        "N s",
        "--eta-c",
    )
    with pytest.raises(ParameterError, match="eta_c"):
        DimensionlessParams(model=Model("eb", "kelvin-shear", "bogie", catalogue), **_base(), eta_c=-1)


def _base() -> dict:
    return table1_case(1).values()


@pytest.mark.slow
def test_kernel_against_quadrature_and_the_base_model(scratch):
    model = Model("eb", "kelvin-shear", "bogie", load_catalogue(scratch / "src/moving_bogie/generated"))
    q = mpmath.mpc("0.3", "0.2")
    with mpmath.workdps(30):
        zero = TrackKernel(bind(DimensionlessParams(model=model, **_base())))(q, [0, 2]).K
        base = TrackKernel(bind(table1_case(1)))(q, [0, 2]).K
        assert all(abs(a - b) < mpmath.mpf(10) ** -25 for a, b in zip(zero, base))
        damped = DimensionlessParams(model=model, **_base(), eta_c="0.1")
        ns = damped.as_mp()
        coeffs = model.foundation.n_coeffs(q, alpha=ns.alpha, eta_f=ns.eta_f, eta_s=ns.eta_s, eta_c=ns.eta_c)
        breaks = [-mpmath.inf, *mpmath.linspace(-20, 20, 81), mpmath.inf]
        quadrature = mpmath.quad(lambda p: 1 / mpmath.polyval(coeffs, p), breaks)
        assert abs(TrackKernel(bind(damped))(q, [0]).K[0] - quadrature) < mpmath.mpf(10) ** -20


@pytest.mark.slow
def test_frequencies_in_python_and_on_the_copy_s_command_line(scratch):
    model = Model("eb", "kelvin-shear", "bogie", load_catalogue(scratch / "src/moving_bogie/generated"))
    at_zero = induced_frequencies(DimensionlessParams(model=model, **_base()), dps=20)
    paper = induced_frequencies(table1_case(1), dps=20)
    assert at_zero.count_ok and [str(r.q)[:14] for r in at_zero.roots] == [str(r.q)[:14] for r in paper.roots]
    damped = induced_frequencies(DimensionlessParams(model=model, **_base(), eta_c="0.2"), dps=20)
    assert damped.count_ok and damped.found == 4
    env = dict(os.environ, PYTHONPATH=str(scratch / "src"))
    argv = ["frequencies", "--case", "1", "--track", "kelvin-shear", "--eta-c", "0.2", "--dps", "20"]
    argv.append("--json")
    run = subprocess.run(
        [sys.executable, "-m", "moving_bogie", *argv], env=env, capture_output=True, text=True, cwd=scratch
    )
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["params"]["track"] == "kelvin-shear" and data["params"]["eta_c"] == "0.2"
    cli = [complex(float(r["re"]), float(r["im"])) for r in data["roots"]]
    assert all(abs(a - complex(b.q)) < 1e-12 for a, b in zip(cli, damped.roots))


@pytest.mark.slow
def test_the_new_track_reaches_its_own_kernels_and_asymptotics(scratch):
    """A track that only the copy has: the bound model holds the copy's modules, and the far-field check
    justifies a radius from the copy's own KERNEL_DECAY (the packaged catalogue has no such module)."""
    catalogue = load_catalogue(scratch / "src/moving_bogie/generated")
    params = DimensionlessParams(
        model=Model("eb", "kelvin-shear", "bogie", catalogue), **_base(), eta_c="0.2"
    )
    bound = bind(params)
    assert bound.foundation is catalogue.module(catalogue.index.MODULES[("eb", "kelvin-shear")])
    assert bound.vehicle is catalogue.module("vehicle_bogie")
    assert bound.kernel_decay is not None
    _, far = far_field_window(bound)
    assert far.radius is not None, far.reason


def test_unknown_model_names_are_refused_naming_the_option():
    with pytest.raises(ParameterError) as info:
        get_model(track="ballast")
    assert info.value.parameter == "track" and "one-layer" in str(info.value)
