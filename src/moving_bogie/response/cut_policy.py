"""When the branch-cut part I_bc (Eq. (35)) enters a closed form, and over which times.

``branch_cut="auto"`` (the default) includes I_bc at the times where it can matter and skips it where its
measured size is below ``bc_tol`` times the largest steady wheel deflection:

1. The rigorous bound |I_bc(tau)| <= B e^{-eta_f tau}, B = (1/pi) integral of |jump| ds over the cut, gives
   tau_bound = ln(B / tol) / eta_f (infinite when eta_f = 0).
2. Below tau_bound, I_bc is measured on windows of one period 2 pi/q_c at tau = 25, 50, 100, ... (doubling);
   the first window where every response stays below tol sets the end tau_on (I_bc decays, so it stays
   below). If none does before ``bc_tau_cap``, I_bc is included up to the cap and a note says so.

I_bc is then computed for tau <= min(tau_bound, tau_on) and taken as zero beyond
(``TimeSeries.branch_cut_until``).
"""

from __future__ import annotations

import math

import numpy as np

from moving_bogie.errors import ParameterError
from moving_bogie.kernels.bound import BoundModel
from moving_bogie.response.branch_cut import BranchCut, BranchCutUnavailable
from moving_bogie.response.cut_integral import CurveBranchCut, branch_cut_for
from moving_bogie.response.residues import ResidueExpansion

__all__ = ["branch_cut_extent", "branch_cut_mode", "branch_cut_or_note", "s_min_for"]

_PROBE_START = 25.0


def branch_cut_mode(branch_cut: bool | str) -> str:
    """ "on", "off" or "auto" from the ``branch_cut`` argument (True, False or one of those words)."""
    if branch_cut is True or branch_cut == "on":
        return "on"
    if branch_cut is False or branch_cut == "off":
        return "off"
    if branch_cut == "auto":
        return "auto"
    raise ParameterError("branch_cut", f"branch_cut must be True, False or 'auto' (got {branch_cut!r})")


def branch_cut_or_note(bound: BoundModel, mode: str) -> tuple[BranchCut | CurveBranchCut | None, list[str]]:
    """(BranchCut or None, notes); raises for an unavailable branch cut only when it was forced on."""
    if mode == "off":
        return None, []
    try:
        return branch_cut_for(bound), []
    except BranchCutUnavailable as exc:
        if mode == "on":
            raise
        return None, [f"branch cut skipped: {exc}"]


def s_min_for(bc: BranchCut | CurveBranchCut, expansion: ResidueExpansion) -> float:
    """Keep every induced frequency's Re q inside the quadrature range of the cut (not in the tail)."""
    top = float(np.max(np.abs(expansion.q.real))) if expansion.q.size else 0.0
    return max(bc.q_c, top) + 1.0


def branch_cut_extent(
    bc: BranchCut | CurveBranchCut,
    tau_max: float,
    *,
    tol: float,
    cap: float = 1e4,
    s_min: float | None = None,
    times: np.ndarray | None = None,
) -> tuple[float, list[str]]:
    """(tau_on, notes): the time up to which I_bc exceeds ``tol`` (the ``auto`` rule, module docstring).

    ``times``: those of the series that follows; a traced cut probes each window with the panels that
    their band will use (:meth:`CurveBranchCut.integrate`, ``rule_tau``), so that the series reuses the
    jump's values when I_bc is kept over that band."""
    notes = []
    bound = max(bc.l1_bound(s_min=s_min).values())
    if bound <= tol:
        return 0.0, [f"branch cut skipped: its bound {bound:.2e} is below tol {tol:.1e}"]
    tau_bound = math.log(bound / tol) / bc.eta_f if bc.eta_f > 0 else math.inf
    limit = min(tau_max, tau_bound)
    # a cut that crosses Re q = 0 (a mass layer's curves) has no slowest period: windows [probe, 2 probe]
    period = 2 * math.pi / bc.q_c if bc.q_c > 0 else math.inf
    probe = _PROBE_START
    while probe < limit:
        if probe > cap:
            notes.append(
                f"branch cut still above tol {tol:.1e} at tau = {cap:g}: included only up to tau = {cap:g}"
            )
            return cap, notes
        window = probe + np.linspace(0.0, min(period, probe), 16)
        values = bc.responses(window, s_min=s_min, rule_tau=times)
        if max(np.abs(v).max() for v in values.values()) < tol:
            return probe, notes
        probe *= 2
    return limit, notes
