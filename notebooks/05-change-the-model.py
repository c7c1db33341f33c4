# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Change the model: a new foundation, derived, generated and analysed
#
# The paper's Discussion says the analysis "can be easily extended to other types of supporting
# structures ... simply by replacing Equation (24) with an equation reflecting the new foundation model".
# In this package that is one edit in `derivations/` (SymPy, the single source of every formula) and a
# regeneration into `generated/`; the runtime then finds the new kernels by name.
#
# This notebook does it end to end, **in a temporary copy of the repository** (it never touches the
# real `derivations/` or `generated/`):
#
# 1. copy `derivations/` and `generated/` to a temporary folder;
# 2. add a model there: the Pasternak shear layer of the Euler-Bernoulli model gets viscous
#    (Kelvin-Voigt) damping $c_s$, i.e. Eq. (1) becomes
#    $EI\,w_{,xxxx} - (k_s + c_s\,\partial_t)\,w_{,xx} + m\,w_{,tt} + c_f\,w_{,t} + k_f\,w = p$, with the new
#    dimensionless group $\eta_c = c_s / (2\sqrt{EI\,m})$;
# 3. run `python -m derivations --root <copy>` there;
# 4. load the generated module from the copy (importlib), evaluate its kernel, and rerun the induced
#    frequency analysis with it, against the base model.
#
# The steps follow `docs/adding_a_model.md`, which explains each one and what the runtime does not yet
# pick up by itself.

# %%
import difflib
import hashlib
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import time
import types
from fractions import Fraction
from pathlib import Path

import mpmath

import moving_bogie
from moving_bogie import table1_case
from moving_bogie.roots.frequencies import induced_frequencies

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")


def find_repository() -> Path:
    """The source checkout: the folder holding derivations/ (from the working directory or the package)."""
    starts = [Path.cwd(), Path(moving_bogie.__file__).resolve()]
    for start in starts:
        for folder in [start, *start.parents]:
            if (folder / "derivations" / "foundations.py").is_file() and (folder / "src/moving_bogie/generated").is_dir():
                return folder
    raise RuntimeError(
        "this notebook needs a source checkout of moving-bogie (with derivations/): "
        "clone the repository and install it with pip install -e '.[dev]'"
    )


def tree_digest(folder: Path) -> str:
    """Hash of every file under `folder`, to prove the real repository is left untouched."""
    h = hashlib.sha256()
    for path in sorted(folder.rglob("*")):
        if path.is_file() and "__pycache__" not in path.parts:
            h.update(str(path.relative_to(folder)).encode())
            h.update(path.read_bytes())
    return h.hexdigest()


repo = find_repository()
before = {name: tree_digest(repo / name) for name in ("derivations", "src/moving_bogie/generated")}
print("repository:", repo)

# %% [markdown]
# ## 1. A temporary copy
#
# `python -m derivations --root DIR` writes `DIR/generated/*.py` and `DIR/docs/proofs.md`; it needs
# nothing else from the repository.

# %%
scratch = Path(tempfile.mkdtemp(prefix="moving-bogie-model-"))
ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
for name in ("derivations", "src/moving_bogie/generated"):
    shutil.copytree(repo / name, scratch / name, ignore=ignore)
(scratch / "docs").mkdir()
print("scratch copy:", scratch)

# %% [markdown]
# ## 2. The new model, in the copy
#
# Two additions (`docs/adding_a_model.md`, steps 1-2): the physical symbol $c_s$ and its dimensionless
# group $\eta_c$ in `symbols.py` ("physical = expression in the group", so that the derivation can check
# that $EI$, $m$, $k_f$, $P$ drop out), and the operator in `foundations.py`, registered in `MODELS`
# under the name `eb_kelvin`. They are appended to the copied files, so this works whatever else those
# files contain.

# %%
SYMBOLS_ADDITION = """

# --- added in a scratch copy by notebooks/05-change-the-model.py -------------------------------------
c_s = sp.Symbol("c_s", positive=True)  # viscous damping of the shear layer (Kelvin-Voigt Pasternak layer)
eta_c = sp.Symbol("eta_c", positive=True)  # c_s / (2 sqrt(EI m))
PHYSICAL_IN_DIMENSIONLESS[c_s] = 2 * eta_c * sp.sqrt(EI * m)
"""

FOUNDATIONS_ADDITION = '''

# --- added in a scratch copy by notebooks/05-change-the-model.py -------------------------------------
from .symbols import c_s  # noqa: E402


def euler_bernoulli_kelvin_shear() -> TrackModel:
    """Eq. (1) with a viscous (Kelvin-Voigt) shear layer: EI w_xxxx - (k_s + c_s d/dt) w_xx + m w_tt + ..."""
    op = sp.Matrix([[EI * dx**4 - (k_s + c_s * dt) * dx**2 + m * dt**2 + c_f * dt + k_f]])
    return TrackModel(op, (w_st,), (4 / (k_f * w_st),), ("eta_c",))


MODELS["eb_kelvin"] = euler_bernoulli_kelvin_shear
'''

for filename, addition in (("symbols.py", SYMBOLS_ADDITION), ("foundations.py", FOUNDATIONS_ADDITION)):
    path = scratch / "derivations" / filename
    old = path.read_text()
    path.write_text(old + addition)
    diff = difflib.unified_diff(
        old.splitlines(True),
        path.read_text().splitlines(True),
        f"a/derivations/{filename}",
        f"b/derivations/{filename}",
        n=0,
    )
    print("".join(diff))

# %% [markdown]
# ## 3. Regenerate, in the copy
#
# The generator derives $D(p, q) = N/Q$ of the new model from the operator (moving coordinates, Eq. (10);
# dimensionless form, Eqs. (15)-(18); transforms, Eqs. (21)-(22)), checks that every free symbol is a
# declared argument and that no constant loses digits, and writes `generated/foundation_eb_kelvin.py`.

# %%
start = time.perf_counter()
run = subprocess.run(
    [sys.executable, "-m", "derivations", "--root", str(scratch)],
    cwd=scratch,  # so that `-m derivations` is the copy, not the repository
    capture_output=True,
    text=True,
)
print(run.stdout, run.stderr)
assert run.returncode == 0, run.stderr
print(f"regenerated in {time.perf_counter() - start:.1f} s")
generated_file = scratch / "src/moving_bogie/generated" / "foundation_eb_kelvin.py"
print("\n".join(generated_file.read_text().splitlines()[:30]))

# %% [markdown]
# The new $N(p, q)$ is $D(p, q)$ of Eq. (24) plus $4\eta_s p^2 + 4i\eta_c p^2 (q - \alpha p)$: the layer's
# $-c_s(\partial_t - v\,\partial_r)\,w_{,rr}$ transformed. Loading the module straight from the copy and
# subtracting the base model's coefficients shows exactly that term.


# %%
def load_from(path: Path, name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


kelvin = load_from(generated_file, "scratch_foundation_eb_kelvin")
base = load_from(scratch / "src/moving_bogie/generated" / "foundation_eb.py", "scratch_foundation_eb")
print("arguments of the new kernel:", kelvin.ARGUMENTS)

with mpmath.workdps(30):
    q, alpha, eta_f, eta_c = (
        mpmath.mpc("0.3", "0.2"),
        mpmath.mpf("0.5"),
        mpmath.mpf("0.05"),
        mpmath.mpf("0.1"),
    )
    common = dict(alpha=alpha, eta_f=eta_f, eta_s=0, S=None, r=None)
    new = kelvin.n_coeffs(q, **common, eta_c=eta_c)
    old = base.n_coeffs(q, **common)
    i4 = 4 * mpmath.j
    expected = [
        0,
        -i4 * eta_c * alpha,
        i4 * eta_c * q,
        0,
        0,
    ]  # 4 i eta_c p^2 (q - alpha p), highest power first
    for k, (a, b, e) in enumerate(zip(new, old, expected)):
        print(f"p^{4 - k}: new - base = {mpmath.nstr(a - b, 8):>24}   expected {mpmath.nstr(e, 8)}")
        assert abs((a - b) - e) < mpmath.mpf(10) ** -25

# %% [markdown]
# ## 4. The frequency analysis with the new model
#
# The runtime looks a track model up by name (`moving_bogie.generated.foundation_<beam>`), and passes
# the kernels the groups their `ARGUMENTS` name, taken from the parameters (`track.foundation_arguments`).
# So the kernel $K$ (Eq. (29), by residues), the cut of $K$ (traced from `n_coeffs_in_q`, whatever its
# shape), $E_{chr}$ and the root search all work for any generated model. What the runtime cannot know
# without an edit is the *parameter*: `DimensionlessParams` has no field `eta_c`, and it accepts the
# beam names of the installed `generated/` (`params.BEAMS`), which does not contain a model generated in a
# scratch folder. To make the model permanent, a researcher regenerates in the real repository (the name
# then joins `BEAMS`, its groups `MODEL_PARAMETERS`), adds the field `eta_c` with its range to
# `DimensionlessParams` in `model/params.py` (and, if wanted, to `PhysicalParams`, the parameter files and the
# CLI options): `docs/adding_a_model.md`.
#
# Here, without editing the package: the module generated in the scratch copy is imported under the
# runtime's name for it, and a small stand-in for `DimensionlessParams` carries the beam name and
# $\eta_c$ (in the precision the runtime asks for: mpmath numbers for polishing, floats for counting).

# %%
spec = importlib.util.spec_from_file_location("moving_bogie.generated.foundation_eb_kelvin", generated_file)
runtime_module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(runtime_module)
sys.modules[spec.name] = runtime_module  # what track.foundation_module("eb_kelvin") imports


class ModelParams:
    """A DimensionlessParams of another track model: its beam name and the groups it adds."""

    def __init__(self, base, beam: str, **groups):
        self._base, self.beam = base, beam
        self._groups = {name: Fraction(str(value)) for name, value in groups.items()}

    def __getattr__(self, name):
        return getattr(self._base, name)

    def as_mp(self):  # at the current mpmath precision, like DimensionlessParams.as_mp
        ns = self._base.as_mp()
        ns.beam = self.beam
        for name, x in self._groups.items():
            setattr(ns, name, mpmath.mpf(x.numerator) / x.denominator)
        return ns

    def as_float(self):
        ns = self._base.as_float()
        ns.beam = self.beam
        for name, x in self._groups.items():
            setattr(ns, name, float(x))
        return ns

    def to_dict(self):
        return self._base.to_dict() | {"beam": self.beam} | {k: str(v) for k, v in self._groups.items()}


def with_shear_damping(params, eta_c):
    return ModelParams(params, "eb_kelvin", eta_c=eta_c)


# %% [markdown]
# First the kernel itself, $K(\xi, q)$ of Eq. (29), evaluated by the runtime's residue sum with the new model:
# at $\eta_c = 0$ it must equal the base model's, and at $\eta_c = 0.1$ it must equal the integral
# $\int e^{ip\xi} / N(p, q)\,dp$ done by brute-force quadrature (here at $\xi = 0$).

# %%
from moving_bogie.kernels.track import TrackKernel  # noqa: E402

p1 = table1_case(1)
zq = mpmath.mpc("0.3", "0.2")
with mpmath.workdps(30):
    k_base = TrackKernel(p1)(zq, [0, 1, -1]).K
    k_zero = TrackKernel(with_shear_damping(p1, 0.0))(zq, [0, 1, -1]).K
    damped = with_shear_damping(p1, 0.1)
    k_damped = TrackKernel(damped)(zq, [0]).K[0]
    coeffs = kelvin.n_coeffs(
        zq,
        alpha=mpmath.mpf(p1.alpha.numerator) / p1.alpha.denominator,
        eta_f=mpmath.mpf(p1.eta_f.numerator) / p1.eta_f.denominator,
        eta_s=0,
        S=None,
        r=None,
        eta_c=mpmath.mpf("0.1"),
    )
    breaks = [-mpmath.inf, *mpmath.linspace(-20, 20, 81), mpmath.inf]  # a pole lies close to the real axis
    k_quad = mpmath.quad(lambda x: 1 / mpmath.polyval(coeffs, x), breaks)
print(
    "eta_c = 0  : K(0), K(1), K(-1) minus the base model's:",
    [mpmath.nstr(abs(a - b), 3) for a, b in zip(k_zero, k_base)],
)
print(f"eta_c = 0.1: K(0) by residues   {mpmath.nstr(k_damped, 20)}")
print(
    f"             K(0) by quadrature {mpmath.nstr(k_quad, 20)}   "
    f"(difference {mpmath.nstr(abs(k_damped - k_quad), 2)})"
)
assert all(a == b for a, b in zip(k_zero, k_base))
assert abs(k_damped - k_quad) < 1e-25

# %%
DPS = 20 if QUICK else 30
ETA_C = (0.0, 0.05, 0.2) if QUICK else (0.0, 0.02, 0.05, 0.1, 0.2)
CASE = 1  # unstable in the subcritical range (Table 2): does damping in the shear layer help?

reference = induced_frequencies(table1_case(CASE), dps=DPS)
results = {}
for eta_c in ETA_C:
    start = time.perf_counter()
    results[eta_c] = induced_frequencies(with_shear_damping(table1_case(CASE), eta_c), dps=DPS)
    r = results[eta_c]
    print(
        f"eta_c = {eta_c:<5}: {r.found}/{r.count} roots, {'stable' if r.stable else 'UNSTABLE'}, "
        f"count ok {r.count_ok}, {time.perf_counter() - start:.1f} s"
    )

# eta_c = 0 reproduces the base model to every confirmed digit
for a, b in zip(results[0.0].roots, reference.roots):
    assert abs(a.q - b.q) < mpmath.mpf(10) ** (-min(a.decimals, b.decimals) + 1)
print(
    "\neta_c = 0 gives the base model's induced frequencies:",
    [r.re_text[:9] + " " + r.im_text[:9] for r in reference.roots],
)

# %% [markdown]
# How the induced frequencies of Case 1 move as the shear layer gets damping. Case 1 is unstable in the
# subcritical range through its second root ($\mathrm{Im}\,q = -0.000130$, Table 2).

# %%
import matplotlib.pyplot as plt  # noqa: E402

print(f"{'eta_c':>6} " + " ".join(f"{'Im q_' + str(k + 1):>12}" for k in range(4)) + "   verdict")
for eta_c, r in results.items():
    ims = [float(root.q.imag) for root in r.roots]
    print(
        f"{eta_c:6.2f} " + " ".join(f"{x:12.6f}" for x in ims) + f"   {'stable' if r.stable else 'UNSTABLE'}"
    )

fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for k in range(4):
    xs = [e for e, r in results.items() if len(r.roots) > k]
    axes[0].plot(xs, [float(results[e].roots[k].q.real) for e in xs], "o-", label=f"root {k + 1}")
    axes[1].plot(xs, [float(results[e].roots[k].q.imag) for e in xs], "o-", label=f"root {k + 1}")
axes[1].axhline(0, color="k", lw=0.8)
axes[1].set_yscale("symlog", linthresh=1e-4)
axes[0].set_ylabel("Re q")
axes[1].set_ylabel("Im q (below 0: unstable)")
for ax in axes:
    ax.set_xlabel("shear-layer damping η_c")
axes[0].legend(fontsize=8)
fig.suptitle(f"Case {CASE}: induced frequencies with a viscous Pasternak layer (model 'eb_kelvin', η_s = 0)")
plt.show()

# %%
unstable_im = [min(float(root.q.imag) for root in r.roots) for r in results.values()]
assert all(b < a for a, b in zip(unstable_im, unstable_im[1:])), unstable_im  # the text below relies on it
print("most negative Im q as eta_c grows:", [f"{x:.6f}" for x in unstable_im])

# %% [markdown]
# The base model is recovered exactly at $\eta_c = 0$, and the generated kernel differs from the base one by
# exactly the derived term. The new model then tells something the base model cannot: **damping in the
# shear layer makes Case 1 more unstable**, not less. The stable roots decay faster (their $\mathrm{Im}\,q$
# grows), but the unstable root's $\mathrm{Im}\,q$ becomes more negative. This is the same surprise the paper
# reports for the foundation damping $\eta_f$ (Section 3.5, Figure 3): for two interacting contact points,
# more damping in the track can aggravate the instability in the subcritical range.
#
# ## Clean up
#
# The scratch copy is deleted, the temporary module is unregistered, and the real repository is checked
# to be byte-for-byte what it was.

# %%
del sys.modules["moving_bogie.generated.foundation_eb_kelvin"]
shutil.rmtree(scratch)
after = {name: tree_digest(repo / name) for name in ("derivations", "src/moving_bogie/generated")}
assert after == before, "the repository's derivations/ or generated/ changed"
print("derivations/ and generated/ of", repo, "are unchanged")
