"""The reset-PID contraction certificate (``reset-contraction/v1``): reset PID settles exponentially (beyond the paper).

Coulomb friction (``f_s = f_c``), ``x = (σ, φ, v)``, ``E(τ) = e^{Aτ}`` (eq. xDot).  A stick ends at ``φ = d·f_c``,
``d = sign σ``; the slip has ``x − d·f_c e₂ = E(τ)σe₁``, so ``v = σE₃₁`` (``E₃₁(0) = E₃₁'(0) = 0``, ``E₃₁'' = (A²E)₃₁``,
``1`` at 0).  The derivation (main verifier: ``_certify/reset_contraction_proof.py``, whose premise names are used;
the reset law: ``_model/reset.py``):

1. [first zero] ``E₃₁ > 0`` on ``(0, τ_lo]`` and ``E₃₁(τ_hi) < 0``: the slip lasts ``τ* ∈ (τ_lo, τ_hi)``, the first
   zero of ``E₃₁``, and ends at ``σ' = σE₁₁(τ*)``, ``φ' = d·f_c + σE₂₁(τ*)`` with ``E₂₁(τ*) = E₃₁'(τ*) ≤ 0``.
2. [contraction] ``|E₁₁| ≤ ρ < 1`` on ``[τ_lo, τ_hi]``: ``|σ_{k+1}| ≤ ρ|σ_k|`` at the stick exits (a jump keeps ``σ``).
3. [overshoot] ``E₁₁ < 0``: ``σ'φ' ≤ 0`` in the stick until the dwell timer allows the reset, at most
   ``max(0, dwell − τ_lo)`` later, if ``radius·(|E₂₁| + ρ·max(0, dwell − τ_lo)) ≤ f_c``; the jump ``φ⁺ = f_c sign σ'``
   ends the stick: exits at most ``max(τ_hi, dwell)`` apart.
4. [no overshoot] ``E₁₁ > 0``: the mass sticks if ``radius·|E₂₁| ≤ 2f_c`` and the stick lasts ``|E₂₁|/E₁₁`` at most
   (a reset only ends it sooner): exits at most ``τ_hi + |E₂₁|/E₁₁`` apart.
5. [settling] ``ρ^cycles ≤ tol`` and ``settling_time ≥ cycles·cycle_time``: ``|σ(t)| ≤ tol·|σ₀|`` from then on.

``E₃₁ > 0`` on ``(0, τ_lo]`` is shown as in :mod:`.hunting`: ``(A²E)₃₁ > 0`` on ``[0, δ]``, ``E₃₁ > 0`` on ``[δ, τ_a]``,
``E₃₁' = (AE)₃₁ < 0`` on ``[τ_a, τ_lo]`` and ``E₃₁(τ_lo) > 0``.  Exact premises in ``Fraction``, the others in arb
balls; undecided is not proved.  The main verifier's format rules (key sets, provenance) are not checked.
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ._core import Malformed, Verdict, _ints, _kept, ball, q
from .hunting import flow, pair, positive, start, system

SHAPE = ("k_i > 0", "k_p > 0", "k_v·k_p > k_i", "f_c > 0", "0 < τ_a < τ_lo < τ_hi", "dwell ≥ 0")
SLIP = ("E31 > 0 on (0, τ_lo]", "E31(τ_hi) < 0", "|E11| ≤ rho on [τ_lo, τ_hi]")
OVERSHOOT = ("E11 < 0 on [τ_lo, τ_hi]", "radius·(|E21| + rho·max(0, dwell − τ_lo)) ≤ f_c on [τ_lo, τ_hi]",
             "cycle_time ≥ max(τ_hi, dwell)")
NO_OVERSHOOT = ("E11 > 0 on [τ_lo, τ_hi]", "radius·|E21| ≤ 2·f_c on [τ_lo, τ_hi]",
                "cycle_time ≥ τ_hi + |E21|/E11 on [τ_lo, τ_hi]")
PREMISES = SHAPE + SLIP + ("rho < 1", "radius > 0") + OVERSHOOT + NO_OVERSHOOT + (
    "rho^cycles ≤ tol", "settling_time ≥ cycles·cycle_time")
MAX_CYCLES = 10_000  # settling.cycles a file may hold (the main reader's bound)


def check(data: dict) -> Verdict:
    """Decide a ``reset-contraction/v1`` file (module docstring)."""
    p, slip, settling, over = data.get("parameters"), data.get("slip"), data.get("settling"), data.get("overshoot")
    if not (isinstance(p, dict) and isinstance(slip, dict) and isinstance(settling, dict) and type(over) is bool):
        raise Malformed("a reset-contraction certificate needs parameters, slip, settling and a boolean overshoot")
    kp, ki, kv, fc = (q(p.get(n)) for n in ("k_p", "k_i", "k_v", "f_c"))
    (lo, hi), ta = pair(slip.get("tau")), q(slip.get("monotone_from"))
    rho, radius, dwell, cycle = (q(data.get(n)) for n in ("rho", "radius", "dwell", "cycle_time"))
    tol, time, cycles = q(settling.get("tol")), q(settling.get("time")), settling.get("cycles")
    if type(cycles) is not int or not 0 <= cycles <= MAX_CYCLES:
        raise Malformed(f"settling.cycles must be an integer in [0, {MAX_CYCLES}]; got {cycles!r:.40}")
    verdict = Verdict("reset-contraction/v1")
    # the model's standing assumptions (Assumption 1, f_c > 0) and the certificate's shape
    shape = [verdict.add(name, holds) for name, holds in zip(SHAPE, (
        ki > 0, kp > 0, kv * kp > ki, fc > 0, 0 < ta < lo < hi, dwell >= 0))]
    kind = OVERSHOOT if over else NO_OVERSHOOT
    old, flint.ctx.prec = flint.ctx.prec, 128
    try:  # the premises on E only where the gains and the interval hold (else they mean nothing: not evaluated)
        flows = _flow((kp, ki, kv), fc, (lo, hi, ta), rho, radius, dwell, cycle) if all(shape) else {}
        for name in SLIP:
            verdict.add(name, flows.get(name), "" if flows else "not evaluated")
        verdict.add("rho < 1", rho < 1)  # step 2
        verdict.add("radius > 0", radius > 0)
        for name in kind[:2]:
            verdict.add(name, flows.get(name), "" if flows else "not evaluated")
        verdict.add(kind[2], cycle >= max(hi, dwell) if over else flows.get(kind[2]))
        # step 5: rho^cycles in arb, exactly when the ball does not decide and the power is short
        power, bound = ball(rho) ** cycles, ball(tol)
        small = True if power <= bound else False if power > bound else None
        # (measured in bits, about 200,000 digits: len(str(rho)) raised past 4300 digits, a traceback for a long rho)
        if small is None and (rho.numerator.bit_length() + rho.denominator.bit_length()) * cycles <= 650_000:
            small = rho ** cycles <= tol
        verdict.add("rho^cycles ≤ tol", small)
        verdict.add("settling_time ≥ cycles·cycle_time", time >= cycles * cycle)
    finally:
        flint.ctx.prec = old
    return verdict


def _flow(gains, fc: Fraction, taus, rho, radius, dwell, cycle) -> dict[str, bool]:
    """Steps 1–4: the premises on ``E``, decided in arb balls, by name."""
    (lo, hi, ta), A = taus, system(*gains)
    # step 1: E31'' > 0 on [0, δ] (E31 = E31' = 0 at 0), E31 > 0 on [δ, τ_a], E31' < 0 on [τ_a, τ_lo], E31(τ_lo) > 0
    delta = start(lambda a, b: (A * A * flow(A, a, b))[2, 0], ta)
    first = delta is not None and _kept(("reset", flint.ctx.prec, _ints(*gains, delta, lo, ta)), lambda: positive(
        lambda a, b: flow(A, a, b)[2, 0], delta, ta) and positive(lambda a, b: -(A * flow(A, a, b))[2, 0], ta, lo)
        and flow(A, lo, lo)[2, 0] > 0)
    E = flow(A, lo, hi)  # every τ of [τ_lo, τ_hi], τ* among them
    e11, e21 = E[0, 0], E[1, 0]
    wait = rho * max(Fraction(0), dwell - lo)  # the longest stick before the timer allows the reset
    return {
        SLIP[0]: first, SLIP[1]: flow(A, hi, hi)[2, 0] < 0,
        SLIP[2]: abs(e11) <= ball(rho),  # step 2: |σ| contracts at the stick exits
        # step 3: after an overshoot σφ ≤ 0 in the stick until the reset, which ends it
        OVERSHOOT[0]: e11 < 0, OVERSHOOT[1]: ball(radius) * (abs(e21) + ball(wait)) <= ball(fc),
        # step 4: without one, the mass sticks, for |E21|/E11 at most
        NO_OVERSHOOT[0]: e11 > 0, NO_OVERSHOOT[1]: ball(radius) * abs(e21) <= 2 * ball(fc),
        NO_OVERSHOOT[2]: ball(cycle - hi) >= abs(e21) / e11,
    }
