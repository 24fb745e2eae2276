"""The quadratic template (``quadratic/v1``): Proposition 1's bound with a free ``P`` and a general ``V̂``.

A file holds the gains (``parameters``), the constants ``p11, p22, p33, c, c2, k11, k13, k22, k23, k33,
gamma`` and the decimal ``overshoot_bound`` κ.  The certificate replaces the paper's ``P`` of
eq. (lyapLikeP) by

    P = [[p11, 0, −p22], [0, p22, p23], [−p22, p23, p33]],   p23 = k_i·p11 − k_v·p22,

(``P₁₂ = 0`` keeps the minimiser of eq. (lyapLikeV) at ``v = 0`` the projection of φ on ``[−f_c, f_c]``;
``Q = AᵀP + PA`` has ``Q₁₁ = 2P₁₂``, so ``Q ⪯ 0`` needs its first row zero, which the other two entries
give), and ``V̂`` of eq. (Vhat) by ``U = yᵀKy``, ``y = (|σ|, |dz(φ)|, |v|)``,
``K = [[k11, 0, k13], [0, k22, k23], [k13, k23, k33]]``.  Semidefiniteness is decided exactly (every
principal minor), copositivity by Hadeler's criterion (:func:`._core.copositive`, arb balls for its one
inequality with square roots; undecided is not proved).  Then ``|x(t)|²_𝒜 ≤ max(c2, γ)|x(0)|²_𝒜`` by
Proposition 1's case analysis.
"""

from __future__ import annotations

from fractions import Fraction

from ._core import Verdict, copositive, psd, q
from .paper import GAINS, numbers

CONSTANTS = ("p11", "p22", "p33", "c", "c2", "k11", "k13", "k22", "k23", "k33", "gamma")
Matrix = list[list[Fraction]]


def _mul(a: Matrix, b: Matrix) -> Matrix:
    return [[sum((a[i][m] * b[m][j] for m in range(len(b))), Fraction(0)) for j in range(len(b[0]))] for i in range(len(a))]


def _sym(m: Matrix) -> Matrix:
    """``M + Mᵀ``."""
    return [[m[i][j] + m[j][i] for j in range(len(m))] for i in range(len(m))]


def _minus(a: Matrix, b: Matrix) -> Matrix:
    return [[x - y for x, y in zip(ra, rb)] for ra, rb in zip(a, b)]


def _eye(n: int, s: Fraction = Fraction(1)) -> Matrix:
    return [[s if i == j else Fraction(0) for j in range(n)] for i in range(n)]


def _neg(m: Matrix) -> Matrix:
    return [[-x for x in row] for row in m]


def matrices(g: dict[str, Fraction], k: dict[str, Fraction]) -> dict[str, Matrix]:
    """The matrices of the premises, by name: ``⪰ 0`` in the name asks semidefinite, else copositive."""
    kp, ki, kv = g["k_p"], g["k_i"], g["k_v"]
    zero, one = Fraction(0), Fraction(1)
    p23 = ki * k["p11"] - kv * k["p22"]
    P = [[k["p11"], zero, -k["p22"]], [zero, k["p22"], p23], [-k["p22"], p23, k["p33"]]]
    K = [[k["k11"], zero, k["k13"]], [zero, k["k22"], k["k23"]], [k["k13"], k["k23"], k["k33"]]]
    A = [[zero, zero, -ki], [one, zero, -kp], [zero, one, -kv]]  # eq. (xDot) in x = (σ, φ, v)
    # Lemma 2 item 1 with c1 = 1 (|x|²_𝒜 ≤ V everywhere) and Lemma 3, eq. (VandR): V ≤ c2|x|²_𝒜 on R
    out = {"P − I ⪰ 0": _minus(P, _eye(3)), "c2·I − P ⪰ 0": _minus(_eye(3, k["c2"]), P)}
    # Lemma 2 item 2, eq. (Vdecrease): in a slip w = x ∓ f_c e₂ follows ẇ = Aw, so d/dt wᵀPw = wᵀQw ≤ −c·v²
    decrease = _neg(_sym(_mul(P, A)))
    decrease[2][2] -= k["c"]
    out["−(AᵀP + PA) − c·e3e3ᵀ ⪰ 0"] = decrease
    # Lemma 3, eq. (hatVdot), for U: on R̂ ∩ {v > 0} with s = sign(σ), outside the band |φ| ≤ f_c,
    # ẏ = B_s y − f·e₃ with f = f_c − φ − |dz(φ)| ≥ 0, so U̇ = −yᵀ(−(K B_s + B_sᵀ K))y − 2(Ky)₃ f;
    # inside the band y₂ = 0 and U̇ = −(the band form in (|σ|, v)) − 2(Ky)₃ f; v < 0 is the mirror image
    for s, sign in ((1, "+"), (-1, "−")):
        B = [[zero, zero, -ki * s], [Fraction(-s), zero, kp], [zero, -one, -kv]]
        out[f"−(K·B{sign} + B{sign}ᵀ·K) copositive"] = _neg(_sym(_mul(K, B)))
        off = ki * s * k["k11"] + kv * k["k13"]
        out[f"band form (s = {sign}1) copositive"] = [[zero, off], [off, 2 * ki * s * k["k13"] + 2 * kv * k["k33"]]]
    # Lemma 3, eq. (hatVandHatR), for U: |y|² ≤ U ≤ γ|y|² on R̂ (|y| = |x|_𝒜 there)
    out["K − I copositive"] = _minus(K, _eye(3))
    out["gamma·I − K copositive"] = _minus(_eye(3, k["gamma"]), K)
    # Proposition 1's case (ii): U ≥ V where a solution leaves R̂.  At v = 0, V = p11σ² + p22·dz(φ)²
    # (P₁₂ = 0); at φ = ±f_c, v ≠ 0, V = p11σ² − 2p22σv + p33v² ≤ p11σ² + 2p22|σ||v| + p33v² (p22 ≥ 1)
    out["U − V copositive at v = 0"] = [[K[0][0] - P[0][0], K[0][1]], [K[0][1], K[1][1] - P[1][1]]]
    cross = K[0][2] - P[1][1]
    out["U − V copositive at φ = ±f_c"] = [[K[0][0] - P[0][0], cross], [cross, K[2][2] - P[2][2]]]
    return out


def check(data: dict) -> Verdict:
    """Decide every premise of a ``quadratic/v1`` file (each cites the step of the proof it stands for)."""
    g = numbers(data.get("parameters"), GAINS, "parameters")
    k = numbers(data.get("constants"), CONSTANTS, "constants")
    kappa = q(data.get("overshoot_bound"))
    kp, ki, kv, fc = (g[n] for n in GAINS)
    v = Verdict("quadratic/v1")
    # Assumption 1 and the model's f_c > 0
    v.add("k_i > 0", ki > 0)
    v.add("k_p > 0", kp > 0)
    v.add("k_v·k_p > k_i", kv * kp > ki)
    v.add("f_c > 0", fc > 0)
    # Lemma 2 item 2: a positive rate c (its form is among the matrices)
    v.add("c > 0", k["c"] > 0)
    for name, m in matrices(g, k).items():
        v.add(name, psd(m) if "⪰" in name else copositive(m))
    # Lemma 3, eq. (hatVdot), for U: the friction term −2(Ky)₃ f ≤ 0 for every y ≥ 0
    for j, name in enumerate(("k13", "k23", "k33")):
        v.add(f"K3{j + 1} ≥ 0", k[name] >= 0)
    # Proposition 1, eq. (stabState) with max(c2, γ) for c2ĉ2/(c1ĉ1): κ > 0, κ² ≥ c2, κ² ≥ γ
    v.add("overshoot_bound > 0", kappa > 0)
    v.add("overshoot_bound² ≥ c2", kappa * kappa >= k["c2"])
    v.add("overshoot_bound² ≥ gamma", kappa * kappa >= k["gamma"])
    return v
