"""One gain set's run: simulate its budget of trajectories and check every certificate on them."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._model.parameters import Parameters
from ._checker import BatchChecker
from ._claims import Claims
from ._outcome import sample_times

__all__ = ["GroupRun"]


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
