"""The checker: every property of :mod:`._properties` on every certificate of a gain set, batch by batch.

It owns no inequality: it hands each batch of trajectories to each
:class:`~._property.Property` (once, for a property that does not use the
certificate), folds the :class:`~._property.Evaluation` into a
:class:`~._results.Tally` per certificate and property (the tolerance is
applied there, in one place), keeps the observed overshoots for the report,
and follows the trajectories that have not yet reached ``θ|x(0)|_𝒜`` at the
horizon (:func:`~.prop1.resolve_attractivity`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._infra.errors import ParameterError
from .._model.parameters import Parameters
from ._along import along
from ._claims import Claims
from ._properties import properties
from ._property import DEFAULT_RTOL, DEFAULT_THETA, Evaluation
from ._results import Counterexample, PropertyResult, Tally

__all__ = ["BatchChecker"]

_ATTRACTIVITY = "prop1.attractivity"


class BatchChecker:
    """Check certificates sharing one gain set on batches of trajectories.

    Parameters
    ----------
    params : Parameters
    claims : sequence of Claims
        Certificates for ``params`` (e.g. the feasible and the tightest one).
    rtol : float, keyword-only
        Relative tolerance (see :mod:`._property`).
    theta : float, keyword-only
        Attractivity factor at the horizon.

    Feed batches with :meth:`add`; read :meth:`results`.
    """

    def __init__(self, params: Parameters, claims: list[Claims], *, rtol: float = DEFAULT_RTOL,
                 theta: float = DEFAULT_THETA) -> None:
        for cl in claims:
            if cl.params != params:
                raise ParameterError(
                    f"certificate {cl.label} has gains {cl.params}; a checker for {params} takes only those gains"
                )
        self.params = params
        self.claims = list(claims)
        self.rtol = float(rtol)
        self.theta = float(theta)
        self.properties = properties(rtol=self.rtol, theta=self.theta)
        # a certificate is held to the properties that are its claims (another template than the paper's: κ only)
        self._tallies = [{p.id: Tally(p, cl.label, self.rtol) for p in self.properties if p.applies_to(cl)}
                         for cl in self.claims]
        self._offset = 0
        self._overshoot: list[np.ndarray] = []
        self._sources: list[np.ndarray] = []
        self._final_ratio: list[np.ndarray] = []
        self._final_z: list[np.ndarray] = []
        self._pending: list[tuple] = []
        self._times_to_theta: list[float] = []
        self.incomplete = 0
        """Trajectories the simulator could not finish (event limit): never checked as holding."""
        self.incomplete_examples: list[tuple[str, tuple[float, float, float]]] = []
        self.max_events = 10_000

    # -- batches ---------------------------------------------------------------------------------
    def add(self, batch: Any, *, attractivity: bool = True) -> None:
        """Check every certificate on the trajectories of ``batch``.

        ``attractivity=False`` skips the horizon test (for short adversarial runs).
        """
        if batch.params != self.params:
            raise ParameterError(f"the batch was simulated with {batch.params}; this checker is for {self.params}")
        N = batch.size
        if N == 0:
            return
        a = along(batch)
        if not a.complete.all():
            self.incomplete += int(np.count_nonzero(~a.complete))
            for i in np.flatnonzero(~a.complete)[: 5 - len(self.incomplete_examples)]:
                self.incomplete_examples.append((str(batch.source[i]), tuple(float(q) for q in batch.z0[i])))
        for prop in self.properties:
            if prop.id == _ATTRACTIVITY and not attractivity:
                continue
            shared: Evaluation | None = None
            for ci, cl in enumerate(self.claims):
                if prop.id not in self._tallies[ci]:
                    continue
                if prop.uses_certificate or shared is None:
                    shared = prop.check(batch, cl)
                self._fold(self._tallies[ci][prop.id], shared)
        if attractivity:
            self._horizon_statistics(batch)
        self._overshoot.append(a.overshoot)
        self._sources.append(np.asarray(batch.source))
        self._offset += N

    def _fold(self, tally: Tally, ev: Evaluation, *, first: bool = True) -> None:
        tally.add(ev.slack, ev.mask, ev.witness, offset=self._offset, count_trajectories=first)
        tally.inconclusive += ev.inconclusive
        for key, values, mask, largest in ev.extremes:
            tally.extreme(key, values, mask, largest=largest)
        for more in ev.more:
            self._fold(tally, more, first=False)

    def _horizon_statistics(self, batch: Any) -> None:
        from .._model.attractor import attractor_bound_z
        from .._model.coordinates import x_to_z

        a = along(batch)
        prop = next(p for p in self.properties if p.id == _ATTRACTIVITY)
        d_final = a.d[np.arange(a.N), a.last_sample]
        with np.errstate(divide="ignore", invalid="ignore"):
            self._final_ratio.append(np.where(a.complete, np.where(a.d0 > 0, d_final / a.d0, 0.0), np.nan))
        # in z (Proposition 1, item 1): s, v → 0 and e_i enters [-f_c/k_i, f_c/k_i]
        zT = x_to_z(self.params, batch.x[:, -1, :])
        bound = float(attractor_bound_z(self.params))
        self._final_z.append(np.stack([np.abs(zT[:, 1]), np.abs(zT[:, 2]),
                                       np.maximum(np.abs(zT[:, 0]) - bound, 0.0)], axis=1))
        for i in prop.pending(batch):
            self._pending.append((self._offset + int(i), batch.z0[i].copy(), batch.x0[i].copy(), float(a.d0[i]),
                                  float(a.L[i]), str(batch.source[i]), float(batch.t[-1])))

    def resolve_attractivity(self, *, doublings: int = 60, samples: int = 40) -> None:
        """Follow the pending trajectories (:func:`~.prop1.resolve_attractivity`); fail those that never make it."""
        from .prop1 import resolve_attractivity

        if not self._pending:
            return
        z = np.array([p[1] for p in self._pending], dtype=float)
        target = np.array([self.theta * p[3] for p in self._pending])
        window = max(p[6] for p in self._pending)
        outcome = resolve_attractivity(self.params, z, target, window, max_events=self.max_events,
                                       doublings=doublings, samples=samples)
        self.incomplete += sum(1 for o in outcome if o is None)
        for (gi, z0, x0, d0, L, source, _T), result in zip(self._pending, outcome):
            if result is None:
                continue
            ok, tk, dk, xk = result
            if not ok:
                dk = dk if math.isfinite(dk) else d0
                xk = xk if all(math.isfinite(q) for q in xk) else tuple(float(q) for q in x0)
            if ok:
                self._times_to_theta.append(tk)
            rel = np.array([(self.theta * d0 - dk) / L])
            cx = Counterexample(
                property=_ATTRACTIVITY, certificate="", trajectory=gi, source=source,
                z0=tuple(float(q) for q in z0), x0=tuple(float(q) for q in x0), t=tk, t_start=0.0, x=xk,
                values={"dist_T": dk, "dist0": d0, "theta": self.theta}, relative_slack=float(rel[0]),
            )
            for tallies in self._tallies:
                tallies[_ATTRACTIVITY].add(rel, np.array([True]), lambda idx, cx=cx: cx)
        self._pending = []

    def add_peaks(self, x0: np.ndarray, t_peak: np.ndarray, x_peak: np.ndarray, d0: np.ndarray,
                  source: str = "adversarial overshoot (peak refined on the closed form)") -> None:
        """Check Proposition 1's bound at peaks located between samples (:func:`~._overshoot.refine_peak`).

        The peak states are re-simulated solutions (not counted as new
        trajectories); each is one more instance of ``prop1.stability``.
        """
        from .._model.attractor import distance_x
        from .._model.coordinates import x_to_z

        ok = np.isfinite(t_peak) & (d0 > 0) & np.isfinite(x_peak).all(axis=1)
        if not np.any(ok):
            return
        xp = np.where(ok[:, None], x_peak, 0.0)
        d = distance_x(self.params, xp)
        L = np.maximum(np.linalg.norm(xp, axis=1), np.linalg.norm(x0, axis=1)) + float(self.params.f_c)
        for ci, cl in enumerate(self.claims):
            rel = (cl.kappa * d0 - d) / L

            def make(idx: tuple[int, ...], rel: np.ndarray = rel, kappa: float = cl.kappa) -> Counterexample:
                i = idx[0]
                return Counterexample(
                    property="prop1.stability", certificate="", trajectory=-1, source=source,
                    z0=tuple(float(q) for q in x_to_z(self.params, x0[i])), x0=tuple(float(q) for q in x0[i]),
                    t=float(t_peak[i]), t_start=None, x=tuple(float(q) for q in x_peak[i]),
                    values={"dist": float(d[i]), "dist0": float(d0[i]), "kappa": kappa,
                            "observed_ratio": float(d[i] / d0[i]), "scale": float(L[i])},
                    relative_slack=float(rel[i]),
                )

            self._tallies[ci]["prop1.stability"].add(rel[:, None], ok[:, None], make, count_trajectories=False)

    # -- results ---------------------------------------------------------------------------------
    def results(self) -> list[list[PropertyResult]]:
        """Per certificate, the results in the order of :data:`~._properties.PROPERTIES`."""
        out = []
        final = np.concatenate(self._final_ratio) if self._final_ratio else np.zeros(0)
        ov = self.overshoots()
        ov = ov[np.isfinite(ov)]
        for ci, cl in enumerate(self.claims):
            tallies = self._tallies[ci]
            if ov.size:
                tallies["prop1.stability"].details |= {
                    "max_overshoot": float(ov.max()), "kappa": cl.kappa, "tightness": float(ov.max()) / cl.kappa,
                }
            if final.size:
                tallies[_ATTRACTIVITY].details |= self._attractivity_details(final)
            out.append([tallies[p.id].result() for p in self.properties if p.id in tallies])
        return out

    def _attractivity_details(self, final: np.ndarray) -> dict[str, Any]:
        fin = np.isfinite(final)
        times = self._times_to_theta
        fz = np.concatenate(self._final_z)

        def median(col: np.ndarray) -> float:
            return float(np.nanmedian(col)) if np.any(np.isfinite(col)) else math.nan

        return {
            "theta": self.theta,
            "median_final_ratio": float(np.nanmedian(final)) if fin.any() else math.nan,
            "max_final_ratio": float(np.nanmax(final)) if fin.any() else math.nan,
            "extended": len(times),
            "latest_time_to_theta": max(times) if times else None,
            "median |s(T)|": median(fz[:, 0]),
            "median |v(T)|": median(fz[:, 1]),
            "share e_i(T) in [-f_c/k_i, f_c/k_i]": float(np.mean(fz[np.isfinite(fz[:, 2]), 2] == 0.0))
            if np.any(np.isfinite(fz[:, 2])) else math.nan,
        }

    def overshoots(self) -> np.ndarray:
        """Observed ``max_t |x(t)|_𝒜/|x(0)|_𝒜`` of every trajectory added so far (NaN if ``x(0) ∈ 𝒜``)."""
        return np.concatenate(self._overshoot) if self._overshoot else np.zeros(0)

    def last_overshoots(self) -> np.ndarray:
        """The observed overshoot ratios of the batch added last (without joining the whole history)."""
        return self._overshoot[-1] if self._overshoot else np.zeros(0)

    def sources(self) -> np.ndarray:
        """Source label of every trajectory added so far (aligned with :meth:`overshoots`)."""
        return np.concatenate(self._sources) if self._sources else np.zeros(0, dtype=object)
