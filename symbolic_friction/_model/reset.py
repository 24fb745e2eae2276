"""Reset PID: the jump set and the jump map of the integrator reset, in ``x`` and in ``z`` (beyond the paper).

The paper's conclusion leaves "compensation schemes relying on the proposed
Lyapunov-based proof" as future work; Bisoffi et al. (*To stick or to slip: A
reset PID control perspective on positioning systems with friction*, Annu. Rev.
Control 49, 2020) later put resets of the integrator on top of the PID.  The idea
is theirs; the law below is the package's own, derived from ``V`` of eq.
(lyapLikeV):

* at a stick (``v = 0``, ``|φ| ≤ f_c``) ``V = (k_v/k_i)σ²`` (Remark after Lemma 2),
  whatever ``φ`` is in ``[-f_c, f_c]``;
* so a jump of ``e_i`` that moves ``φ`` within ``[-f_c, f_c]`` leaves ``V`` unchanged;
* the jump to ``φ⁺ = f_c·sign(σ)`` ends the stick at once (the appendix's rows
  (iii) and (ix): at ``φ = ±f_c`` with ``σ`` of the same sign the mass slips
  toward the setpoint), and the slip that follows decreases ``V`` strictly
  (Lemma 2, item 2).

The hybrid closed loop, with a timer ``τ`` that excludes Zeno solutions:

* flow set ``C = ℝ³ × [0, τ_d]``, flow map Filippov's ``x' ∈ Ax − b SGN(v)``
  (eq. xDot) and ``τ' ∈ 1 − SGN⁺(τ − τ_d)`` (``τ' = 1`` below ``τ_d``, ``[0, 1]`` at ``τ_d``);
* jump set ``D = {v = 0, |φ| ≤ f_s, σφ ≤ f_c|σ|} × {τ_d}`` (:func:`jump_set_margins`:
  every margin ``≥ 0``; closed, as each margin is continuous);
* jump map ``G(x, τ) = {(σ, f, 0) : f ∈ f_c SGN(σ)} × {0}`` (:func:`jump_map_x`,
  outer semicontinuous: the graph of ``SGN`` is closed).

In ``z = (e_i, s, v)`` (eq. CoC: ``σ = -k_i s``, ``φ = -k_i e_i - k_p s``) the
jump is ``e_i⁺ = (f_c·sign(s) - k_p s)/k_i`` (:func:`jump_map_z`).  With
``f_s = f_c`` the last inequality of ``D`` always holds; with ``f_s > f_c`` it
keeps the jump from moving ``φ`` back from beyond ``sign(σ) f_c``.

The event kernel jumps only when ``φ`` is strictly short of ``sign(σ) f_c``
(a jump from ``φ = sign(σ) f_c`` is the identity) and at ``σ ≠ 0`` (at ``σ = 0``
the state is in 𝒜, an equilibrium).  Every function uses plain arithmetic,
so floats, Fractions and sympy share this one definition (``reset.*``
obligations).
"""

from __future__ import annotations

from typing import Any

__all__ = ["jump_map_x", "jump_map_z", "jump_set_margins", "JUMP_SET_MARGINS"]

JUMP_SET_MARGINS = ("v = 0 (as -v² ≥ 0)", "f_s - |φ| ≥ 0", "f_c|σ| - σφ ≥ 0", "τ - τ_d ≥ 0")
"""What each entry of :func:`jump_set_margins` says."""


def jump_map_x(sigma: Any, phi: Any, v: Any, f_c: Any, sign_sigma: Any) -> tuple[Any, Any, Any]:
    """``G`` in ``x = (σ, φ, v)``: ``(σ, f_c·s, v)`` with ``s`` in ``SGN(σ)`` (``±1``, or any of ``[-1, 1]`` at ``σ = 0``)."""
    del phi
    return sigma, f_c * sign_sigma, v


def jump_map_z(e_i: Any, s: Any, v: Any, k_p: Any, k_i: Any, f_c: Any, sign_s: Any) -> tuple[Any, Any, Any]:
    """``G`` in ``z = (e_i, s, v)``: ``e_i⁺ = (f_c·sign(s) - k_p s)/k_i`` (``sign(σ) = -sign(s)``)."""
    del e_i
    return (f_c * sign_s - k_p * s) / k_i, s, v


def jump_set_margins(sigma: Any, phi: Any, v: Any, abs_sigma: Any, abs_phi: Any, f_c: Any, f_s: Any,
                     tau: Any, dwell: Any) -> tuple[Any, ...]:
    """The margins of ``D``; the state is in ``D`` iff every one is ``≥ 0`` (:data:`JUMP_SET_MARGINS`).

    ``abs_sigma`` and ``abs_phi`` are ``|σ|`` and ``|φ|``, given so that sympy can
    be handed a sign class.
    """
    return -v * v, f_s - abs_phi, f_c * abs_sigma - sigma * phi, tau - dwell
