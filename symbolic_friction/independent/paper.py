"""The paper's point certificate (``lyapunov-pair/v1``): Lemma 2, Lemma 3 and Proposition 1 for one gain set.

A file holds the gains ``k_p, k_i, k_v, f_c`` (``parameters``), the constants ``k1 … k4, c1, c2, c1_hat,
c2_hat, c`` (``constants``) and the decimal ``overshoot_bound`` κ, claiming ``|x(t)|_𝒜 ≤ κ|x(0)|_𝒜``
(eq. stabState).  Every premise is decided exactly in ``Fraction``.  :func:`premises` is also what
:mod:`.box` evaluates at the corners of its pieces.

The main verifier's format rules are not repeated: the labels and obligations of ``provenance``, and
``c = 2(k_v k_p − k_i)`` as an equation; what Lemma 2 needs of ``c`` is ``0 < c ≤ 2(k_v k_p − k_i)``.
"""

from __future__ import annotations

from fractions import Fraction

from ._core import Malformed, Verdict, psd, q

GAINS = ("k_p", "k_i", "k_v", "f_c")
CONSTANTS = ("k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat")
PHYSICAL = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")


def numbers(obj: object, names: tuple[str, ...], where: str) -> dict[str, Fraction]:
    """The members ``names`` of the JSON object ``obj``, as exact rationals (``Malformed`` if one is missing)."""
    if not isinstance(obj, dict) or any(n not in obj for n in names):
        raise Malformed(f"{where} must be an object with the members {', '.join(names)}")
    return {n: q(obj[n]) for n in names}


def premises(g: dict[str, Fraction], k: dict[str, Fraction], c: Fraction, kappa: Fraction) -> list[tuple[str, bool]]:
    """Every premise of Lemmas 2–3 and Proposition 1 for gains ``g``, constants ``k``, rate ``c`` and bound κ.

    Each is a pair ``(name, holds)``; a premise that would divide by zero fails (the sign premise that the
    zero breaks fails beside it).
    """
    kp, ki, kv, fc = (g[n] for n in GAINS)
    k1, k2, k3, k4, c1, c2, h1, h2 = (k[n] for n in CONSTANTS)
    out = [
        # Assumption 1 (Routh: A Hurwitz; it makes P of eq. lyapLikeP positive definite) and the model's f_c > 0
        ("k_i > 0", ki > 0), ("k_p > 0", kp > 0), ("k_v·k_p > k_i", kv * kp > ki), ("f_c > 0", fc > 0),
        # Lemma 2 item 2, eq. (Vdecrease): along a slip dV/dt = −2(k_v k_p − k_i)v², which is ≤ −c·v²
        ("c > 0", c > 0), ("c ≤ 2(k_v·k_p − k_i)", c <= 2 * (kv * kp - ki)),
        # Lemma 2 item 1: c1|x|²_𝒜 ≤ V(x), as V ≥ (σ, dz(φ), v) P (σ, dz(φ), v)ᵀ and P − c1·I ⪰ 0
        ("c1 > 0", c1 > 0),
    ]
    # P = [[k_v/k_i, 0, −1], [0, 1, 0], [−1, 0, k_p]] of eq. (lyapLikeP): its middle row and column are decoupled,
    # so s·I − P (or P − s·I) is positive semidefinite iff its middle entry and its (σ, v) block are
    if ki != 0:
        a = kv / ki
        lower = 1 - c1 >= 0 and psd([[a - c1, Fraction(-1)], [Fraction(-1), kp - c1]])
        upper = c2 - 1 >= 0 and psd([[c2 - a, Fraction(1)], [Fraction(1), c2 - kp]])
    else:
        lower = upper = False
    # Lemma 2 item 1 (the lower bound) and Lemma 3, eq. (VandR): V ≤ c2|x|²_𝒜 on R, where V = (…)P(…)ᵀ
    out += [("P − c1·I ⪰ 0", lower), ("c2·I − P ⪰ 0", upper)]
    ratio = ki / kv if kv != 0 else None
    out += [
        # Lemma 3: k1 … k4 positive, and the conditions of the proof of eq. (hatVdot) that make V̂° ≤ 0 on R̂
        ("k1 > 0", k1 > 0), ("k2 > 0", k2 > 0), ("k3 > 0", k3 > 0), ("k4 > 0", k4 > 0),
        ("k3 > (k_i/k_v)·k1", ratio is not None and k3 > ratio * k1),
        ("k3 > k2", k3 > k2),
        ("k4 > (k_i/k_v)·k3", ratio is not None and k4 > ratio * k3),
        ("k4 > k_p·k2", k4 > kp * k2),
        # Lemma 3, eq. (hatVandHatR): K ≻ 0 (the paper's route) and ĉ1|x|²_𝒜 ≤ V̂ = ½wᵀKw ≤ ĉ2|x|²_𝒜 on R̂,
        # w = (|σ|, |dz(φ)|, |v|) ≥ 0; k3 ≥ 0 makes ½wᵀKw ≥ ½min(k1, k2, k4)|w|², so ĉ1 ≤ k_j/2 suffices
        ("k1·k4 > k3²", k1 * k4 > k3 * k3),
        ("c1_hat > 0", h1 > 0), ("c1_hat ≤ k1/2", h1 <= k1 / 2), ("c1_hat ≤ k2/2", h1 <= k2 / 2), ("c1_hat ≤ k4/2", h1 <= k4 / 2),
        # K = [[k1, 0, k3], [0, k2, 0], [k3, 0, k4]] is decoupled in its middle row and column too
        ("c2_hat·I − K/2 ⪰ 0", h2 - k2 / 2 >= 0 and psd([[h2 - k1 / 2, -k3 / 2], [-k3 / 2, h2 - k4 / 2]])),
        # Proposition 1, eq. (stabState): its proof uses c1 ≤ c2 and ĉ1 ≤ ĉ2, and κ² ≥ c2ĉ2/(c1ĉ1)
        ("c1 ≤ c2", c1 <= c2), ("c1_hat ≤ c2_hat", h1 <= h2), ("overshoot_bound > 0", kappa > 0),
        ("overshoot_bound² ≥ c2·c2_hat/(c1·c1_hat)", c1 * h1 != 0 and kappa * kappa >= c2 * h2 / (c1 * h1)),
    ]
    return out


def check(data: dict) -> Verdict:
    """Decide a ``lyapunov-pair/v1`` file: :func:`premises`, and a recorded physical gain set (paper §II-A)."""
    g = numbers(data.get("parameters"), GAINS, "parameters")
    k = numbers(data.get("constants"), (*CONSTANTS, "c"), "constants")
    verdict = Verdict("lyapunov-pair/v1")
    for name, holds in premises(g, k, k["c"], q(data.get("overshoot_bound"))):
        verdict.add(name, holds)
    if "physical" in data:
        # §II-A: m > 0, α_v ≥ 0, and k_p = k̄_p/m, k_i = k̄_i/m, k_v = (k̄_d + α_v)/m, f_c = f̄_c/m
        ph = numbers(data["physical"], PHYSICAL, "physical")
        m = ph["m"]
        verdict.add("physical: m > 0, alpha_v ≥ 0", m > 0 and ph["alpha_v"] >= 0)
        image = {"k_p": ph["k_p_bar"], "k_i": ph["k_i_bar"], "k_v": ph["k_d_bar"] + ph["alpha_v"], "f_c": ph["f_c_bar"]}
        for n, formula in (("k_p", "k_p_bar/m"), ("k_i", "k_i_bar/m"), ("k_v", "(k_d_bar + alpha_v)/m"), ("f_c", "f_c_bar/m")):
            verdict.add(f"{n} = {formula}", m != 0 and g[n] == image[n] / m)
    return verdict
