"""Writes the known-false certificates shipped in ``symbolic_friction/_certify/false_certificates/``.

Each is a true certificate with its numbers edited so that one premise of the
verifier fails (or, where the premises are not independent, that premise and
the ones it implies; ``fails`` lists them all).  Run ``python -m
tests.certify.forge_false_certificates`` to rewrite them; ``test_self_check.py``
checks that the shipped files are what this writes.
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction as F
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
TARGET = REPO / "symbolic_friction" / "_certify" / "false_certificates"

# -- stability certificates: (file stem, premise, base, edits) ----------------------------------------
# A sign premise is broken by a well-formed number of the wrong sign: the format reads it and the verifier
# must refuse it, naming the premise (a file refused as malformed fails the self-check).
STABILITY = [
    ("k_i_positive", "k_i > 0", "a", {"k_i": "-4", "c": "232/5"}),
    ("k_p_positive", "k_p > 0", "a", {"k_p": "-3"}),
    ("assumption1", "k_v·k_p > k_i", "a", {"k_p": "5/8"}),
    ("f_c_positive", "f_c > 0", "a", {"f_c": "-1"}),
    ("c_equation", "c = 2(k_v·k_p − k_i)", "a", {"c": "153/5"}),
    ("c_positive", "c > 0", "a", {"c": "-152/5"}),
    ("c1_positive", "c1 > 0", "a", {"c1": "-1"}),
    ("c1_below_lambda_min", "P − c1·I ⪰ 0", "a", {"c1": "88896553/25000000"}),
    ("c2_above_lambda_max", "c2·I − P ⪰ 0", "a", {"c2": "990099009/1000000000"}),
    ("k1_positive", "k1 > 0", "a", {"k1": "-2"}),
    ("k2_positive", "k2 > 0", "a", {"k2": "-2"}),
    ("k3_positive", "k3 > 0", "a", {"k3": "-101/50"}),
    ("k4_positive", "k4 > 0", "a", {"k4": "-303/50"}),
    ("k3_over_k1", "k3 > (k_i/k_v)·k1", "a", {"k1": "101/25", "c2_hat": "4", "overshoot_bound": "3.8"}),
    ("k3_over_k2", "k3 > k2", "a", {"k3": "2"}),
    ("k4_over_k3", "k4 > (k_i/k_v)·k3", "a", {"k2": "1/10", "k4": "101/80", "c1_hat": "1/20", "overshoot_bound": "16"}),
    ("k4_over_k2", "k4 > k_p·k2", "a", {"k4": "6"}),
    ("k_definite", "k1·k4 > k3²", "a", {"k1": "1/2", "c1_hat": "1/4", "overshoot_bound": "7.1"}),
    ("c1_hat_positive", "c1_hat > 0", "a", {"c1_hat": "-1"}),
    ("c1_hat_k1", "c1_hat ≤ k1/2", "a", {"k1": "19/10"}),
    ("c1_hat_k2", "c1_hat ≤ k2/2", "a", {"k2": "19/10"}),
    ("c1_hat_k4", "c1_hat ≤ k4/2", "b", {"k4": "19/10", "k1": "5/2", "c2_hat": "3", "overshoot_bound": "9.8"}),
    ("c2_hat_above_K", "c2_hat·I − K/2 ⪰ 0", "a", {"c2_hat": "1"}),
    ("c1_above_c2", "c1 ≤ c2", "a", {"c1": "4"}),
    ("c1_hat_above_c2_hat", "c1_hat ≤ c2_hat", "a", {"c2_hat": "1/2"}),
    ("kappa_positive", "overshoot_bound > 0", "a", {"overshoot_bound": "-3.51842"}),
    ("kappa_too_small", "overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)", "a", {"overshoot_bound": "3.5"}),
]


# -- quadratic certificates: (file stem, premise, edits: constant or gain -> factor, or the bound) -----------
QUADRATIC = [
    ("k_i_positive", "k_i > 0", {"k_i": -1}),
    ("k_p_positive", "k_p > 0", {"k_p": -1}),
    ("assumption1", "k_v·k_p > k_i", {"k_p": F(1, 10)}),
    ("f_c_positive", "f_c > 0", {"f_c": -1}),
    ("p_lower", "P − I ⪰ 0", {"p11": F(99, 100)}),
    ("p_upper", "c2·I − P ⪰ 0", {"c2": 0}),
    ("c_positive", "c > 0", {"c": 0}),
    ("v_decrease", "−(AᵀP + PA) − c·e3e3ᵀ ⪰ 0", {"k_p": F(1, 2)}),
    ("u_rate_plus", "−(K·B+ + B+ᵀ·K) copositive", {"k22": 2}),
    ("band_plus", "band form (s = +1) copositive", {"k11": -100}),
    ("u_rate_minus", "−(K·B− + B−ᵀ·K) copositive", {"k22": F(101, 100)}),
    ("band_minus", "band form (s = −1) copositive", {"k11": F(1001, 1000)}),
    ("k31", "K31 ≥ 0", {"k13": F(-999, 1000)}),
    ("k32", "K32 ≥ 0", {"k23": -1}),
    ("k33", "K33 ≥ 0", {"k33": F(-1, 10)}),
    ("u_lower", "K − I copositive", {"k22": 0}),
    ("u_upper", "gamma·I − K copositive", {"gamma": 0}),
    ("exit_rest", "U − V copositive at v = 0", {"k22": F(999, 1000)}),
    ("exit_edge", "U − V copositive at φ = ±f_c", {"k11": F(9, 10)}),
    ("kappa_positive", "overshoot_bound > 0", {"overshoot_bound": "-1.80834"}),
    ("kappa_c2", "overshoot_bound² ≥ c2", {"c2": 2}),
    ("kappa_gamma", "overshoot_bound² ≥ gamma", {"gamma": 2}),
]


# -- sup-flow certificates: the premises only this template has (the ones it shares with the quadratic template --
# Assumption 1, the rate, band and K3j premises, gamma, the bound -- are decided by the same functions and broken by
# the quadratic files), each on a small true certificate with room
SUP_FLOW = [
    ("first_start", "the first piece starts at t = 0", lambda d: d["pieces"][0].update(start="1/1000")),
    ("gap", "piece 3 starts where piece 2 ends", lambda d: d["pieces"][2].update(start="21/10")),
    ("last_end", "the last piece ends at ∞", lambda d: d["pieces"][-1].update(end="1000")),
    ("horizon", "T ≥ 0 (the last piece starts at or after 0)", lambda d: d.update(pieces=[dict(d["pieces"][-1], start="-1")])),
    # the tail's own P: the paper's P written out, with p above its least eigenvalue; then I, which no A makes a
    # Lyapunov matrix (−(A + Aᵀ) has a zero diagonal entry beside a non-zero one)
    ("tail_lower", "P − p·I ⪰ 0 (the tail's P)", lambda d: d["constants"].update(_tail((1, 0, -1, 1, 0, 11)), p="10")),
    ("tail_rate", "−(AᵀP + PA) ⪰ 0 (the tail's P)", lambda d: d["constants"].update(_tail((1, 0, 0, 1, 0, 1)), p="1")),
    ("p_positive", "p > 0", lambda d: d["constants"].update(p="0")),
    ("p_lower", "P − p·I ⪰ 0 (the paper's P)", lambda d: d["constants"].update(p="10")),
    ("c2_flow", "c2 ≥ ‖e^(At)‖² for every t ≥ 0", lambda d: d["constants"].update(c2="1")),
    ("u_lower", "K1 − I copositive (piece 1)", lambda d: _scale(d["pieces"][0], F(1, 100))),
    # K = 0 keeps every cone premise of the piece: only the exit premise, decided on the enclosures, can fail
    ("exit", "piece 2: U ≥ |e^(At)w|² on the exits of R̂ for t in [2, 4)", lambda d: _scale(d["pieces"][1], F(0))),
    ("exit_tail", "piece 5: U ≥ |e^(At)w|² on the exits of R̂ for t in [8, ∞)", lambda d: _scale(d["pieces"][-1], F(0))),
]


def _tail(entries: tuple[int, ...]) -> dict[str, str]:
    """The tail's own ``P`` (entries 11, 12, 13, 22, 23, 33) as a file's constants."""
    return {f"tail_p{ij}": str(e) for ij, e in zip(("11", "12", "13", "22", "23", "33"), entries)}


def _single_piece(base: dict) -> dict:
    """``base`` with one piece ``[0, ∞)``, the tail at ``T = 0`` (true: the tail form at ``T = 0`` is ``P/p``)."""
    data = copy.deepcopy(base)
    data["pieces"] = [dict(data["pieces"][-1], start="0")]
    return data


def _scale(piece: dict, factor: F) -> None:
    from symbolic_friction._infra.rational import format_rational

    for name in ("k11", "k13", "k22", "k23", "k33"):
        piece[name] = format_rational(F(piece[name]) * factor)


def _sup_flow_base() -> dict:
    """A true sup-flow certificate that verifies in a few parts: gains with roots −1, −2, −3 (a short horizon),
    five pieces, and ``K``, ``γ``, ``c₂`` doubled so that every premise has room."""
    from symbolic_friction import Parameters
    from symbolic_friction._certify.rounding import sqrt_decimal_up
    from symbolic_friction._certify.sup_flow import dumps_sup_flow
    from symbolic_friction._certify.sup_flow_search import Layout, certify_sup_flow
    from symbolic_friction._infra.rational import format_rational

    data = json.loads(dumps_sup_flow(certify_sup_flow(Parameters(k_p=11, k_i=6, k_v=6, f_c=1), max_pieces=3, rel_tol=0.5,
                                                      layout=Layout(version=1))))
    del data["provenance"]
    for piece in data["pieces"]:
        _scale(piece, F(2))
        piece["gamma"] = format_rational(F(piece["gamma"]) * 2)
    data["constants"]["c2"] = format_rational(F(data["constants"]["c2"]) * 2)
    data["overshoot_bound"] = sqrt_decimal_up(max([F(data["constants"]["c2"])] + [F(q["gamma"]) for q in data["pieces"]]))
    return data


# -- sup-flow/v2 certificates: the premises only version 2 has (the frame it shares with version 1 -- Assumption 1, the
# pieces, the tail's P -- is decided by the same function and broken by the sup-flow files), on a one-piece true certificate
# [0, ∞) with the friction-drag split (the tail at T = 0), its split [0, 1/2) + [1/2, ∞) (a finite piece), and one without
# the split (ℓ = 0: then the exits are version 1's planes only): (file stem, premise, base, edit of the parsed file).
# Where a premise is implied by others it fails with them (the comments say why), and the manifest lists them all.
V2_ELL = (F(1, 100), F(1, 100), F(1, 100))
"""``ℓ`` of the shipped version-2 files: the search's ``(1/1000, 0, 1/1000)`` raised, which adds ``Ke₃ℓᵀ + ℓe₃ᵀK ≥ 0``
(entrywise: ``K₃ⱼ ≥ 0``) to every drag rate and band form, so that the forms the SDP left on the boundary have room."""
V2_WIDE_ELL = (F(1, 10), F(1, 10), F(1, 10))
"""A larger ``ℓ`` for the exit files: it widens the gap between the drag exit form and the planes' forms."""
SUP_FLOW_V2 = [
    # ℓ₁ < 0 makes the band forms' (1, 1) entry 2K₁₃ℓ₁ negative for both signs (K₁₃ > 0): they fail with it
    ("ell1_negative", "ell1 ≥ 0", "one", lambda d: _v2_set(d, c={"ell1": F(-1, 10**6)})),
    ("ell2_negative", "ell2 ≥ 0", "one", lambda d: _v2_set(d, c={"ell2": F(-1, 10**6)})),
    ("ell3_negative", "ell3 ≥ 0", "one", lambda d: _v2_set(d, c={"ell3": F(-1, 10**6)})),
    # c2 between sup‖e^(At)‖² (here λ_max(P/p), the tail at T = 0) and the drag maps' λ_max(D_ℓᵀPD_ℓ/p)
    ("c2_drag", "c2 ≥ ‖e^(At)‖² for every t ≥ 0 and c2 ≥ ‖e^(At)·D_ℓ‖² (both signs)", "one",
     lambda d: _v2_set(d, c={"c2": _v2_c2_between(d)})),
    # K±₁₁ < 1: the exits at t = 0 (G = P/p ⪰ I) need K₁₁ ≥ G₁₁ ≥ 1, so the exit premise fails with it
    ("u_lower_plus", "K+1 − I copositive (piece 1)", "one", lambda d: _v2_set(d, p={"kp11": F(9, 10)})),
    ("u_lower_minus", "K−1 − I copositive (piece 1)", "one", lambda d: _v2_set(d, p={"km11": F(9, 10)})),
    # K⁺₁₂ < 0 keeps the drag rate form's (1, 1) entry 2K₁₂ + 2K₁₃ℓ₁ ≥ 0; K₂₃ raised makes up the (2, 3) entry it took
    ("k12_plus", "piece 1: K+12 ≥ 0", "one", lambda d: _v2_set(d, p={"kp12": F(-1, 1000), "kp23": _v2(d, "kp23") + 2})),
    ("k12_minus", "piece 1: −K−12 ≥ 0", "one",
     lambda d: _v2_set(d, p={"km12": F(1, 1000), "km23": _v2(d, "km23") + F(1, 4)})),
    ("rate_plus", "piece 1: drag rate form of K+ (s = +1) copositive", "one", lambda d: _v2_set(d, p={"kp12": 0})),
    ("rate_minus", "piece 1: drag rate form of K− (s = −1) copositive", "one", lambda d: _v2_set(d, p={"km12": 0})),
    # the band form of s = +1 is copositive when K₁₁, K₁₃, K₃₃, ℓ ≥ 0, and K₁₁ ≥ 0 is implied by the exits: K⁺₁₃ < 0
    # is the least that breaks it (with K+31 ≥ 0)
    ("band_plus", "piece 1: drag band form of K+ (s = +1) copositive", "one", lambda d: _v2_set(d, p={"kp13": F(-1, 10**6)})),
    ("band_minus", "piece 1: drag band form of K− (s = −1) copositive", "one",
     lambda d: _v2_set(d, p={"km11": _v2(d, "km11") * F(11, 10)})),
    # K⁺₁₃ < 0 with ℓ₁ = 0 (else the band form's (1, 1) entry 2K₁₃ℓ₁ < 0), and K⁻₁₁ lowered so that the band form of
    # s = −1 keeps its off-diagonal entry −k_i·K₁₁ + (k_v + ℓ₃)·K₁₃ ≥ 0 without ℓ₁
    ("k31_plus", "piece 1: K+31 ≥ 0", "one", lambda d: _v2_set(
        d, c={"ell1": 0}, p={"kp13": F(-1, 10**6), "km11": _v2(d, "km13") * (F(d["parameters"]["k_v"]) + F(d["constants"]["ell3"]))
                             / F(d["parameters"]["k_i"]) * F(999, 1000)})),
    # K⁻₁₃ < 0 breaks the band form of s = −1: its (1, 1) entry 2K₁₃ℓ₁ < 0, or with ℓ₁ = 0 its off-diagonal entry
    # −k_i·K₁₁ + (k_v + ℓ₃)·K₁₃ < 0; K⁻₁₃ also carries the rate form of s = −1 (it fails too)
    ("k31_minus", "piece 1: K−31 ≥ 0", "one", lambda d: _v2_set(d, p={"km13": F(-1, 10**6)})),
    # K₂₃ < 0 is the rate form's (2, 2) entry 2K₂₃(1 + ℓ₂) < 0; K⁺₃₃ raised keeps the coupling
    ("k32_plus", "piece 1: K+32 ≥ 0", "one", lambda d: _v2_set(d, p={"kp23": F(-1, 10**6), "kp33": _v2(d, "kp33") + F(1, 10)})),
    ("k32_minus", "piece 1: K−32 ≥ 0", "one", lambda d: _v2_set(d, p={"km23": F(-1, 10**6)})),
    # K₃₃ < 0: the exit at φ = f_c needs K₃₃ ≥ G₃₃ > 0, K − I its diagonal, the coupling K⁺₃₃ ≥ K⁻₃₃
    ("k33_plus", "piece 1: K+33 ≥ 0", "one", lambda d: _v2_set(d, p={"kp33": F(-1, 10**6)})),
    ("k33_minus", "piece 1: K−33 ≥ 0", "one", lambda d: _v2_set(d, p={"km33": F(-1, 10**6)})),
    # K⁺ scaled up (every cone premise and the coupling are kept, the exits only gain); γ between K⁺'s least γ and K⁻'s
    ("u_upper_plus", "piece 1: gamma·I − K+ copositive", "one", lambda d: _v2_scale(d, 0, plus=F(6, 5))),
    ("u_upper_minus", "piece 1: gamma·I − K− copositive", "one", lambda d: _v2_set(d, p={"gamma": _v2_gamma_between(d)})),
    # K⁻ scaled up: U⁻ > U⁺ on σ = 0 (every other premise of the piece is kept, γ has room)
    ("coupling", "piece 1: coupling (K+ − K−) on (|dz φ|, |v|) copositive", "one", lambda d: _v2_scale(d, 0, minus=F(21, 20))),
    # K± scaled to just above where the planes bind (1/2 of the doubled K), below where the drag exit form of s = −1
    # does: only that form fails
    ("exit_tail", "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [0, ∞)", "one",
     lambda d: _v2_scale(d, 0, plus=F(501, 1000), minus=F(501, 1000))),
    # a finite piece: K± of [0, 1/2) scaled so that the planes hold on the whole piece and, with the wider ℓ, the drag
    # exit form of s = −1 does not (near t = 0.02)
    ("exit", "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [0, 1/2)", "two",
     lambda d: (_v2_set(d, c=_ell(V2_WIDE_ELL)), _v2_scale(d, 0, plus=F(9, 20), minus=F(9, 20)))),
    # past T = 1/2, K⁻ scaled below the planes' bound at y = e₁ (K⁻₁₁ ≥ G₁₁), where the drag exit form is lower
    # (w = (−y₁, −ℓ₁y₁, 0) there): only the planes of s = −1 fail, the drag exit form holds
    ("exit_plane", "piece 2: U± ≥ |e^(At)w|² on the exits of R̂ and of f > ℓᵀy for t in [1/2, ∞)", "two",
     lambda d: (_v2_set(d, c=_ell(V2_WIDE_ELL)), _v2_scale(d, 1, minus=F(43, 100)))),
    ("exit_no_drag", "piece 1: U± ≥ |e^(At)w|² on the exits of R̂ for t in [0, ∞)", "no_drag",
     lambda d: _v2_scale(d, 0, plus=F(49, 100), minus=F(49, 100))),
    ("kappa_positive", "overshoot_bound > 0", "one", lambda d: d.update(overshoot_bound="-" + d["overshoot_bound"])),
    ("kappa_c2", "overshoot_bound² ≥ c2", "one", lambda d: _v2_set(d, c={"c2": F(d["overshoot_bound"]) ** 2 * F(1001, 1000)})),
    ("kappa_gamma", "overshoot_bound² ≥ gamma (piece 1)", "one",
     lambda d: _v2_set(d, p={"gamma": F(d["overshoot_bound"]) ** 2 * F(1001, 1000)})),
]
_V2_ENTRIES = ("11", "12", "13", "22", "23", "33")


def _ell(ell: tuple) -> dict:
    return {f"ell{j + 1}": ell[j] for j in range(3)}


def _v2(data: dict, name: str, piece: int = 0) -> F:
    return F(data["pieces"][piece][name])


def _v2_set(data: dict, *, c: dict | None = None, p: dict | None = None, piece: int = 0) -> None:
    from symbolic_friction._infra.rational import format_rational

    data["constants"].update({k: format_rational(F(v)) for k, v in (c or {}).items()})
    data["pieces"][piece].update({k: format_rational(F(v)) for k, v in (p or {}).items()})


def _v2_scale(data: dict, piece: int, *, plus: F = F(1), minus: F = F(1)) -> None:
    """``K⁺`` and ``K⁻`` of ``piece`` times ``plus`` and ``minus`` (every cone premise of a form is homogeneous in it)."""
    _v2_set(data, piece=piece, p={tag + e: _v2(data, tag + e, piece) * factor
                                  for tag, factor in (("kp", plus), ("km", minus)) for e in _V2_ENTRIES})


def _v2_c2_between(data: dict) -> F:
    """A ``c₂`` above ``λ_max(P/p)`` (the flow's bound past ``T = 0``) and below ``λ_max(D_ℓᵀPD_ℓ/p)`` for some sign."""
    import numpy as np

    from symbolic_friction._certify.sup_flow_v2 import SupFlowCertificateV2

    cert = SupFlowCertificateV2.from_dict(data)
    gram = np.array(cert.tail_matrix(), dtype=float) / float(cert.constants["p"])
    plain = float(np.linalg.eigvalsh(gram)[-1])
    drag = max(float(np.linalg.eigvalsh(np.array(d, dtype=float).T @ gram @ np.array(d, dtype=float))[-1])
               for _, d in cert.drag_maps())
    c2 = F(round((plain + drag) / 2 * 10**4), 10**4)
    assert plain * (1 + 1e-5) < c2 < drag * (1 - 1e-5), (plain, c2, drag)
    return c2


def _least_gamma(k: tuple) -> F:
    """The least ``γ`` with ``γI − K`` copositive, to within 2⁻⁴⁰ of its bound (bisection, exact decisions)."""
    from symbolic_friction._certify.copositive import decide_copositive

    lo, hi = F(0), F(sum(abs(x) for row in k for x in row))
    for _ in range(40):
        mid = (lo + hi) / 2
        if decide_copositive([[(mid if i == j else 0) - k[i][j] for j in range(3)] for i in range(3)]).holds:
            hi = mid
        else:
            lo = mid
    return hi


def _v2_gamma_between(data: dict) -> F:
    """A ``γ`` above ``K⁺``'s least ``γ`` and below ``K⁻``'s (piece 1)."""
    from symbolic_friction._certify.sup_flow_v2 import SupFlowCertificateV2

    piece = SupFlowCertificateV2.from_dict(data).pieces[0]
    plus, minus = _least_gamma(piece.form(1)), _least_gamma(piece.form(-1))
    gamma = F(round((plus + minus) * 500), 1000)
    assert plus < gamma < minus, (plus, gamma, minus)
    return gamma


def _sup_flow_v2_bases() -> dict[str, dict]:
    """True version-2 certificates with room, from the one-piece search (:func:`.sup_flow_tail.certify_sup_flow_tail`:
    the tail's own ``P`` at ``T = 0``; a certificate of pieces takes ten times as long to verify) on the gains of the
    sup-flow files: ``"one"`` with the drag split, ``"two"`` the same split at ``t = 1/2`` (the tail's ``K`` holds on any
    finite piece: ``|e^(At)w|² ≤ |w|²_P/p``), ``"no_drag"`` searched with ``ℓ = 0``.  ``K±`` and ``c₂`` doubled, ``γ``
    times 11/5 and (with the drag split) ``ℓ`` raised to :data:`V2_ELL`, so that every premise has room."""
    from symbolic_friction import Parameters
    from symbolic_friction._certify.rounding import sqrt_decimal_up
    from symbolic_friction._certify.sup_flow import dumps_sup_flow
    from symbolic_friction._certify.sup_flow_search import ELL, Layout
    from symbolic_friction._certify.sup_flow_tail import certify_sup_flow_tail
    from symbolic_friction._infra.rational import format_rational

    gains = Parameters(k_p=11, k_i=6, k_v=6, f_c=1)
    bases = {}
    for key, ell in (("one", ELL), ("no_drag", (F(0), F(0), F(0)))):
        data = json.loads(dumps_sup_flow(certify_sup_flow_tail(gains, layout=Layout(version=2, ell=ell))))
        del data["provenance"]
        _v2_scale(data, 0, plus=F(2), minus=F(2))
        _v2_set(data, c={"c2": F(data["constants"]["c2"]) * 2, **(_ell(V2_ELL) if any(ell) else {})},
                p={"gamma": _v2(data, "gamma") * F(11, 5)})
        data["overshoot_bound"] = sqrt_decimal_up(max(F(data["constants"]["c2"]), _v2(data, "gamma")))
        bases[key] = data
    two = copy.deepcopy(bases["one"])
    two["pieces"] = [dict(two["pieces"][0], end=format_rational(F(1, 2))), dict(two["pieces"][0], start=format_rational(F(1, 2)))]
    bases["two"] = two
    return bases


def _quadratic(edits: dict | None = None) -> dict:
    from symbolic_friction._infra.rational import format_rational

    data = json.loads((REPO / "proofs" / "quadratic" / "case_a.json").read_text(encoding="utf-8"))
    del data["provenance"]
    for key, factor in (edits or {}).items():
        if key == "overshoot_bound":
            data[key] = factor
            continue
        group = "parameters" if key in data["parameters"] else "constants"
        data[group][key] = format_rational(F(data[group][key]) * factor)
    return data


def _stability_base(case: str) -> dict:
    data = json.loads((REPO / "proofs" / f"case_{case}_feasible.json").read_text(encoding="utf-8"))
    del data["provenance"]  # a forged file claims nothing about its origin
    return data


def _edit(data: dict, edits: dict) -> dict:
    out = copy.deepcopy(data)
    for key, value in edits.items():
        if key == "overshoot_bound":
            out[key] = value
        elif key in out["parameters"]:
            out["parameters"][key] = value
        else:
            out["constants"][key] = value
    return out


def _text(data: dict) -> str:
    return json.dumps(data, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def forged() -> tuple[dict[str, str], list[dict]]:
    """``({file name: text}, manifest entries)``."""
    from symbolic_friction._certify.self_check import expected_failures

    files: dict[str, str] = {}
    manifest: list[dict] = []
    control = _stability_base("a")
    files["true_stability.json"] = _text(control)
    manifest.append({"file": "true_stability.json", "template": "stability", "premise": None, "fails": []})
    for stem, premise, case, edits in STABILITY:
        data = _edit(_stability_base(case), edits)
        name = f"stability_{stem}.json"
        files[name] = _text(data)
        manifest.append({"file": name, "template": "stability", "premise": premise, "fails": expected_failures(data)})
    files["true_quadratic.json"] = _text(_quadratic())
    manifest.append({"file": "true_quadratic.json", "template": "quadratic", "premise": None, "fails": []})
    for stem, premise, edits in QUADRATIC:
        data = _quadratic(edits)
        name = f"quadratic_{stem}.json"
        files[name] = _text(data)
        manifest.append({"file": name, "template": "quadratic", "premise": premise, "fails": expected_failures(data)})
    base = _sup_flow_base()
    files["true_sup_flow.json"] = _text(base)
    manifest.append({"file": "true_sup_flow.json", "template": "sup-flow", "premise": None, "fails": []})
    files["true_sup_flow_single.json"] = _text(_single_piece(base))
    manifest.append({"file": "true_sup_flow_single.json", "template": "sup-flow", "premise": None, "fails": []})
    for stem, premise, edit in SUP_FLOW:
        data = copy.deepcopy(base)
        edit(data)
        name = f"sup-flow_{stem}.json"
        files[name] = _text(data)
        manifest.append({"file": name, "template": "sup-flow", "premise": premise, "fails": expected_failures(data)})
    v2 = _sup_flow_v2_bases()
    for key, suffix in (("one", ""), ("two", "_pieces"), ("no_drag", "_no_drag")):
        name = f"true_sup_flow_v2{suffix}.json"
        files[name] = _text(v2[key])
        manifest.append({"file": name, "template": "sup-flow/v2", "premise": None, "fails": []})
    for stem, premise, key, edit in SUP_FLOW_V2:
        data = copy.deepcopy(v2[key])
        edit(data)
        name = f"sup-flow-v2_{stem}.json"
        files[name] = _text(data)
        manifest.append({"file": name, "template": "sup-flow/v2", "premise": premise, "fails": expected_failures(data)})
    for name, premise, data in _reset_contraction():
        files[name] = _text(data)
        manifest.append({"file": name, "template": "reset-contraction", "premise": premise,
                         "fails": [] if premise is None else expected_failures(data)})
    for name, premise, data in _hunting():
        files[name] = _text(data)
        manifest.append({"file": name, "template": "hunting", "premise": premise,
                         "fails": [] if premise is None else _hunting_failures(data)})
    return files, manifest


def _hunting():
    from symbolic_friction import Parameters
    from symbolic_friction._certify.hunting import certificate_for
    from symbolic_friction._certify.hunting_cycle import polish

    p = Parameters(k_p=3, k_i=4, k_v="32/5", f_c=1, f_s="6/5")
    true, _ = certificate_for(p, 0.10504486800579656, 2.6531212420323778)
    base = true.to_dict()
    yield "true_hunting.json", None, base
    (s_lo, s_hi), (t_lo, t_hi) = true.box.sigma, true.box.tau
    ws, wt = s_hi - s_lo, t_hi - t_lo

    def box(**edits):
        d = copy.deepcopy(base)
        del d["cycle"]  # a forged box claims no cycle numbers: its refusal names the proof's step only
        for key, (lo, hi) in edits.items():
            d["box"][key] = [str(lo), str(hi)] if key != "monotone_from" else str(lo)
        return d

    later, _ = certificate_for(p, *polish(p, 0.02355118, 9.962899))  # a zero of F after a sign change of v
    d = later.to_dict()
    del d["cycle"]
    yield "hunting_later_zero.json", "first_zero.positive", d
    yield "hunting_no_fixed_point.json", "krawczyk", box(sigma=(s_lo + 2 * ws, s_hi + 2 * ws))
    shift = ws * F(6, 10)
    yield "hunting_zero_above_sigma.json", "krawczyk", box(sigma=(s_lo - shift, s_hi - shift))
    yield "hunting_zero_below_sigma.json", "krawczyk", box(sigma=(s_lo + shift, s_hi + shift))
    shift = wt * F(6, 10)
    yield "hunting_zero_above_tau.json", "krawczyk", box(tau=(t_lo - shift, t_hi - shift))
    yield "hunting_zero_below_tau.json", "krawczyk", box(tau=(t_lo + shift, t_hi + shift))
    yield "hunting_sigma_not_positive.json", "box", box(sigma=(F(0), s_hi))
    yield "hunting_monotone_too_early.json", "first_zero.decreasing", box(monotone_from=(F(1, 10), None))
    yield "hunting_start_unshown.json", "first_zero.start", box(sigma=(F(1, 10), F(10) ** 30))
    for field, value in [("period", ["99", "99"]), ("stick_time", ["20", "41/2"]), ("slip_time", ["2", "5/2"]),
                         ("sigma", ["1/10", "21/200"]), ("multiplier", ["0", "1/20"]), ("stable", False)]:
        d = copy.deepcopy(base)
        d["cycle"][field] = value
        yield f"hunting_cycle_{field}.json", f"cycle.{field}", d
    d = copy.deepcopy(base)
    d["verdict"] = "not proved"
    yield "hunting_verdict.json", "verdict", d


# -- reset-contraction certificates: (file stem, premise, edit) on Table I (a) (an overshoot), then on gains without one --
RESET_OVERSHOOT = [
    ("k_i_positive", "k_i > 0", lambda d: d["parameters"].update(k_i="-4")),
    ("k_p_positive", "k_p > 0", lambda d: d["parameters"].update(k_p="-3")),
    ("assumption1", "k_v·k_p > k_i", lambda d: d["parameters"].update(k_p="5/8")),
    ("f_c_positive", "f_c > 0", lambda d: d["parameters"].update(f_c="-1")),
    ("interval", "0 < τ_a < τ_lo < τ_hi", lambda d: d["slip"].update(tau=d["slip"]["tau"][::-1])),
    ("dwell", "dwell ≥ 0", lambda d: d.update(dwell="-1")),
    # E₃₁ falls on [1, τ_lo]? it rises there: the monotone part fails
    ("monotone_too_early", "E31 > 0 on (0, τ_lo]", lambda d: d["slip"].update(monotone_from="1")),
    # the interval one width below τ*: E₃₁ is still positive at τ_hi
    ("slip_not_ended", "E31(τ_hi) < 0", lambda d: d["slip"].update(tau=_shift(d["slip"]["tau"], -2))),
    # ρ one unit of the sixth digit below what is proved: |E₁₁(τ*)| = 0.45863270… > 0.458632
    ("rho_below", "|E11| ≤ rho on [τ_lo, τ_hi]", lambda d: d.update(rho="57329/125000")),
    ("rho_one", "rho < 1", lambda d: d.update(rho="1")),
    ("radius_positive", "radius > 0", lambda d: d.update(radius="-" + d["radius"])),
    # claiming no overshoot where there is one: only the sign fails (the other two premises get weaker)
    ("no_overshoot_claimed", "E11 > 0 on [τ_lo, τ_hi]", lambda d: d.update(overshoot=False)),
    ("radius", "radius·(|E21| + rho·max(0, dwell − τ_lo)) ≤ f_c on [τ_lo, τ_hi]", lambda d: d.update(radius="14")),
    ("cycle_time", "cycle_time ≥ max(τ_hi, dwell)", lambda d: d.update(cycle_time="4")),
    ("cycles", "rho^cycles ≤ tol", lambda d: d["settling"].update(cycles=d["settling"]["cycles"] - 1)),
    ("settling_time", "settling_time ≥ cycles·cycle_time", lambda d: d["settling"].update(time="37")),
]
RESET_DWELL = [
    # a dwell longer than the slip with dwell 0's radius: the stick may outlast σφ ≤ 0 before the timer allows the reset
    ("dwell_radius", "radius·(|E21| + rho·max(0, dwell − τ_lo)) ≤ f_c on [τ_lo, τ_hi]", lambda d: d.update(radius="131077/10000")),
    ("dwell_cycle_time", "cycle_time ≥ max(τ_hi, dwell)", lambda d: d.update(cycle_time="206811/50000")),
]
RESET_NO_OVERSHOOT = [
    # the overshoot's radius premise is f_c, not 2f_c: the radius halved keeps it, so only the sign fails
    ("overshoot_claimed", "E11 < 0 on [τ_lo, τ_hi]", lambda d: d.update(overshoot=True, radius=_half(d["radius"]))),
    ("no_overshoot_radius", "radius·|E21| ≤ 2·f_c on [τ_lo, τ_hi]", lambda d: d.update(radius="3")),
    ("no_overshoot_cycle_time", "cycle_time ≥ τ_hi + |E21|/E11 on [τ_lo, τ_hi]",
     lambda d: d.update(cycle_time=_plus(d["slip"]["tau"][1], 1))),
]
NO_OVERSHOOT_GAINS = {"k_p": 1, "k_i": F(1, 5), "k_v": F(3, 10)}
"""Gains whose slip from a stick ends with E₁₁(τ*) ≈ 0.201 > 0: the stick after it lasts |E₂₁|/E₁₁ ≈ 3.76."""


def _shift(tau: list[str], widths: int) -> list[str]:
    from symbolic_friction._infra.rational import format_rational

    lo, hi = F(tau[0]), F(tau[1])
    return [format_rational(lo + widths * (hi - lo)), format_rational(hi + widths * (hi - lo))]


def _half(value: str) -> str:
    from symbolic_friction._infra.rational import format_rational

    return format_rational(F(value) / 2)


def _plus(value: str, amount: int) -> str:
    from symbolic_friction._infra.rational import format_rational

    return format_rational(F(value) + amount)


def _reset_contraction():
    """The true reset-contraction certificates, then one false one per premise (see :data:`RESET_OVERSHOOT`)."""
    from symbolic_friction import Parameters
    from symbolic_friction._certify.reset_contraction import candidate_at, certify_contraction, dumps_contraction

    def plain(cert) -> dict:
        data = json.loads(dumps_contraction(cert))
        del data["provenance"]  # a forged file claims nothing about its origin
        return data

    a = Parameters.table_i("a")
    bases = {"": plain(certify_contraction(a)), "_dwell": plain(certify_contraction(a, dwell=6)),
             "_no_overshoot": plain(certify_contraction(Parameters(**NO_OVERSHOOT_GAINS)))}
    for suffix, base in bases.items():
        yield f"true_reset_contraction{suffix}.json", None, base
    for suffix, edits in (("", RESET_OVERSHOOT), ("_dwell", RESET_DWELL), ("_no_overshoot", RESET_NO_OVERSHOOT)):
        for stem, premise, edit in edits:
            data = copy.deepcopy(bases[suffix])
            edit(data)
            yield f"reset-contraction_{stem}.json", premise, data
    # the box around the third zero of E₃₁ (the second where it falls), with that zero's own numbers
    yield "reset-contraction_later_zero.json", "E31 > 0 on (0, τ_lo]", plain(candidate_at(a, 12.06696030550267))


def _hunting_failures(data: dict) -> list[str]:
    from symbolic_friction._certify.hunting import hunting_from_data, verify_hunting
    from symbolic_friction._certify.self_check import named_failures

    return named_failures(verify_hunting(hunting_from_data(data)))


def write() -> None:
    files, manifest = forged()
    TARGET.mkdir(exist_ok=True)
    for old in TARGET.glob("*.json"):
        old.unlink()
    for name, text in files.items():
        (TARGET / name).write_text(text, encoding="utf-8")
    (TARGET / "manifest.json").write_text(_text({"false_certificates": manifest}), encoding="utf-8")


if __name__ == "__main__":
    write()
