"""The result of the strip search (:mod:`moving_bogie.roots.strip`): its roots, count, window, verdict and
margin, and the band above its window that it did not search (docs/sleepers.md, "Finding the roots")."""

from __future__ import annotations

from dataclasses import dataclass, field

from moving_bogie.roots.count.contour import Rectangle
from moving_bogie.roots.count.outcomes import Note, Reason, count_mismatch
from moving_bogie.roots.verdict import STABLE, UNDETERMINED, UNSTABLE, Verdict

__all__ = ["CONTINUED", "FloquetResult", "FloquetRoot"]

#: How far the continued window reaches, in units of the smeared rail's free waves' decay rate: the
#: periodic rail's first-band waves, which move the supports as the smeared rail's do, put singular lines
#: just below and above that rate, where the quadrature's integrand is nearly singular
CONTINUED = 0.9


@dataclass(frozen=True)
class FloquetRoot:
    """One induced frequency q in the strip; ``step`` is how far it moved at the last harmonic added."""

    q: complex
    residual: float
    step: float


@dataclass(frozen=True)
class FloquetResult:
    """The roots with Im q <= top in the strip, with the count, the harmonics and the verdict's reasons.

    ``harmonics`` is N (the harmonics -N-1..N); ``converged`` says whether the roots and the count agreed
    at N - 1 and N; ``notes`` say why a verdict is UNDETERMINED. ``free_waves`` is the lowest Im q of the
    rail's free waves (the singular lines of the receptance, Eq. (S15); 0 when not known);
    ``continued_to`` the top of the window when the receptance was continued across them (else None);
    ``skipped`` names a band the continuation could not search, and why.
    """

    roots: tuple[FloquetRoot, ...]
    count: int
    harmonics: int
    converged: bool
    window: Rectangle
    Omega0: float
    evaluations: int
    notes: tuple[str, ...] = field(default=())
    free_waves: float = 0.0
    continued_to: float | None = None
    skipped: tuple[str, ...] = ()

    @property
    def verdict(self) -> Verdict:
        """The one verdict type (:mod:`moving_bogie.roots.verdict`): UNSTABLE when a root has Im q < 0;
        STABLE when every counted root was located, decays (Im q > 0) and the search left no note; else
        UNDETERMINED with the notes (or the count not matched) as its reasons."""
        if any(r.q.imag < 0 for r in self.roots):
            return Verdict(UNSTABLE)
        complete = not self.notes and len(self.roots) == self.count
        if complete and all(r.q.imag > 0 for r in self.roots):
            return Verdict(STABLE)
        reasons = [Note(Reason.STRIP, text) for text in self.notes]
        if len(self.roots) != self.count:
            reasons.append(count_mismatch(self.count, len(self.roots)))
        if not reasons:
            reasons.append(Note(Reason.STRIP, "a root lies on the real axis (neither grows nor decays)"))
        return Verdict(UNDETERMINED, tuple(reasons))

    @property
    def _ceiling(self) -> float:
        """The decay rate beyond which the window vouches for no vibration: the free waves' when the window
        reaches 0.99 of it (the default), else the window's top (a root may lie above it)."""
        return self.free_waves if self.window.y1 >= 0.99 * self.free_waves else self.window.y1

    @property
    def margin_source(self) -> str | None:
        """What sets the margin: "a root", "the rail's free waves", or "the window's top" when the window
        was stopped below them (the margin is then a lower bound); None without a margin."""
        if self.margin is None:
            return None
        least = self.least_damped
        if least is not None and least.q.imag <= self.margin:
            return "a root"
        return "the rail's free waves" if self._ceiling == self.free_waves else "the window's top"

    def unsearched(self, scale: float = 1.0, unit: str = "") -> tuple[str, ...]:
        """The band of the strip above the window that was not searched and why, Im q times ``scale`` (in
        ``unit``); it holds decaying vibrations only, so the verdict does not depend on it."""
        top = self.window.y1
        if top < 0:
            return ()
        if self.skipped:
            return self.skipped
        im = "Im" if unit else "Im q"  # without a unit: the dimensionless q of the strip
        band = f"{im} > {top * scale:.6g}{unit}"
        if self.continued_to is not None:
            return (
                f"{band}: the receptance is continued across the rail's free waves up to "
                f"{CONTINUED:g} of the smeared rail's free waves' decay rate, and roots beyond are not "
                "searched",
            )
        if self.free_waves > top:
            return (
                f"{band}: the rail's free waves put singular lines of the receptance from {im} = "
                f"{self.free_waves * scale:.6g}{unit} up, and roots beyond them are not searched",
            )
        return (f"{band}: the lowest decay rate of this rail's free waves is not known",)

    @property
    def unstable_count(self) -> int:
        """How many located roots have Im q < 0 (the count of unstable roots when every counted root was
        located)."""
        return sum(r.q.imag < 0 for r in self.roots)

    @property
    def least_damped(self) -> FloquetRoot | None:
        """The located root with the smallest Im q (None when none was located)."""
        return min(self.roots, key=lambda r: r.q.imag, default=None)

    @property
    def margin(self) -> float | None:
        """A STABLE result's decay rate Im q of its least-damped vibration, else None.

        The least-damped root's Im q, or the free waves' lowest Im q when that is smaller (or no root lies
        in the window): the rail's own free waves decay at that rate, and roots beyond it are not searched.
        The default window stops at 0.99 of the free waves' rate, so a root in the band left between would
        lower the margin by less than 1 %; a window stopped lower gives its top instead (a lower bound).
        """
        if self.verdict.state != STABLE:
            return None
        ceiling = self._ceiling
        rates = [r.q.imag for r in self.roots] + ([ceiling] if ceiling > 0 else [])
        return min(rates) if rates else None
