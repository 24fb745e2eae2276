"""Tests that kill mutmut's survivors in the sup-flow verifier (``_certify/sup_flow.py``, ``sup_flow_enclosure.py``).

Each test fixes one decision of the verifier on an input where a mutant of it would give another
answer (``tests/mutation/mutmut-report.md``).
"""

from __future__ import annotations

from fractions import Fraction
from types import SimpleNamespace

import pytest

from symbolic_friction._certify import sup_flow_enclosure as E

GAINS = SimpleNamespace(k_p=Fraction(3), k_i=Fraction(4), k_v=Fraction(32, 5))
"""Table I (a)'s gains, in the shape the flow enclosure reads."""


def _entries(m):
    return [m[i, j] for i in range(3) for j in range(3)]


# -- _flow: e^{At} enclosed for every t of [a, b], and not much more ---------------------------------


def test_the_flow_on_an_interval_encloses_the_flow_at_each_of_its_points():
    a, b = Fraction(1), Fraction(65, 64)
    box = E._flow(GAINS, a, b)
    for t in (a, (a + b) / 2, b):
        assert all(x.contains(y) for x, y in zip(_entries(box), _entries(E._flow(GAINS, t, t)))), t


def test_the_flow_on_an_interval_is_apart_from_the_flow_well_past_it():
    a, b = Fraction(1), Fraction(65, 64)
    far = a + 3 * (b - a)
    assert not all(x.overlaps(y) for x, y in zip(_entries(E._flow(GAINS, a, b)), _entries(E._flow(GAINS, far, far))))


# -- _bisect: the parts, the limit of MAX_PARTS, the budget -----------------------------------------


def _short(length):
    """A test that holds on a part exactly when it is at most ``length`` long."""
    return lambda lo, hi: (hi - lo <= length, "too long")


def _never(t):
    return False, ""


def test_bisect_counts_its_parts_and_spends_one_of_the_budget_per_test():
    budget = E.Budget(100)
    assert E._bisect(Fraction(0), Fraction(1), _short(Fraction(1, 4)), _never, budget) == (4, "")
    assert budget.left == 100 - 7  # [0, 1], its halves, their halves


def test_bisect_decides_every_part_not_only_the_first():
    # the left half holds at once; the right half never does
    parts, why = E._bisect(Fraction(0), Fraction(1), lambda lo, hi: (hi <= Fraction(1, 2), "no"), _never, E.Budget())
    assert why.startswith("not decided on [0.5") and parts >= 1


def test_bisect_allows_exactly_max_parts():
    n = E.MAX_PARTS
    assert E._bisect(Fraction(0), Fraction(1), _short(Fraction(1, n)), _never, E.Budget()) == (n, "")


def test_bisect_refuses_one_part_more_than_max_parts():
    n = E.MAX_PARTS
    lo, hi = 1 - Fraction(2, n), 1 - Fraction(1, n)

    def test(a, b):  # parts of 1/n, but the last but one needs two halves: MAX_PARTS + 1 parts
        return (b - a <= (Fraction(1, 2 * n) if lo <= a and b <= hi else Fraction(1, n))), "too long"

    budget = E.Budget()
    parts, why = E._bisect(Fraction(0), Fraction(1), test, _never, budget)
    # when [lo, hi] is halved, n − 2 parts are done and [hi, 1] waits: n + 1 parts
    assert why == f"not decided on [{float(lo):.6g}, {float(hi):.6g}] within {n} parts (too long)" and parts == n - 2
    used = E.MAX_TOTAL_PARTS - budget.left
    # the same refusal with exactly 2 parts of the budget left: still the limit of this premise
    assert E._bisect(Fraction(0), Fraction(1), test, _never, E.Budget(used + 2))[1].endswith(f"within {n} parts (too long)")


def test_bisect_stops_where_the_budget_of_the_verification_ends():
    quarter = _short(Fraction(1, 4))
    assert E._bisect(Fraction(0), Fraction(1), quarter, _never, E.Budget(7)) == (4, "")  # 7 tests, 2 left at each split
    parts, why = E._bisect(Fraction(0), Fraction(1), quarter, _never, E.Budget(6))
    assert why == f"not decided on [0.5, 1] within the {E.MAX_TOTAL_PARTS} parts of one verification (too long)"
    assert parts == 2


# -- _norm_refuted: ‖e^{At}‖² > c₂ at a point, by the Rayleigh quotient ------------------------------


def _rank_one(monkeypatch):
    """e = [[1, 1, 0], 0, 0]: eᵀe has the top eigenvalue 2 at (1, 1, 0)/√2, a float guess of norm ≠ 1."""
    import flint
    import numpy as np

    monkeypatch.setattr(E, "_flow", lambda cert, a, b: flint.arb_mat([[1, 1, 0], [0, 0, 0], [0, 0, 0]]))
    g = np.array([[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0]])
    return sum(Fraction(float(x)) ** 2 for x in np.linalg.eigh(g)[1][:, -1])


@pytest.fixture
def precision():
    """decide_flow's precision (the float guess's norm differs from 1 by about 2⁻⁵³)."""
    import flint

    old, flint.ctx.prec = flint.ctx.prec, E.PRECISION
    yield
    flint.ctx.prec = old


def test_the_norm_is_refuted_only_above_c2(monkeypatch, precision):
    norm2 = _rank_one(monkeypatch)
    assert norm2 != 1
    # ‖e‖² = 2 exactly: not above c₂ = 2, above anything below 2
    assert E._norm_refuted(GAINS, E._arb(Fraction(2)), Fraction(1)) == (False, "‖e^(At)‖² > c2 there")
    for mu in (2 * norm2**2, 2 / norm2**2):
        assert E._norm_refuted(GAINS, E._arb(mu), Fraction(1))[0] is (mu < 2)


# -- decide_flow: the norm premise on [0, T] and past T ------------------------------------------------

import json  # noqa: E402
import re  # noqa: E402
from pathlib import Path  # noqa: E402

from symbolic_friction._certify.sup_flow import SupFlowCertificate, sup_flow_premises  # noqa: E402

PROOFS = Path(__file__).resolve().parents[2] / "proofs" / "sup_flow"


def _certificate(**constants):
    data = json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))
    data["constants"].update(constants)
    return SupFlowCertificate.from_dict(data)


def _norm_premise(cert):
    (premise,) = [p for p in sup_flow_premises(cert) if isinstance(p, E.FlowNorm)]
    return premise


def test_the_norm_is_decided_on_0_to_the_last_start_and_past_it_by_p():
    check = E.decide_flow(_norm_premise(_certificate()), E.Budget())
    assert check.holds is True and check.obligation == "sup_flow.bounds"
    # T = 32, the last piece's start (not the start of any earlier piece)
    assert re.fullmatch(r"c2 = 104939546431/50000000000 on \[0, 32\] in \d+ parts and past it by P", check.instance)


def test_a_tail_form_above_c2_is_refused_at_t():
    premise = _norm_premise(_certificate(p="1/10000000000000000000000000000000000000000"))
    check = E.decide_flow(premise, E.Budget())
    assert (check.obligation, check.name, check.instance, check.holds) == (
        "sup_flow.bounds", premise.name, "the tail form at T = 32 is not below c2", False)


def test_a_norm_not_decided_within_the_budget_says_why():
    check = E.decide_flow(_norm_premise(_certificate()), E.Budget(2))
    assert check.holds is False
    assert check.instance == (f"not decided on [0, 32] within the {E.MAX_TOTAL_PARTS} parts of one verification "
                              "(‖e^(At)‖² ≥ c2 or too close to it)")


def test_the_norm_is_decided_from_t_0():
    # ‖e^(At)‖² peaks near 1.885 at t ≈ 0.8 and is at most 1.856 from t = 1 on
    check = E.decide_flow(_norm_premise(_certificate(c2="187/100")), E.Budget())
    assert check.holds is False and check.instance.startswith("refuted at t = ")


def test_the_tail_piece_is_decided_past_t_by_p():
    cert = _certificate()
    (premise,) = [p for p in sup_flow_premises(cert) if isinstance(p, E.FlowExit) and p.index == len(cert.pieces) - 1]
    check = E.decide_flow(premise, E.Budget())
    assert (check.obligation, check.name, check.instance, check.holds) == ("sup_flow.exit", premise.name, "past T = 32 by P", True)


def test_an_empty_piece_is_refused_as_such():
    data = json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))
    data["pieces"][1]["end"] = data["pieces"][1]["start"]
    cert = SupFlowCertificate.from_dict(data)
    (premise,) = [p for p in sup_flow_premises(cert) if isinstance(p, E.FlowExit) and p.index == 1]
    check = E.decide_flow(premise, E.Budget())
    assert (check.obligation, check.name, check.instance, check.holds) == (
        "sup_flow.exit", premise.name, "empty piece [1/64, 1/64)", False)


def test_a_ball_too_wide_to_decide_refutes_nothing():
    # k_i = 100 > k_v·k_p: the flow grows like e^(0.65t), beyond 2^4096 by t = 3000
    data = json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))
    data["parameters"]["k_i"] = "100"
    data["pieces"][1]["start"], data["pieces"][1]["end"] = "3000", "3001"
    cert = SupFlowCertificate.from_dict(data)
    (premise,) = [p for p in sup_flow_premises(cert) if isinstance(p, E.FlowExit) and p.index == 1]
    check = E.decide_flow(premise, E.Budget(2))
    assert (check.obligation, check.name, check.holds) == ("sup_flow.exit", premise.name, False)
    assert check.instance == (f"not decided on [3000, 3001] within the {E.MAX_TOTAL_PARTS} parts of one verification "
                              f"(v = 0: a ball end beyond 2^{E.EXPONENT_LIMIT})")


# -- _end: a ball end as a Fraction, outward where it is tiny, refused where it is huge ---------------


def _two(k):
    import flint

    return flint.arb(2) ** k


def test_end_of_zero_is_zero():
    import flint

    assert E._end(flint.arb(0), down=True) == 0 and E._end(flint.arb(0), down=False) == 0


def test_end_is_exact_up_to_the_limit_and_refused_beyond_it():
    import flint

    n = E.EXPONENT_LIMIT
    assert E._end(_two(n - 1), down=True) == 2 ** (n - 1)  # magnitude 2^(n−1) ≤ x < 2^n: kept
    assert E._end(-_two(n - 1), down=False) == -(2 ** (n - 1))
    with pytest.raises(E._TooWide):
        E._end(_two(n), down=True)
    # a long mantissa: x = (2^52 + 1)·2^(n − 16) is beyond 2^n though its exponent is not
    with pytest.raises(E._TooWide):
        E._end(flint.arb(2**52 + 1) * _two(n - 16), down=False)
    assert E._end(flint.arb(3) * _two(-2), down=False) == Fraction(3, 4)
    assert E._end(flint.arb(3) * _two(5), down=True) == 96


def test_end_moves_outward_only_below_the_limit():
    n = E.EXPONENT_LIMIT
    assert E._end(_two(-n - 1), down=True) == Fraction(1, 2 ** (n + 1))  # magnitude 2^(−n−1): still exact
    assert E._end(-_two(-n - 1), down=False) == -Fraction(1, 2 ** (n + 1))
    tiny, bound = _two(-n - 2), Fraction(1, 2**n)
    assert (E._end(tiny, down=True), E._end(tiny, down=False)) == (0, bound)
    assert (E._end(-tiny, down=True), E._end(-tiny, down=False)) == (-bound, 0)


def test_end_of_a_long_mantissa_below_one_is_exact(precision):
    import flint

    x = Fraction(2**60 + 1, 2**70)  # 61 bits of mantissa: not a float
    assert E._end(flint.arb(2**60 + 1) * _two(-70), down=True) == x


def test_too_wide_says_where_the_limit_is():
    with pytest.raises(E._TooWide, match=rf"a ball end beyond 2\^{E.EXPONENT_LIMIT}"):
        E._end(_two(E.EXPONENT_LIMIT + 1), down=True)


def test_lower_and_upper_take_the_ends_and_round_outward():
    import flint

    ball = flint.arb(1, 0.5)  # about [1/2, 3/2] (the radius rounded up)
    assert Fraction(1, 2) - Fraction(1, 10**6) < E._lower(ball) <= Fraction(1, 2)
    assert Fraction(3, 2) <= E._upper(ball) < Fraction(3, 2) + Fraction(1, 10**6)
    tiny = _two(-2 * E.EXPONENT_LIMIT)  # a positive point below 2^-limit
    assert (E._lower(tiny), E._upper(tiny)) == (0, Fraction(1, 2**E.EXPONENT_LIMIT))
    assert (E._lower(-tiny), E._upper(-tiny)) == (-Fraction(1, 2**E.EXPONENT_LIMIT), 0)


# -- _exit_holds: both signs of σ, both planes, the off-diagonal's worse end ------------------------


def _arbs(rows):
    return tuple(tuple(E._arb(Fraction(x)) for x in row) for row in rows)


def test_exit_holds_looks_at_both_signs_of_sigma():
    # on v = 0 the off-diagonal is s·G₁₂: copositive for σ > 0, not for σ < 0
    k = _arbs(((Fraction(3, 2), 0, 0), (0, Fraction(3, 2), 0), (0, 0, 2)))
    gram = _arbs(((1, 1, 0), (1, 1, 0), (0, 0, 0)))
    for end in (E._lower, E._upper):
        holds, why = E._exit_holds(k, gram, end=end)
        assert holds is False and why.startswith("v = 0, sign σ = −: "), why
    gram = _arbs(((1, -1, 0), (-1, 1, 0), (0, 0, 0)))
    holds, why = E._exit_holds(k, gram)
    assert holds is False and why.startswith("v = 0, sign σ = +: "), why
    assert E._exit_holds(_arbs(((2, 0, 0), (0, 2, 0), (0, 0, 2))), gram) == (True, "")


def test_exit_holds_reads_the_off_diagonal_not_a_diagonal_entry():
    # the form on v = 0, σ > 0 is [[1/100, −1], [−1, 2]]: not copositive (1 > 2/100), with either end
    k = _arbs(((Fraction(101, 100), 0, 0), (0, 3, 0), (0, 0, 5)))
    gram = _arbs(((1, -1, 0), (-1, 1, 0), (0, 0, 0)))
    for end in (E._lower, E._upper):
        holds, why = E._exit_holds(k, gram, end=end)
        assert holds is False and why.startswith("v = 0, sign σ = +: "), why


def test_exit_holds_takes_the_worse_end_of_the_two_off_diagonal_balls():
    # an enclosure whose two off-diagonal entries differ: the proof takes the lower (−1), the refutation the upper (+1)
    k = _arbs(((1, 0, 0), (0, 1, 0), (0, 0, 1)))
    gram = _arbs(((Fraction(1, 2), -1, 0), (1, Fraction(1, 2), 0), (0, 0, 0)))
    assert E._exit_holds(k, gram)[0] is False
    assert E._exit_holds(k, gram, end=E._upper) == (True, "")


# -- verify_sup_flow: one budget, the enclosures not evaluated after a structural failure --------------


def test_verify_needs_a_certificate():
    from symbolic_friction._certify.sup_flow import verify_sup_flow

    with pytest.raises(TypeError, match="verify_sup_flow needs a SupFlowCertificate; got dict"):
        verify_sup_flow({})
    assert verify_sup_flow(_certificate()).source == "<certificate>"


def test_the_enclosures_are_not_evaluated_after_a_structural_failure():
    from symbolic_friction._certify.sup_flow import verify_sup_flow
    from symbolic_friction._certify.verify import Check

    data = json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))
    data["parameters"]["k_i"] = "-4"
    report = verify_sup_flow(SupFlowCertificate.from_dict(data))
    (norm,) = [c for c in report.checks if c.name.startswith("c2 ≥")]
    expected = Check("sup_flow.bounds", norm.name, "not evaluated (an earlier premise fails)", False, evaluated=False)
    assert (norm.obligation, norm.name, norm.instance, norm.holds, norm.evaluated) == (
        expected.obligation, expected.name, expected.instance, False, False)
    assert norm.holds is False and norm.evaluated is False


def test_one_budget_serves_every_enclosure_of_a_verification(monkeypatch):
    from symbolic_friction._certify import sup_flow

    made = []

    class Counted(E.Budget):
        def __init__(self, parts=None):
            super().__init__(parts)
            made.append(self)

    monkeypatch.setattr(sup_flow, "Budget", Counted)
    assert sup_flow.verify_sup_flow(_certificate()).proved
    assert len(made) == 1


def test_decide_passes_the_budget_it_is_given():
    from symbolic_friction._certify import sup_flow

    check = sup_flow._decide(_norm_premise(_certificate()), E.Budget(2))
    assert check.instance.startswith("not decided on [0, 32] within the ")


# -- sup_flow_premises: every premise cites its obligation (the structural ones gate the enclosures) ---

TWO_PIECES = [
    ('lemma2.P', 'k_i > 0'),
    ('lemma2.P', 'k_p > 0'),
    ('lemma2.P', 'k_v·k_p > k_i'),
    ('model', 'f_c > 0'),
    ('sup_flow.exit', 'the first piece starts at t = 0'),
    ('sup_flow.exit', 'piece 2 starts where piece 1 ends'),
    ('sup_flow.exit', 'the last piece ends at ∞'),
    ('sup_flow.exit', 'T > 0 (the last piece starts after 0)'),
    ('sup_flow.exit', 'p > 0'),
    ('sup_flow.exit', "P − p·I ⪰ 0 (the paper's P)"),
    ('lemma2.dVdt', "−(AᵀP + PA) ⪰ 0 (the paper's P)"),
    ('sup_flow.bounds', 'c2 ≥ ‖e^(At)‖² for every t ≥ 0'),
    ('sup_flow.bounds', 'K1 − I copositive (piece 1)'),
    ('quadratic.U_rate', 'piece 1: −(K·B+ + B+ᵀ·K) copositive'),
    ('quadratic.U_rate', 'piece 1: band form (s = +1) copositive'),
    ('quadratic.U_rate', 'piece 1: −(K·B− + B−ᵀ·K) copositive'),
    ('quadratic.U_rate', 'piece 1: band form (s = −1) copositive'),
    ('quadratic.U_rate', 'piece 1: K31 ≥ 0'),
    ('quadratic.U_rate', 'piece 1: K32 ≥ 0'),
    ('quadratic.U_rate', 'piece 1: K33 ≥ 0'),
    ('sup_flow.stability_bound', 'piece 1: gamma·I − K copositive'),
    ('sup_flow.exit', 'piece 1: U ≥ |e^(At)w|² on the exits of R̂ for t in [0, 1/64)'),
    ('quadratic.U_rate', 'piece 2: −(K·B+ + B+ᵀ·K) copositive'),
    ('quadratic.U_rate', 'piece 2: band form (s = +1) copositive'),
    ('quadratic.U_rate', 'piece 2: −(K·B− + B−ᵀ·K) copositive'),
    ('quadratic.U_rate', 'piece 2: band form (s = −1) copositive'),
    ('quadratic.U_rate', 'piece 2: K31 ≥ 0'),
    ('quadratic.U_rate', 'piece 2: K32 ≥ 0'),
    ('quadratic.U_rate', 'piece 2: K33 ≥ 0'),
    ('sup_flow.stability_bound', 'piece 2: gamma·I − K copositive'),
    ('sup_flow.exit', 'piece 2: U ≥ |e^(At)w|² on the exits of R̂ for t in [1/64, ∞)'),
    ('sup_flow.stability_bound', 'overshoot_bound > 0'),
    ('sup_flow.stability_bound', 'overshoot_bound² ≥ c2'),
    ('sup_flow.stability_bound', 'overshoot_bound² ≥ gamma (piece 1)'),
    ('sup_flow.stability_bound', 'overshoot_bound² ≥ gamma (piece 2)'),
]
"""Every premise of a two-piece certificate ([0, 1/64) and [1/64, ∞)), in proof order, with the obligation it cites."""


def test_every_premise_cites_its_obligation_in_proof_order():
    data = json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))
    first, tail = data["pieces"][0], data["pieces"][-1]
    first["end"] = tail["start"] = "1/64"
    data["pieces"] = [first, tail]
    assert [(p.obligation, p.name) for p in sup_flow_premises(SupFlowCertificate.from_dict(data))] == TWO_PIECES


def test_the_report_names_its_source():
    from symbolic_friction._certify.sup_flow import verify_sup_flow

    assert verify_sup_flow(_certificate(), source="case_a.json").source == "case_a.json"


def test_exit_map_refuses_an_unknown_plane_naming_the_planes():
    from symbolic_friction._model import sup_flow as model

    with pytest.raises(ValueError, match=r"exit plane must be one of \('v = 0', 'φ = f_c'\); got 'v = 1'"):
        model.exit_map("v = 1", 1)
