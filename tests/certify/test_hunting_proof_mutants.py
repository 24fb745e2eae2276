"""The Krawczyk proof of hunting cycles, pinned on the committed boxes and on forged ones (kills its mutants).

For every committed hunting certificate and for forged boxes (shifted, with
``σ ≤ 0``, ``τ_a`` past the box, ``f_s = f_c``, ``τ_a`` where ``v`` still
rises, a ``v`` with an early dip) the full list of checks (name, verdict and
the enclosures that decided it), the verdict, the multiplier's enclosure and
the stability are compared with ``golden/hunting_proofs.json``.  Every line
comes from exact rationals and arb balls at a fixed precision, so it is
deterministic.  Regenerate only after checking the difference by hand::

    SF_REGENERATE_GOLDEN=1 python -m pytest -n 0 tests/certify/test_hunting_proof_mutants.py
"""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction as F
from pathlib import Path

import pytest

from tests.certify.golden import assert_golden

from symbolic_friction import Parameters
from symbolic_friction._certify import hunting_proof as H
from symbolic_friction._certify.hunting import load_hunting

ROOT = Path(__file__).resolve().parents[2]
NAMES = ("case_a_fs1.2", "case_b_fs1.2", "triple_root_fs1.2", "stiff_fs1.2", "high_gain_fs1.4")


def _cert(name):
    return load_hunting(ROOT / "proofs" / "hunting" / f"{name}.json")


def _lines(proof: H.CycleProof) -> list[str]:
    return [str(ch) for ch in proof.checks] + [f"proved {proof.proved}", f"multiplier {proof.multiplier!r}",
                                                f"stable {proof.stable}"]


def _cases(monkeypatch) -> dict[str, list[str]]:
    out = {}
    for name in NAMES:
        c = _cert(name)
        out[name] = _lines(H.prove_cycle(c.params, c.box, precision=c.precision_bits))
    c = _cert("case_a_fs1.2")
    p, box = c.params, c.box
    (s_lo, s_hi), (t_lo, t_hi) = box.sigma, box.tau
    ws, wt = s_hi - s_lo, t_hi - t_lo
    forged = {
        "sigma_shifted_up": dataclasses.replace(box, sigma=(s_lo + 2 * ws, s_hi + 2 * ws)),
        "sigma_shifted_down": dataclasses.replace(box, sigma=(s_lo - 2 * ws, s_hi - 2 * ws)),
        "tau_shifted_up": dataclasses.replace(box, tau=(t_lo + 2 * wt, t_hi + 2 * wt)),
        "tau_shifted_down": dataclasses.replace(box, tau=(t_lo - 2 * wt, t_hi - 2 * wt)),
        "sigma_half_out": dataclasses.replace(box, sigma=(s_lo + ws / 2, s_hi + ws / 2)),
        "tau_half_out": dataclasses.replace(box, tau=(t_lo - wt / 2, t_hi - wt / 2)),
        "sigma_wide": dataclasses.replace(box, sigma=(s_lo - 1000 * ws, s_hi + 1000 * ws)),
        "sigma_negative": dataclasses.replace(box, sigma=(-s_hi, -s_lo)),
        "sigma_from_zero": dataclasses.replace(box, sigma=(F(0), s_hi)),
        "sigma_reversed": dataclasses.replace(box, sigma=(s_hi, s_lo)),
        "tau_reversed": dataclasses.replace(box, tau=(t_hi, t_lo)),
        "monotone_at_box": dataclasses.replace(box, monotone_from=t_lo),
        "monotone_zero": dataclasses.replace(box, monotone_from=F(0)),
        "monotone_early": dataclasses.replace(box, monotone_from=F(1, 10)),
        "sigma_point": dataclasses.replace(box, sigma=(s_lo, s_lo)),
        "tau_point": dataclasses.replace(box, tau=(t_hi, t_hi)),
    }
    for name, b in forged.items():
        out[name] = _lines(H.prove_cycle(p, b))
    out["f_s_equals_f_c"] = _lines(H.prove_cycle(Parameters.table_i("a"), box))
    out["f_s_below_box_stick"] = _lines(H.prove_cycle(dataclasses.replace(p, f_s=F(11, 10)), box))
    out["other_gains"] = _lines(H.prove_cycle(_cert("case_b_fs1.2").params, box))
    # a box 10⁶ times narrower: its enclosures are known to more digits than each message prints
    shrink = lambda lo, hi: ((lo + hi) / 2 - (hi - lo) / 2_000_000, (lo + hi) / 2 + (hi - lo) / 2_000_000)  # noqa: E731
    out["tight_box"] = _lines(H.prove_cycle(p, dataclasses.replace(box, sigma=shrink(s_lo, s_hi), tau=shrink(t_lo, t_hi))))
    real = H._Arb.state

    def dipping(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if self.ball(F(1, 2), F(1)).overlaps(tau):
            y = [y[0], y[1], y[2] - 1]
        return E, y, dy

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", dipping)
        out["v_dips"] = _lines(H.prove_cycle(p, box))

    def straddling(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if self.ball(F(1, 2), F(1)).overlaps(tau):
            y = [y[0], y[1], y[2] * 0 + self.arb(0, 1)]  # a ball that contains 0 is not positive
        return E, y, dy

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", straddling)
        out["v_straddles_zero"] = _lines(H.prove_cycle(p, box))

    def no_start(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        return E, y, [dy[0], dy[1], dy[2] - 10**6]

    with monkeypatch.context() as m:
        m.setattr(H._Arb, "state", no_start)
        out["v_never_rises"] = _lines(H.prove_cycle(p, box))
    out["box_around"] = [repr(H.box_around(0.1, 2.5)), repr(H.box_around(-0.25, 0.05, relative=1e-6)),
                         repr(H.box_around(3.0, 1000.0)), repr(H.box_around(0.5, 1.0))]
    return out


@pytest.fixture(scope="module")
def actual():
    with pytest.MonkeyPatch.context() as mp:
        return _cases(mp)


def test_every_proof_is_the_golden_one(actual):
    assert_golden("hunting_proofs.json", actual)


def test_the_golden_file_has_every_check_both_ways(actual):
    seen: dict[str, set[str]] = {}
    for lines in actual.values():
        for line in lines:
            verdict, _, rest = line.partition("  ")
            if verdict in ("holds", "FAILS"):
                seen.setdefault(rest.split(":")[0], set()).add(verdict)
    for check in ("box", "krawczyk", "first_zero.start", "first_zero.positive", "first_zero.decreasing", "stick"):
        assert seen[check] == {"holds", "FAILS"}, check
    for name in NAMES:
        assert actual[name][-3] == "proved True" and actual[name][-1] == "stable True"


def test_a_forged_box_is_never_proved(actual):
    for name, lines in actual.items():
        if name not in NAMES and name not in ("box_around", "sigma_wide", "tight_box"):  # the last two hold the cycle
            assert "proved False" in lines, name


def test_the_helpers_round_outward_and_exactly():
    from flint import arb

    x = arb(1) / 3
    assert H._lower(x) <= 1 / 3 <= H._upper(x) and H._lower(x) < H._upper(x)
    assert H._lower(arb(2)) == math.nextafter(2.0, 0) and H._upper(arb(2)) == math.nextafter(2.0, 3)
    assert H._exact_mid(arb(1) / 4) == F(1, 4) and H._exact_mid(arb(3) * 8) == 24 and H._exact_mid(arb(-5) / 2) == F(-5, 2)
    assert H._short(F(0)) == 0 and H._short(F(1, 3)) == F("0.33333333333333331")
    assert H._short(F(-2)) == -2 and H._short(F(1)) == 1


def test_the_precision_is_set_for_the_proof_and_restored(monkeypatch):
    from flint import ctx

    seen = []
    real = H._prove

    def spy(params, box):
        seen.append(ctx.prec)
        return real(params, box)

    monkeypatch.setattr(H, "_prove", spy)
    c = _cert("case_a_fs1.2")
    before = ctx.prec
    H.prove_cycle(c.params, c.box, precision=200)
    assert seen == [200] and ctx.prec == before
    with pytest.raises(RuntimeError):
        monkeypatch.setattr(H, "_prove", lambda params, box: (_ for _ in ()).throw(RuntimeError("x")))
        H.prove_cycle(c.params, c.box, precision=300)
    assert ctx.prec == before


class _Linear:
    """A fake closed form with ``F(σ, τ) = (τ - τ*, σ - σ*)`` exactly (``J = [[0, 1], [1, 0]]``, ``E = 0``).

    With dyadic corners every ball is exact, ``C = J⁻¹`` and ``I - CJ = 0``, so
    ``K(X) = (σ*, τ*)`` exactly: the Krawczyk inclusion is decided on a point
    that can sit exactly on a corner of the box.
    """

    def __init__(self, s_star, t_star, dv0=None):
        self.s_star, self.t_star, self.dv0 = F(s_star), F(t_star), dv0

    def __call__(self, M, sigma, tau):
        from flint import arb_mat

        E = arb_mat(3, 3)
        y = [-M.q(self.s_star) + 0 * sigma, M.arb(0), tau - M.q(self.t_star)]
        dy = [M.arb(0), M.arb(0), M.arb(1) if self.dv0 is None else self.dv0(M)]
        return E, y, dy


BOX = H.Box(sigma=(F(1, 8), F(3, 8)), tau=(F(2), F(3)), monotone_from=F(1))
P12 = Parameters(k_p=3, k_i=4, k_v="6.4", f_s="1.2")


def _krawczyk(monkeypatch, fake):
    monkeypatch.setattr(H._Arb, "state", lambda self, sigma, tau: fake(self, sigma, tau))
    (check,) = [c for c in H.prove_cycle(P12, BOX).checks if c.name == "krawczyk"]
    return check


@pytest.mark.parametrize("s_star, t_star, inside", [
    (F(1, 4), F(5, 2), True), (F(1, 8), F(5, 2), False), (F(3, 8), F(5, 2), False),
    (F(1, 4), F(2), False), (F(1, 4), F(3), False), (F(1, 2), F(5, 2), False),
])
def test_the_krawczyk_inclusion_is_strict_at_both_ends(monkeypatch, s_star, t_star, inside):
    """``K(X)`` on a corner of ``X`` is not in its interior: ``>`` on both ends, never ``≥``."""
    check = _krawczyk(monkeypatch, _Linear(s_star, t_star))
    assert check.holds is inside, check


def test_a_singular_jacobian_is_refused(monkeypatch):
    monkeypatch.setattr(H, "_exact_mid", lambda x: F(0))
    c = _cert("case_a_fs1.2")
    proof = H.prove_cycle(c.params, c.box)
    assert isinstance(proof.checks, tuple) and [(ch.name, ch.holds) for ch in proof.checks] == [("box", True), ("krawczyk", False)]
    assert str(proof.checks[-1]) == "FAILS  krawczyk: the Jacobian at the box centre is singular"
    assert proof.proved is False and proof.stable is None
    assert len(proof.multiplier) == 2 and all(math.isnan(m) for m in proof.multiplier)


def test_a_malformed_box_has_no_multiplier():
    c = _cert("case_a_fs1.2")
    proof = H.prove_cycle(c.params, dataclasses.replace(c.box, sigma=(c.box.sigma[1], c.box.sigma[0])))
    assert proof.proved is False and proof.stable is None and isinstance(proof.checks, tuple)
    assert len(proof.multiplier) == 2 and all(math.isnan(m) for m in proof.multiplier)
    assert [(ch.name, ch.holds) for ch in proof.checks] == [("box", False)]


def test_the_start_check_uses_the_box_sigma_and_a_strict_sign(monkeypatch):
    c = _cert("case_a_fs1.2")
    real = H._Arb.state
    seen = []

    def spy(self, sigma, tau):
        seen.append((sigma, tau))
        return real(self, sigma, tau)

    monkeypatch.setattr(H._Arb, "state", spy)
    H.prove_cycle(c.params, c.box)
    S = H._Arb(c.params).ball(*c.box.sigma)
    starts = [s for s, t in seen if t.contains(0)]
    assert starts and all(s is not None and s.overlaps(S) and s.rad() > 0 for s in starts)

    def zero_slope(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        return (E, y, [dy[0], dy[1], self.arb(0)]) if tau.contains(0) else (E, y, dy)

    monkeypatch.setattr(H._Arb, "state", zero_slope)
    proof = H.prove_cycle(c.params, c.box)
    (start,) = [ch for ch in proof.checks if ch.name == "first_zero.start"]
    positive = [ch for ch in proof.checks if ch.name == "first_zero.positive"]
    # the first-zero search is not run once the start fails (the box is refused either way)
    assert start.holds is False and all(ch.holds is False for ch in positive) and not proof.proved
    assert str(start) == "FAILS  first_zero.start: v' > 0 near τ = 0 could not be shown"


def test_the_decreasing_check_needs_a_negative_slope(monkeypatch):
    """``∂v/∂τ`` in ``(0, 1)`` on ``[τ_a, τ_hi]`` is not ``< 0``."""
    from flint import arb

    fake = _Linear(F(1, 4), F(5, 2), dv0=lambda M: arb(1) / 2)
    monkeypatch.setattr(H._Arb, "state", lambda self, sigma, tau: fake(self, sigma, tau))
    checks = {c.name: c for c in H.prove_cycle(P12, BOX).checks}
    assert checks["first_zero.decreasing"].holds is False
    assert checks["first_zero.positive"].holds is False  # v = τ - τ* < 0 before τ*: giving up is not proved


# -- _positive_on on forged balls: a ball that touches 0 is not positive, and every exit of the search ----------------
#
# The value is a function of the piece only, so each exit (a ball certainly ≤ 0 in the first pass or in the
# refinement, a piece narrower than the floor, too many pieces) is reached on purpose, with balls whose end
# lands exactly on 0: [0, 1] is not > 0 (v may vanish at a point), [-1, 0] and [0, 0] are ≤ 0.  The piece
# count is pinned: it says at which piece the search stopped.

def _balls():
    from flint import arb

    above = arb(0, 1).nonnegative_part()  # lower end exactly 0 (arb(0.5, 0.5) rounds its radius up, past 0)
    return {"pos": arb(1), "zero": arb(0), "straddle": arb(0, 1), "touch_above": above, "touch_below": -above}


def test_arb_balls_whose_end_is_zero():
    b = _balls()
    assert b["touch_above"].lower() == 0 and b["touch_above"].upper() > 0 and b["touch_below"].upper() == 0
    assert not (b["touch_above"] > 0) and (b["touch_above"] >= 0) and not (b["touch_above"] <= 0)
    assert (b["touch_below"] <= 0) and not (b["touch_below"] < 0)
    assert (b["zero"] <= 0) and not (b["zero"] < 0) and not (b["straddle"] > 0) and not (b["straddle"] <= 0)


def test_positive_on_refuses_a_ball_that_touches_zero():
    """[0, 1] on every piece: never positive (in the first pass nor in the refinement); the floor ends the search."""
    ball = _balls()["touch_above"]
    assert H._positive_on(lambda lo, hi: ball, F(0), F(1), floor=F(1, 1024)) == (False, 73)
    # only the pieces of the first pass touch 0; their halves are positive: refined, then shown
    first = F(1, 64)
    b = _balls()
    value = lambda lo, hi: b["touch_above"] if hi - lo == first else b["pos"]  # noqa: E731
    assert H._positive_on(value, F(0), F(1), floor=F(1, 1024)) == (True, 64 + 128)
    # and only their halves touch 0 (the first pass straddles)
    value = lambda lo, hi: b["straddle"] if hi - lo == first else b["touch_above"]  # noqa: E731
    assert H._positive_on(value, F(0), F(1), floor=F(1, 100)) == (False, 65)


@pytest.mark.parametrize("which", ["zero", "touch_below"])
def test_positive_on_stops_at_a_ball_certainly_not_positive(which):
    """A ball ≤ 0 (its upper end exactly 0) ends the search at that piece, in the first pass and in the refinement."""
    b = _balls()
    assert H._positive_on(lambda lo, hi: b[which], F(0), F(1), floor=F(0)) == (False, 1)
    value = lambda lo, hi: b["pos"] if lo < F(1, 2) else b[which]  # noqa: E731
    assert H._positive_on(value, F(0), F(1), floor=F(0)) == (False, 33)
    first = F(1, 64)
    value = lambda lo, hi: b["straddle"] if hi - lo == first else b[which]  # noqa: E731
    assert H._positive_on(value, F(0), F(1), floor=F(0)) == (False, 65)


def test_positive_on_gives_up_at_the_floor_not_one_level_earlier():
    """A piece exactly as wide as the floor is still refined; a narrower one ends the search (not shown)."""
    straddle = _balls()["straddle"]
    assert H._positive_on(lambda lo, hi: straddle, F(0), F(1), floor=F(1, 256)) == (False, 69)
    # positive once a piece is no wider than the floor: shown, with every piece at the floor's width
    b = _balls()
    value = lambda lo, hi: b["pos"] if hi - lo <= F(1, 256) else b["straddle"]  # noqa: E731
    assert H._positive_on(value, F(0), F(1), floor=F(1, 256)) == (True, 64 + 128 + 256)
    # from a positive start: the floor is a width (piece[1] − piece[0]), not a position
    assert H._positive_on(lambda lo, hi: straddle, F(1000), F(1001), floor=F(1, 256)) == (False, 69)


def test_positive_on_gives_up_after_max_pieces(monkeypatch):
    monkeypatch.setattr(H, "_MAX_PIECES", 100)
    straddle = _balls()["straddle"]
    assert H._positive_on(lambda lo, hi: straddle, F(0), F(1), floor=F(1, 2**200)) == (False, 101)


def test_positive_on_refines_by_halving_and_covers_the_interval():
    """The pieces shown positive tile [lo, hi] exactly (halves): nothing is skipped, nothing overlaps."""
    b = _balls()
    shown = []

    def value(lo, hi):
        if hi - lo <= F(3, 256):
            shown.append((lo, hi))
            return b["pos"]
        return b["straddle"]

    assert H._positive_on(value, F(1), F(4), floor=F(0)) == (True, 64 + 128 + 256)
    shown.sort()
    assert shown[0][0] == 1 and shown[-1][1] == 4
    assert all(p[1] == q[0] for p, q in zip(shown, shown[1:]))
    assert all(hi - lo == F(3, 256) for lo, hi in shown)


# -- the rest of _prove on balls whose end lands exactly on a bound ---------------------------------------------------

def test_the_decreasing_check_refuses_a_slope_whose_upper_end_is_zero(monkeypatch):
    """∂v/∂τ ∈ [-1, 0] is not certainly < 0 (v may stop falling at a point): ``<``, never ``≤``."""
    touch_below = _balls()["touch_below"]
    fake = _Linear(F(1, 4), F(5, 2), dv0=lambda M: touch_below)
    monkeypatch.setattr(H._Arb, "state", lambda self, sigma, tau: fake(self, sigma, tau))
    checks = {c.name: c for c in H.prove_cycle(P12, BOX).checks}
    assert "stick" in checks  # the Jacobian [[0, -½], [1, 0]] at the centre is regular: every check ran
    assert checks["first_zero.decreasing"].holds is False
    assert str(checks["first_zero.decreasing"]).startswith("FAILS  first_zero.decreasing: ∂v/∂τ ∈ ")
    assert "not < 0 on [τ_a, τ_hi]" in str(checks["first_zero.decreasing"])


def _unit_multiplier(M, sigma, tau):
    """E₂₀ = 1, σ₁' = -1, v' = 1 (else as :class:`_Linear`): the multiplier -(E₀₀ - σ₁'E₂₀/v') is exactly -1."""
    from flint import arb_mat

    E = arb_mat(3, 3)
    E[2, 0] = M.arb(1)
    y = [-M.q(F(1, 4)) + 0 * sigma, M.arb(0), tau - M.q(F(5, 2))]
    return E, y, [M.arb(-1), M.arb(0), M.arb(1)]


def test_a_multiplier_of_modulus_exactly_one_decides_no_stability(monkeypatch):
    """|P'(σ*)| = 1 is neither < 1 (stable) nor > 1 (unstable): stability is left undecided (None)."""
    monkeypatch.setattr(H._Arb, "state", _unit_multiplier)
    proof = H.prove_cycle(P12, BOX)
    assert proof.stable is None
    assert proof.multiplier == (math.nextafter(-1.0, -math.inf), math.nextafter(-1.0, math.inf))


def _start_shown_below(bound, real):
    """v' > 0 on [0, δ] only once δ's ball lies below ``bound`` (a straddling ball before)."""

    def state(self, sigma, tau):
        E, y, dy = real(self, sigma, tau)
        if tau.contains(0):
            dy = [dy[0], dy[1], self.arb(1) if bool(tau < self.q(bound)) else self.arb(0, 1)]
        return E, y, dy

    return state


@pytest.mark.parametrize("halvings, shown", [(58, True), (59, True), (60, False)])
def test_the_start_search_tries_sixty_halvings_of_delta(monkeypatch, halvings, shown):
    """δ = τ_a/64 · 2⁻ᵏ for k = 0 … 59: shown if v' > 0 once δ ≤ τ_a/64 · 2⁻⁵⁹, given up below that."""
    c = _cert("case_a_fs1.2")
    t_a = c.box.monotone_from
    bound = t_a / 64 / 2**halvings * F(3, 2)  # between the k-th δ and the one before
    monkeypatch.setattr(H._Arb, "state", _start_shown_below(bound, H._Arb.state))
    (start,) = [ch for ch in H.prove_cycle(c.params, c.box).checks if ch.name == "first_zero.start"]
    assert start.holds is shown
    if shown:
        assert str(start) == (f"holds  first_zero.start: v' > 0 on [0, {float(t_a / 64 / 2**halvings):.3g}] for every σ "
                              "in the box (v(0) = 0, v'(0) = f_s - f_c)")


def test_the_zero_is_the_krawczyk_box_only_when_it_is_inside():
    """``zero`` holds K(X)'s exact ends, lower < upper, inside X, when the inclusion holds; None otherwise."""
    c = _cert("case_a_fs1.2")
    proof = H.prove_cycle(c.params, c.box)
    assert proof.proved and proof.zero is not None
    for (lo, hi), (b_lo, b_hi) in zip(proof.zero, (c.box.sigma, c.box.tau)):
        assert b_lo < lo < hi < b_hi
    ws = c.box.sigma[1] - c.box.sigma[0]
    shifted = dataclasses.replace(c.box, sigma=(c.box.sigma[0] + 2 * ws, c.box.sigma[1] + 2 * ws))
    refused = H.prove_cycle(c.params, shifted)
    assert not refused.proved and refused.zero is None
