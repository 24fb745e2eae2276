"""The cross-check driver: certificates in, per-property verdicts out.

For every gain set it simulates (exactly, with the ``event`` method) a
budget of trajectories from random spheres, a grid, special states and
adversarial searches, and checks every certificate of that gain set on the
same trajectories (the solutions depend on the gains only; the
certificates differ in their constants).

One gain set's run: simulate its budget of trajectories and check every certificate on them.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any, Iterable, Sequence

import numpy as np

from .._infra.errors import ParameterError, UnprovedCertificateError
from .._infra.guards import check_count, check_items, check_real, shown
from .._model.parameters import Parameters
from .._simulation._base import MAX_EVENTS
from ._checker import BatchChecker
from ._claims import Claims
from ._outcome import (MAX_CERTIFICATES, MAX_HORIZON, MAX_SAMPLES, MAX_SEED, MAX_TOTAL_SAMPLES, MAX_TRAJECTORIES, CertificateCheck,
                       CrosscheckReport, default_horizon, sample_times, search_mode, SEARCH_MODES)
from ._property import DEFAULT_RTOL, DEFAULT_THETA
from ._simulate import simulate

__all__ = ["CertificateCheck", "CrosscheckReport", "crosscheck", "default_horizon", "sample_times", "SEARCH_MODES", "search_mode", "GroupRun"]

def _as_claims(items: Iterable[Any], *, require_proved: bool) -> list[tuple[Claims, str, bool | None]]:
    """``(claims, source, proved)`` per item; with ``require_proved`` every certificate is verified exactly first.

    Raises
    ------
    UnprovedCertificateError
        With ``require_proved``, for a certificate that exact verification
        rejects (the message names the file and the failing inequalities), or
        for :class:`Claims` (floats: nothing left to verify).
    """
    from .._certify.certificate import Certificate
    from .._certify.quadratic import QuadraticCertificate
    from .._certify.sup_flow import SupFlowCertificate

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
            cert, source, label = _read(item), str(path), path.stem  # the text as given: 'x.json/' is refused
            if path.parent.name in ("quadratic", "sup_flow"):
                label = f"{path.parent.name}/{label}"  # beside the paper's case_a_tightest etc.
        else:
            cert, source, label = item, "", None
        proved = None
        if require_proved:
            if not isinstance(cert, (Certificate, QuadraticCertificate, SupFlowCertificate)):
                raise UnprovedCertificateError(f"{type(cert).__name__} is not a certificate; it cannot be verified exactly")
            report = _verify(cert, source or "<certificate>")
            if not report.proved:
                raise UnprovedCertificateError(
                    f"{source or 'certificate'} does not verify, refusing to cross-check it: "
                    + "; ".join(check.message for check in report.failures)
                )
            proved = True
        out.append((Claims.from_certificate(cert, label=label), source, proved))
    return out


def _read(path: Any) -> Any:
    """A certificate file of a template whose bound the trajectories can test (the paper's, quadratic or sup-flow).

    Raises
    ------
    CertificateFormatError
        For a file of another template (a box, a hunting cycle), naming why it is not cross-checked.
    """
    from .._certify.templates import read_certificate_file
    from .._infra.errors import CertificateFormatError
    from ._files import CHECKED, SKIPPED

    template, certificate = read_certificate_file(path)
    if template.id not in CHECKED:
        raise CertificateFormatError(f"{path}: " + SKIPPED.get(template.id, f"a {template.id} certificate is not "
                                                                          "cross-checked on trajectories"))
    return certificate


def _verify(certificate: Any, source: str) -> Any:
    """The exact decision of the certificate's own template."""
    from .._certify.quadratic import QuadraticCertificate, verify_quadratic
    from .._certify.sup_flow import SupFlowCertificate, verify_sup_flow
    from .._certify.verify import verify_certificate

    if isinstance(certificate, QuadraticCertificate):
        return verify_quadratic(certificate, source=source)
    if isinstance(certificate, SupFlowCertificate):
        return verify_sup_flow(certificate, source=source)
    return verify_certificate(certificate, source=source)


def crosscheck(
    certificates: Sequence[Any],
    *,
    trajectories: int = 100_000,
    seed: int = 0,
    horizon: float | None = None,
    samples: int = 101,
    rtol: float = DEFAULT_RTOL,
    theta: float = DEFAULT_THETA,
    adversarial: bool = True,
    decay: bool = False,
    iss: bool = False,
    iss_search: tuple = (),
    chunk: int = 1000,
    progress: bool | None = None,
    require_proved: bool = True,
    max_events: int = 10_000,
) -> CrosscheckReport:
    """Check certificates on exact simulated trajectories.

    Examples
    --------
    >>> from symbolic_friction import certify, crosscheck, Parameters
    >>> report = crosscheck([certify(Parameters.table_i("a"), mode="feasible")],
    ...                     trajectories=10, samples=21, adversarial=False, progress=False)
    >>> report.passed
    True
    >>> report.summary()
    'crosscheck: PASSED — 1 certificate(s), 10 trajectories (0 incomplete), ... properties checked (...)'

    Parameters
    ----------
    certificates : sequence
        Certificate objects or paths to certificate files; with
        ``require_proved=False`` also altered copies and :class:`Claims`.
        One certificate or one path is a list of one.
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
    iss_search : tuple of numbers, keyword-only
        With ``iss``: inflations ``ρ`` at which to search the selections of
        ``SGN_ρ`` for the worst found ultimate bound (:mod:`._iss_search`).
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
        Before anything is simulated, if ``trajectories``, ``samples`` (and their product), ``horizon``, ``rtol``,
        ``theta``, ``seed``, ``chunk`` (≥ 1), ``max_events`` or ``iss_search`` is out of range (the bounds of
        :mod:`._outcome`, ``MAX_TRAJECTORIES`` …), or no certificate is given.
    ParameterTypeError
        If ``certificates`` is not a list (``None``, a number, bytes); a single certificate, or a single
        ``str`` or ``pathlib.Path`` (one certificate file), is a list of one.
    InputFileError, CertificateFormatError
        If a certificate file is missing, unreadable or not a certificate (the message names the file).
    UnprovedCertificateError
        If ``require_proved`` and a certificate does not verify exactly.
    """
    from .._certify.certificate import Certificate
    from .._certify.quadratic import Gains  # the certificates of the templates beyond the paper
    from .._infra.progress import Progress

    trajectories = check_count(trajectories, name="trajectories", high=MAX_TRAJECTORIES, why="a bound on time and memory")
    samples = check_count(samples, name="samples", low=3, high=MAX_SAMPLES, why="a bound on memory")
    check_count(trajectories * samples, name="trajectories × samples", high=MAX_TOTAL_SAMPLES, why="samples per gain set, a bound on memory")
    if horizon is not None:
        if isinstance(horizon, bool) or not isinstance(horizon, (int, float)) or not horizon > 0:  # NaN too
            raise ParameterError(f"horizon must be a finite number > 0; got {shown(horizon)}")
        horizon = check_real(horizon, name="horizon", high=MAX_HORIZON, why="a bound on time")
    if not (isinstance(rtol, (int, float)) and 0 < rtol < 1):
        raise ParameterError(f"rtol must be in (0, 1); got {shown(rtol)}")
    if not (isinstance(theta, (int, float)) and 0 < theta <= 1):
        raise ParameterError(f"theta must be in (0, 1]; got {shown(theta)}")
    seed = check_count(seed, name="seed", low=0, high=MAX_SEED, why="with each gain set's offset, below the 2**32 of scipy's optimisers")
    chunk = check_count(chunk, name="chunk", high=MAX_TRAJECTORIES, why="trajectories simulated at a time")
    max_events = check_count(max_events, name="max_events", high=MAX_EVENTS, why="a bound on time and memory per trajectory")
    iss_search = tuple(check_items(iss_search, name="iss_search", what="a tuple of inflations ρ", high=16))
    for i, rho in enumerate(iss_search):
        check_real(rho, name=f"iss_search[{i}]", low=0, low_open=False)
    start = time.perf_counter()
    items = check_items(certificates, name="certificates", high=MAX_CERTIFICATES, single=(str, os.PathLike, Certificate, Gains, Claims),
                        what="a list of certificates or certificate files (a str or pathlib.Path)")
    claims = _as_claims(items, require_proved=require_proved)
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
            T = horizon if horizon is not None else default_horizon(params)
            run = GroupRun(params, [m[0] for m in members], T=T, samples=samples, rtol=rtol, theta=theta,
                            seed=seed + 1000 * gi, chunk=chunk, bar=bar, max_events=max_events)
            run.execute(trajectories, adversarial=adversarial)
            seconds = time.perf_counter() - t0
            ov = run.checker.overshoots()
            src = run.checker.sources()
            modes = np.array([search_mode(str(s)) for s in src], dtype=object)
            finite = np.isfinite(ov)
            max_ov = {m: float(ov[finite & (modes == m)].max()) for m in SEARCH_MODES if np.any(finite & (modes == m))}
            best = int(np.nanargmax(np.where(finite, ov, -np.inf))) if np.any(finite) else 0
            worst = tuple(float(q) for q in run.x0_all[best]) if run.x0_all.size else (0.0, 0.0, 0.0)
            search = run.search
            if search is not None and np.any(np.isfinite(search.ratio)):
                # the peak refined on the closed form can only raise the sampled maximum
                found = float(search.ratio[search.best])
                if found > max_ov.get("adversarial", -np.inf):
                    max_ov["adversarial"] = found
                if found >= max(max_ov.values()):
                    worst = tuple(float(q) for q in search.x0[search.best])
            for (cl, source, proved), results in zip(members, run.checker.results()):
                checks.append(
                    CertificateCheck(
                        claims=cl,
                        source=source,
                        results=tuple(results),
                        trajectories=run.count,
                        horizon=T,
                        max_overshoot=max_ov,
                        worst_state=worst,
                        seconds=seconds,
                        overshoots=ov,
                        initial_distance=run.d0_all,
                        modes=modes,
                        incomplete=run.checker.incomplete,
                        proved=proved,
                        overshoot_search=search,
                    )
                )
            key = members[0][0].label
            if decay:
                from ._overshoot import decay_fit

                decay_fits[key] = decay_fit(params, seed=seed)
            if iss:
                from ._iss import iss_gain

                iss_estimates[key] = iss_gain(params, search_rhos=iss_search)
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


class GroupRun:
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
        self.search: Any = None
        """The :class:`~._overshoot.OvershootSearch` of the run (``None`` without the adversary)."""
        self._x0: list[np.ndarray] = []

    @property
    def x0_all(self) -> np.ndarray:
        return np.concatenate(self._x0) if self._x0 else np.zeros((0, 3))

    @property
    def d0_all(self) -> np.ndarray:
        from .._model.attractor import distance_x

        return distance_x(self.params, self.x0_all) if self._x0 else np.zeros(0)

    def evaluate(
        self, X0: np.ndarray, label: str, *, t: np.ndarray | None = None, attractivity: bool = True
    ) -> np.ndarray:
        """Simulate and check the states ``X0`` (rows, in ``x``); return their overshoots."""
        from .._model.coordinates import x_to_z

        X0 = np.atleast_2d(np.asarray(X0, dtype=float))
        out = []
        for lo in range(0, X0.shape[0], self.chunk):
            part = X0[lo : lo + self.chunk]
            times = self.t if t is None else t
            batch = simulate(
                self.params, x_to_z(self.params, part), float(times[-1]), t_eval=times,
                source=np.full(part.shape[0], label, dtype=object), max_events=self.max_events,
            )
            # the simulator starts from z(0); use the x(0) it actually simulated
            self.checker.add(batch, attractivity=attractivity)
            out.append(self.checker.last_overshoots())
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
            from ._initial import pointwise_extremes, rate_maximisers

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
                if not cl.is_paper:  # V̂ is the paper's template's
                    continue
                X = rate_maximisers(self.params, cl, seed=self.seed + 7 * j, count=min(16, room))
                self.evaluate(X[:room], f"adversarial max V̂'/V̂ on R̂ [{cl.label}]", t=t_short, attractivity=False)
            room = budget - self.count
            if room > 0:
                from ._overshoot import search_overshoot

                # Proposition 1's adversary: direction and scale of x(0), peak refined on the closed form
                self.search = search_overshoot(
                    self.params, lambda X, label: self.evaluate(X, label),
                    budget=max(1, min(room, int(0.1 * budget))), seed=self.seed, t_eval=self.t,
                    max_events=self.max_events,
                )
                s = self.search
                self.checker.add_peaks(s.x0, s.t_peak, s.x_peak, s.scales * float(self.params.f_c))
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
