"""Values of the jump across the traced cut (Eq. (35)) that
:class:`~moving_bogie.response.cut_integral.CurveBranchCut` keeps for reuse across the bands of times.

The jump is evaluated by chunks of whole panels of 16 nodes
(:func:`~moving_bogie.response.cut_pieces.roots_along` seeds within a panel, so a value does not depend
on the chunk it was evaluated in). Kept, each store dropping its oldest entry when full: the values at
the nodes of the adapted panels (every rule's panels that stay whole have these nodes: all of them in the
first band and the L1 bound, most in the next bands), the values of a rule (a band whose rule is that of
an earlier band, or of a probe of the ``auto`` rule), and small results (Re q at the panel edges, the
end terms of the tails).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from moving_bogie.response.cut_pieces import CurvePiece
from moving_bogie.response.quadrature import GL_X, gauss_panels

__all__ = ["JumpValues", "PieceChannel"]

#: The jump along one piece of the cut at nodes in p: ``channel(piece, p) -> (q, J)``.
PieceChannel = Callable[[CurvePiece, np.ndarray], tuple[np.ndarray, np.ndarray]]

#: Jump values kept for reuse across bands of times: entries, and only for this many columns (responses).
_CACHE_ENTRIES = 64
_CACHE_COLUMNS = 8
#: Values at the nodes of the adapted panels kept (per piece and channel).
_KNOWN_ENTRIES = 16
#: Small results kept (per piece, truncation and channel: Re q at the panel edges, the end terms).
_SMALL_ENTRIES = 256
#: Nodes per evaluation of the jump (a multiple of the 16 nodes of a panel; arrays that fit the cache).
_CHUNK = 4096


class JumpValues:
    """The stores of jump values of a traced cut (module docstring)."""

    def __init__(self) -> None:
        self._base: dict = {}
        self._cache: dict = {}
        self._small: dict = {}
        self._known: dict = {}

    def _store_adapted(
        self, piece: CurvePiece, channel: PieceChannel, edges: np.ndarray, final: np.ndarray
    ) -> None:
        """Keep ``final``, the values (J columns, then q) at the Gauss nodes of the panels ``edges`` that
        the adaptation ended with, sorted by node (time series only: few columns)."""
        if (
            final.shape != (GL_X.size * (edges.size - 1), final.shape[1])
            or final.shape[1] > _CACHE_COLUMNS + 1
        ):
            return
        nodes = gauss_panels(edges[:-1], edges[1:])[0]
        order = np.argsort(nodes, kind="stable")
        if len(self._known) >= _KNOWN_ENTRIES:
            self._known.pop(next(iter(self._known)))
        self._known[(id(piece), channel)] = nodes[order], final[order]

    def _remember(self, key: tuple, value: object) -> None:
        """Keep a small result (Re q at the edges, the end terms) for the other bands of times."""
        if len(self._small) >= _SMALL_ENTRIES:
            self._small.pop(next(iter(self._small)))
        self._small[key] = value

    def _values(
        self, piece: CurvePiece, nodes: np.ndarray, channel: PieceChannel, m: int
    ) -> tuple[np.ndarray, np.ndarray]:
        """(q, J) at the nodes of a rule; a band of times whose rule is that of an earlier band (panels
        set by e^{i p xi} rather than by the phase) reuses its values (time series only: m small)."""
        key = (id(piece), channel, nodes.size, hash(nodes.tobytes()))
        if key in self._cache:
            return self._cache[key]
        value = self._reuse_known(piece, nodes, channel)
        if m <= _CACHE_COLUMNS:
            self._keep(key, value)
        return value

    def _reuse_known(
        self, piece: CurvePiece, nodes: np.ndarray, channel: PieceChannel
    ) -> tuple[np.ndarray, np.ndarray]:
        """(q, J) at the nodes: at the nodes of the adapted panels (:meth:`_panels`) their values, at the
        others (whole panels of the rule) by :meth:`_chunked`."""
        known = self._known.get((id(piece), channel))
        if known is None:
            return self._chunked(piece, nodes, channel)
        at, values = known
        k = np.minimum(np.searchsorted(at, nodes), at.size - 1)
        hit = at[k] == nodes
        out = np.empty((nodes.size, values.shape[1]), dtype=complex)
        out[hit] = values[k[hit]]
        if not np.all(hit):
            q, J = self._chunked(piece, nodes[~hit], channel)
            out[~hit] = np.concatenate([J, q[:, None]], axis=1)
        return out[:, -1], out[:, :-1]

    @staticmethod
    def _chunked(
        piece: CurvePiece, nodes: np.ndarray, channel: PieceChannel
    ) -> tuple[np.ndarray, np.ndarray]:
        """(q, J) at the nodes, by chunks of ``_CHUNK`` nodes (whole panels: the values do not depend on
        the chunks, :func:`~moving_bogie.response.cut_pieces.roots_along` seeds within a panel)."""
        parts = [channel(piece, nodes[k : k + _CHUNK]) for k in range(0, nodes.size, _CHUNK)]
        return np.concatenate([v[0] for v in parts]), np.concatenate([v[1] for v in parts])

    def _keep(self, key: tuple, value: tuple[np.ndarray, np.ndarray]) -> None:
        """Cache the jump values of a rule (the oldest entry leaves when the cache is full)."""
        if len(self._cache) >= _CACHE_ENTRIES:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = value
