"""The cross-check driver: certificates in, per-property verdicts out.

For every gain set it simulates (exactly, with the ``event`` method) a
budget of trajectories from random spheres, a grid, special states and
adversarial searches, and checks every certificate of that gain set on the
same trajectories (the solutions depend on the gains only; the
certificates differ in their constants).
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable, Sequence

import numpy as np

from .._errors import ParameterError, UnprovedCertificateError
from .._parameters import Parameters
from ._claims import Claims
from ._properties import DEFAULT_RTOL, DEFAULT_THETA, BatchChecker, Counterexample, PropertyResult

__all__ = [
    "CertificateCheck",
    "CrosscheckReport",
    "crosscheck",
    "default_horizon",
    "sample_times",
    "SEARCH_MODES",
    "search_mode",
]

SEARCH_MODES = ("random spheres", "grid", "special", "adversarial")
"""Sources of initial states, for the per-mode tightness ratio."""


def search_mode(label: str) -> str:
    """Map an initial-state label to one of :data:`SEARCH_MODES`."""
    if label.startswith("sphere"):
        return "random spheres"
    if label.startswith("grid"):
        return "grid"
    if label.startswith("adversarial"):
        return "adversarial"
    return "special"


def slowest_root(params: Parameters) -> float:
    """``Re λ`` of the slowest eigenvalue ``λ`` of ``A`` (eq. xDot), i.e. root of ``det(sI - A)``."""
    from .._coordinates import system_matrix

    return float(np.max(np.linalg.eigvals(system_matrix(params)).real))


def default_horizon(params: Parameters) -> float:
    """``20/|Re λ|`` for the slowest eigenvalue ``λ`` of ``A`` (rounded up)."""
    return float(math.ceil(20.0 / abs(slowest_root(params))))


def sample_times(horizon: float, samples: int) -> np.ndarray:
    """``t_j = T (j/(n-1))²``: dense at the start, where overshoots and ``R̂`` visits happen."""
    u = np.linspace(0.0, 1.0, samples)
    return horizon * u * u


@dataclass(frozen=True)
class CertificateCheck:
    """The cross-check of one certificate.

    Attributes
    ----------
    claims : Claims
    source : str
        File the certificate came from (or ``""``).
    results : tuple of PropertyResult
    trajectories : int
        Trajectories simulated for this gain set.
    horizon : float
    max_overshoot : dict
        Search mode -> largest observed ``sup_t |x(t)|_𝒜/|x(0)|_𝒜``.
    worst_state : tuple of float
        ``x(0)`` of the largest overshoot found.
    seconds : float
        Wall time of the gain set's run (shared by its certificates).
    incomplete : int
        Trajectories the simulator could not finish (event limit); they are
        never counted as holding, and any makes the check incomplete.
    proved : bool or None
        Whether exact verification proved the certificate first (``None``:
        candidate constants checked on purpose, ``require_proved=False``).
    """

    claims: Claims
    source: str
    results: tuple[PropertyResult, ...]
    trajectories: int
    horizon: float
    max_overshoot: dict
    worst_state: tuple[float, float, float]
    seconds: float
    overshoots: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    initial_distance: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    modes: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    incomplete: int = 0
    proved: bool | None = None

    @property
    def label(self) -> str:
        return self.claims.label

    @property
    def complete(self) -> bool:
        """Every trajectory was simulated to its horizon."""
        return self.incomplete == 0

    @property
    def passed(self) -> bool:
        """Every property held on complete data (an incomplete run never passes)."""
        return self.complete and all(r.passed for r in self.results)

    @property
    def verdict(self) -> str:
        """``"passed"``, ``"failed"`` (a property is violated) or ``"incomplete"``."""
        if not all(r.passed for r in self.results):
            return "failed"
        return "passed" if self.complete else "incomplete"

    @property
    def tightness(self) -> dict:
        """Search mode -> largest overshoot / κ (and ``"all"``)."""
        out = {mode: value / self.claims.kappa for mode, value in self.max_overshoot.items()}
        if self.max_overshoot:
            out["all"] = max(self.max_overshoot.values()) / self.claims.kappa
        return out

    def counterexamples(self) -> list[Counterexample]:
        return [r.counterexample for r in self.results if r.counterexample is not None]


@dataclass(frozen=True)
class CrosscheckReport:
    """Everything a cross-check run found.

    Attributes
    ----------
    checks : tuple of CertificateCheck
    rtol, theta : float
    seed : int
    seconds : float
    decay : dict
        Gain-set label -> :class:`~._decay.DecayFit` (if requested).
    iss : dict
        Gain-set label -> :class:`~._iss.IssEstimate` (if requested).
    """

    checks: tuple[CertificateCheck, ...]
    rtol: float
    theta: float
    seed: int
    seconds: float
    decay: dict = field(default_factory=dict)
    iss: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return bool(self.checks) and all(c.passed for c in self.checks)

    @property
    def incomplete(self) -> int:
        """Incomplete trajectories over every gain set (each gain set counted once)."""
        seen: dict[Any, int] = {}
        for c in self.checks:
            seen[c.claims.params] = c.incomplete
        return sum(seen.values())

    @property
    def trajectories(self) -> int:
        seen: dict[Any, int] = {}
        for c in self.checks:
            seen[c.claims.params] = c.trajectories
        return sum(seen.values())

    def summary(self) -> str:
        """The last line: what was checked, with counts, and the verdict."""
        failed = [c.label for c in self.checks if c.verdict == "failed"]
        verdict = "FAILED" if failed else ("INCOMPLETE" if self.incomplete else "PASSED")
        checked = sum(r.samples for c in self.checks for r in c.results)
        text = (
            f"crosscheck: {verdict} — {len(self.checks)} certificate(s), {self.trajectories} trajectories "
            f"({self.incomplete} incomplete), {checked} instances of {len(self.checks[0].results) if self.checks else 0} "
            f"properties checked"
        )
        if failed:
            text += f"; violated by {', '.join(failed)}"
        return text + f" ({self.seconds:.1f} s)"

    def counterexamples(self) -> list[Counterexample]:
        return [cx for c in self.checks for cx in c.counterexamples()]


def _as_claims(items: Iterable[Any], *, require_proved: bool) -> list[tuple[Claims, str, bool | None]]:
    """``(claims, source, proved)`` per item; with ``require_proved`` every certificate is verified exactly first.

    Raises
    ------
    UnprovedCertificateError
        With ``require_proved``, for a certificate that exact verification
        rejects (the message names the file and the failing inequalities), or
        for :class:`Claims` (floats: nothing left to verify).
    """
    from .._certify.certificate import Certificate, load
    from .._certify.verify import verify_certificate

    out = []
    for item in items:
        if isinstance(item, Claims):
            if require_proved:
                raise UnprovedCertificateError(
                    f"{item.label}: Claims hold floats and cannot be verified exactly; pass the certificate, "
                    "or require_proved=False to check candidate constants"
                )
            out.append((item, "", None))
            continue
        if isinstance(item, (str, os.PathLike)):
            path = Path(item)
            cert, source, label = load(path), str(path), path.stem
        else:
            cert, source, label = item, "", None
        proved = None
        if require_proved:
            if not isinstance(cert, Certificate):
                raise UnprovedCertificateError(f"{type(cert).__name__} is not a certificate; it cannot be verified exactly")
            report = verify_certificate(cert, source=source or "<certificate>")
            if not report.proved:
                raise UnprovedCertificateError(
                    f"{source or 'certificate'} does not verify, refusing to cross-check it: "
                    + "; ".join(check.message for check in report.failures)
                )
            proved = True
        out.append((Claims.from_certificate(cert, label=label), source, proved))
    return out


def crosscheck(
    certificates: Sequence[Any],
    *,
    trajectories: int = 10_000,
    seed: int = 0,
    horizon: float | None = None,
    samples: int = 301,
    rtol: float = DEFAULT_RTOL,
    theta: float = DEFAULT_THETA,
    adversarial: bool = True,
    decay: bool = False,
    iss: bool = False,
    chunk: int = 1000,
    progress: bool | None = None,
    require_proved: bool = True,
    max_events: int = 10_000,
) -> CrosscheckReport:
    """Check certificates on exact simulated trajectories.

    Parameters
    ----------
    certificates : sequence
        Certificate objects or paths to certificate files; with
        ``require_proved=False`` also altered copies and :class:`Claims`.
    trajectories : int, keyword-only
        Trajectories per gain set (shared by the certificates of that gain set).
    seed : int, keyword-only
        Seed of the random initial states and of the optimisers.
    horizon : float, optional, keyword-only
        Simulation horizon; default :func:`default_horizon` per gain set.
    samples : int, keyword-only
        Samples per trajectory (:func:`sample_times`), plus every event.
    rtol : float, keyword-only
        Relative tolerance of every check (see :mod:`._properties`).
    theta : float, keyword-only
        Attractivity factor: ``|x(T)|_𝒜 ≤ θ|x(0)|_𝒜`` at the horizon.
    adversarial : bool, keyword-only
        Run the optimisers (overshoot, pointwise bounds, growth of ``V̂``).
    decay, iss : bool, keyword-only
        Also fit the decay of ``|x|_𝒜`` and estimate Corollary 1's gain.
    chunk : int, keyword-only
        Trajectories simulated and checked at a time (memory bound).
    progress : bool or None, keyword-only
        Progress bar on stderr; ``None``: only if stderr is a terminal.
    require_proved : bool, keyword-only
        Verify every certificate exactly first and refuse one that does not
        verify (default).  ``False`` checks candidate constants on purpose,
        e.g. deliberately wrong ones, to show that the cross-check catches them.
    max_events : int, keyword-only
        Event limit per trajectory; a trajectory that reaches it is reported
        as incomplete, never as holding.

    Returns
    -------
    CrosscheckReport

    Raises
    ------
    ParameterError
        If ``trajectories``, ``samples``, ``horizon``, ``rtol`` or ``theta``
        is out of range.
    UnprovedCertificateError
        If ``require_proved`` and a certificate does not verify exactly.
    """
    from .._progress import Progress

    if isinstance(trajectories, bool) or not isinstance(trajectories, (int, np.integer)) or trajectories < 1:
        raise ParameterError(f"trajectories must be an integer ≥ 1; got {trajectories!r}")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 3:
        raise ParameterError(f"samples must be an integer ≥ 3; got {samples!r}")
    if horizon is not None and not (isinstance(horizon, (int, float)) and math.isfinite(horizon) and horizon > 0):
        raise ParameterError(f"horizon must be a finite number > 0; got {horizon!r}")
    if not (isinstance(rtol, (int, float)) and 0 < rtol < 1):
        raise ParameterError(f"rtol must be in (0, 1); got {rtol!r}")
    if not (isinstance(theta, (int, float)) and 0 < theta <= 1):
        raise ParameterError(f"theta must be in (0, 1]; got {theta!r}")
    start = time.perf_counter()
    if isinstance(max_events, bool) or not isinstance(max_events, (int, np.integer)) or max_events < 1:
        raise ParameterError(f"max_events must be an integer ≥ 1; got {max_events!r}")
    claims = _as_claims(certificates, require_proved=require_proved)
    if not claims:
        raise ParameterError("no certificate to cross-check")
    groups: dict[Parameters, list[tuple[Claims, str, bool | None]]] = {}
    for cl, src, proved in claims:
        groups.setdefault(cl.params, []).append((cl, src, proved))
    checks: list[CertificateCheck] = []
    decay_fits: dict[str, Any] = {}
    iss_estimates: dict[str, Any] = {}
    bar = Progress(trajectories * len(groups), desc="crosscheck", enabled=progress)
    try:
        for gi, (params, members) in enumerate(groups.items()):
            t0 = time.perf_counter()
            T = float(horizon) if horizon is not None else default_horizon(params)
            run = _GroupRun(params, [m[0] for m in members], T=T, samples=samples, rtol=rtol, theta=theta,
                            seed=seed + 1000 * gi, chunk=chunk, bar=bar, max_events=int(max_events))
            run.execute(trajectories, adversarial=adversarial)
            seconds = time.perf_counter() - t0
            ov = run.checker.overshoots()
            src = run.checker.sources()
            modes = np.array([search_mode(str(s)) for s in src], dtype=object)
            finite = np.isfinite(ov)
            max_ov = {m: float(ov[finite & (modes == m)].max()) for m in SEARCH_MODES if np.any(finite & (modes == m))}
            best = int(np.nanargmax(np.where(finite, ov, -np.inf))) if np.any(finite) else 0
            for (cl, source, proved), results in zip(members, run.checker.results()):
                checks.append(
                    CertificateCheck(
                        claims=cl,
                        source=source,
                        results=tuple(results),
                        trajectories=run.count,
                        horizon=T,
                        max_overshoot=max_ov,
                        worst_state=tuple(float(q) for q in run.x0_all[best]) if run.x0_all.size else (0.0, 0.0, 0.0),
                        seconds=seconds,
                        overshoots=ov,
                        initial_distance=run.d0_all,
                        modes=modes,
                        incomplete=run.checker.incomplete,
                        proved=proved,
                    )
                )
            key = members[0][0].label
            if decay:
                from ._decay import decay_fit

                decay_fits[key] = decay_fit(params, seed=seed)
            if iss:
                from ._iss import iss_gain

                iss_estimates[key] = iss_gain(params)
    finally:
        bar.close()
    return CrosscheckReport(
        checks=tuple(checks),
        rtol=rtol,
        theta=theta,
        seed=seed,
        seconds=time.perf_counter() - start,
        decay=decay_fits,
        iss=iss_estimates,
    )


class _GroupRun:
    """Simulate and check one gain set's trajectories within the budget."""

    def __init__(self, params: Parameters, claims: list[Claims], *, T: float, samples: int, rtol: float, theta: float,
                 seed: int, chunk: int, bar: Any, max_events: int = 10_000) -> None:
        self.params = params
        self.claims = claims
        self.t = sample_times(T, samples)
        self.T = T
        self.seed = seed
        self.chunk = max(1, int(chunk))
        self.bar = bar
        self.checker = BatchChecker(params, claims, rtol=rtol, theta=theta)
        self.checker.max_events = max_events
        self.max_events = max_events
        self.count = 0
        self._x0: list[np.ndarray] = []

    @property
    def x0_all(self) -> np.ndarray:
        return np.concatenate(self._x0) if self._x0 else np.zeros((0, 3))

    @property
    def d0_all(self) -> np.ndarray:
        from .._attractor import distance_x

        return distance_x(self.params, self.x0_all) if self._x0 else np.zeros(0)

    def evaluate(
        self, X0: np.ndarray, label: str, *, t: np.ndarray | None = None, attractivity: bool = True
    ) -> np.ndarray:
        """Simulate and check the states ``X0`` (rows, in ``x``); return their overshoots."""
        from .._coordinates import x_to_z
        from .._simulation.batch import simulate_batch

        X0 = np.atleast_2d(np.asarray(X0, dtype=float))
        out = []
        for lo in range(0, X0.shape[0], self.chunk):
            part = X0[lo : lo + self.chunk]
            times = self.t if t is None else t
            batch = simulate_batch(
                self.params, x_to_z(self.params, part), float(times[-1]), t_eval=times,
                source=np.full(part.shape[0], label, dtype=object), max_events=self.max_events,
            )
            # the simulator starts from z(0); use the x(0) it actually simulated
            self.checker.add(batch, attractivity=attractivity)
            out.append(self.checker.overshoots()[-part.shape[0]:])
            self._x0.append(batch.x0)
            self.count += part.shape[0]
            self.bar.update(part.shape[0])
        return np.concatenate(out) if out else np.zeros(0)

    def execute(self, budget: int, *, adversarial: bool) -> None:
        from ._initial import InitialStates, grid_states, special_states, sphere_states

        rng = np.random.default_rng(self.seed)
        fixed = [special_states(self.params)]
        fixed.append(grid_states(self.params, int(0.15 * budget)))
        if adversarial:
            from ._adversarial import pointwise_extremes, rate_maximisers

            fixed.append(pointwise_extremes(self.params, self.claims, seed=self.seed))
        init = InitialStates.concat(fixed)
        init = InitialStates(init.x[: budget], init.source[: budget])
        self.evaluate_states(init)
        if adversarial and self.count < budget:
            # Growth of V̂ in R̂: dense short runs from the maximisers of V̂'/V̂
            t_short = np.concatenate([[0.0], np.geomspace(1e-6, min(self.T, 5.0), 199)])
            for j, cl in enumerate(self.claims):
                room = budget - self.count
                if room <= 0:
                    break
                X = rate_maximisers(self.params, cl, seed=self.seed + 7 * j, count=min(16, room))
                self.evaluate(X[:room], f"adversarial max V̂'/V̂ on R̂ [{cl.label}]", t=t_short, attractivity=False)
            room = budget - self.count
            if room > 0:
                from ._adversarial import maximise_overshoot

                maximise_overshoot(
                    self.params,
                    lambda X, label: self.evaluate(X, label),
                    budget=max(1, min(room, int(0.1 * budget))),
                    seed=self.seed,
                )
        room = budget - self.count
        if room > 0:
            self.evaluate_states(sphere_states(self.params, room, rng))
        self.checker.resolve_attractivity()

    def evaluate_states(self, init: Any) -> None:
        if len(init) == 0:
            return
        # one call per distinct label keeps the labels; the chunking is inside evaluate
        labels = init.source
        order = np.argsort(labels.astype(str), kind="stable")
        uniq, starts = np.unique(labels.astype(str)[order], return_index=True)
        bounds = list(starts) + [len(order)]
        for u, a, b in zip(uniq, bounds[:-1], bounds[1:]):
            self.evaluate(init.x[order[a:b]], str(u))
