"""Proofs in ball arithmetic (python-flint, Arb): E_chr and dE_chr/dq in balls (Eqs. (38), (40)), the p-root
balls and discs of N(p, q), the rectangles of the proven count, proven winding numbers, and the certificate
of the roots, the count and the verdict.
"""

from moving_bogie.roots.proof.ball_block import BlockBalls, coefficient, series_det
from moving_bogie.roots.proof.balls import BallCharacteristic, exact_ball, square_ball
from moving_bogie.roots.proof.certify import (
    Certificate,
    Enclosure,
    ProofVerdict,
    krawczyk,
    pinches_around_roots,
    refine,
)
from moving_bogie.roots.proof.p_balls import (
    Undecided,
    derivative_coefficients,
    direct_root_balls,
    horner,
    isolate_roots,
)
from moving_bogie.roots.proof.p_discs import PRootDiscs, RootDisc, coefficients_in_q, taylor_in_q
from moving_bogie.roots.proof.proof_tiling import ProofTiling, Staircase
from moving_bogie.roots.proof.strip_proof import StripProof, strip_from_below
from moving_bogie.roots.proof.winding import NotProven, ProvenCount, proven_count

__all__ = [
    "BallCharacteristic",
    "BlockBalls",
    "Certificate",
    "Enclosure",
    "NotProven",
    "PRootDiscs",
    "ProofTiling",
    "ProofVerdict",
    "ProvenCount",
    "RootDisc",
    "Staircase",
    "StripProof",
    "Undecided",
    "coefficient",
    "coefficients_in_q",
    "derivative_coefficients",
    "direct_root_balls",
    "exact_ball",
    "horner",
    "isolate_roots",
    "krawczyk",
    "pinches_around_roots",
    "proven_count",
    "refine",
    "series_det",
    "square_ball",
    "strip_from_below",
    "taylor_in_q",
]
