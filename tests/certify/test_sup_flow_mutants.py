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



def _v1(k):
    """Version 1's forms for ``_exit_holds``: one ``K`` for both signs of ``σ``, no drag map."""
    return ((1, k, None), (-1, k, None))

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
    assert why == f"not decided on [0.5, 1] within the 6 parts of one verification (too long)"
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

from symbolic_friction._certify.sup_flow import TAIL_CONSTANTS, SupFlowCertificate, sup_flow_premises  # noqa: E402

PROOFS = Path(__file__).resolve().parent / "data" / "sup_flow_v1"  # version 1 files (proofs/sup_flow/ is version 2 now)


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
    # T = 8, the last piece's start (not the start of any earlier piece)
    assert re.fullmatch(r"c2 = 104834527537/50000000000 on \[0, 8\] in \d+ parts and past it by P", check.instance)


def test_a_tail_form_above_c2_is_refused_at_t():
    premise = _norm_premise(_certificate(p="1/10000000000000000000000000000000000000000"))
    check = E.decide_flow(premise, E.Budget())
    assert (check.obligation, check.name, check.instance, check.holds) == (
        "sup_flow.bounds", premise.name, "the tail form at T = 8 is not below c2", False)


def test_a_norm_not_decided_within_the_budget_says_why():
    check = E.decide_flow(_norm_premise(_certificate()), E.Budget(2))
    assert check.holds is False
    assert check.instance == (f"not decided on [0, 8] within the 2 parts of one verification "
                              "(‖e^(At)‖² ≥ c2 or too close to it)")


def test_the_norm_is_decided_from_t_0():
    # ‖e^(At)‖² peaks near 1.885 at t ≈ 0.8 and is at most 1.856 from t = 1 on
    check = E.decide_flow(_norm_premise(_certificate(c2="187/100")), E.Budget())
    assert check.holds is False and check.instance.startswith("refuted at t = ")


def test_the_tail_piece_is_decided_past_t_by_p():
    cert = _certificate()
    (premise,) = [p for p in sup_flow_premises(cert) if isinstance(p, E.FlowExit) and p.index == len(cert.pieces) - 1]
    check = E.decide_flow(premise, E.Budget())
    assert (check.obligation, check.name, check.instance, check.holds) == ("sup_flow.exit", premise.name, "past T = 8 by P", True)


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
    assert check.instance == (f"not decided on [3000, 3001] within the 2 parts of one verification "
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
        holds, why = E._exit_holds(_v1(k), gram, end=end)
        assert holds is False and why.startswith("v = 0, sign σ = −: "), why
    gram = _arbs(((1, -1, 0), (-1, 1, 0), (0, 0, 0)))
    holds, why = E._exit_holds(_v1(k), gram)
    assert holds is False and why.startswith("v = 0, sign σ = +: "), why
    assert E._exit_holds(_v1(_arbs(((2, 0, 0), (0, 2, 0), (0, 0, 2)))), gram) == (True, "")


def test_exit_holds_reads_the_off_diagonal_not_a_diagonal_entry():
    # the form on v = 0, σ > 0 is [[1/100, −1], [−1, 2]]: not copositive (1 > 2/100), with either end
    k = _arbs(((Fraction(101, 100), 0, 0), (0, 3, 0), (0, 0, 5)))
    gram = _arbs(((1, -1, 0), (-1, 1, 0), (0, 0, 0)))
    for end in (E._lower, E._upper):
        holds, why = E._exit_holds(_v1(k), gram, end=end)
        assert holds is False and why.startswith("v = 0, sign σ = +: "), why


def test_exit_holds_takes_the_worse_end_of_the_two_off_diagonal_balls():
    # an enclosure whose two off-diagonal entries differ: the proof takes the lower (−1), the refutation the upper (+1)
    k = _arbs(((1, 0, 0), (0, 1, 0), (0, 0, 1)))
    gram = _arbs(((Fraction(1, 2), -1, 0), (1, Fraction(1, 2), 0), (0, 0, 0)))
    assert E._exit_holds(_v1(k), gram)[0] is False
    assert E._exit_holds(_v1(k), gram, end=E._upper) == (True, "")


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
    assert check.instance.startswith("not decided on [0, 8] within the ")


# -- sup_flow_premises: every premise cites its obligation (the structural ones gate the enclosures) ---

TWO_PIECES = [
    ('lemma2.P', 'k_i > 0'),
    ('lemma2.P', 'k_p > 0'),
    ('lemma2.P', 'k_v·k_p > k_i'),
    ('model', 'f_c > 0'),
    ('sup_flow.exit', 'the first piece starts at t = 0'),
    ('sup_flow.exit', 'piece 2 starts where piece 1 ends'),
    ('sup_flow.exit', 'the last piece ends at ∞'),
    ('sup_flow.exit', 'T ≥ 0 (the last piece starts at or after 0)'),
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
    own = [(p.obligation, p.name) for p in sup_flow_premises(SupFlowCertificate.from_dict(data))]
    # the file's own tail P: its two premises are the tail's, cited as sup_flow.exit
    assert own == [(o, n.replace("(the paper's P)", "(the tail's P)")) if "the paper's P" in n else (o, n) for o, n in
                   TWO_PIECES][:10] + [("sup_flow.exit", "−(AᵀP + PA) ⪰ 0 (the tail's P)")] + TWO_PIECES[11:]
    for name in TAIL_CONSTANTS:  # without them, the paper's P (a file of the first format)
        del data["constants"][name]
    assert [(p.obligation, p.name) for p in sup_flow_premises(SupFlowCertificate.from_dict(data))] == TWO_PIECES


def test_the_report_names_its_source():
    from symbolic_friction._certify.sup_flow import verify_sup_flow

    assert verify_sup_flow(_certificate(), source="case_a.json").source == "case_a.json"


def test_exit_map_refuses_an_unknown_plane_naming_the_planes():
    from symbolic_friction._model import sup_flow as model

    with pytest.raises(ValueError, match=r"exit plane must be one of \('v = 0', 'φ = f_c'\); got 'v = 1'"):
        model.exit_map("v = 1", 1)


# -- the reader: SupFlowPiece, SupFlowCertificate, from_dict, load_sup_flow ------------------------------
# Each validation refuses a bad value with the message naming it, and accepts the good value at its boundary.

import dataclasses  # noqa: E402

from symbolic_friction._certify.sup_flow import (  # noqa: E402
    CONSTANTS, MAX_PIECES, PARAMETERS, PIECE_CONSTANTS, SupFlowPiece, load_sup_flow)
from symbolic_friction._infra.errors import CertificateFormatError  # noqa: E402

_K = {"k11": 2, "k13": -1, "k22": 2, "k23": Fraction(1, 3), "k33": 1, "gamma": 3}
_ALLOWED = "start, end, k11, k13, k22, k23, k33, gamma"


def _piece(**fields):
    args = {"start": Fraction(0), "end": None, "constants": dict(_K)}
    args.update(fields)
    return SupFlowPiece(**args)


def _refused(build, message):
    with pytest.raises(CertificateFormatError) as caught:
        build()
    assert str(caught.value) == message


def test_a_piece_holds_fractions_of_the_ints_it_is_given():
    piece = _piece(start=1, end=2, constants=dict(reversed(list(_K.items()))))
    assert (piece.start, piece.end) == (1, 2) and type(piece.start) is Fraction and type(piece.end) is Fraction
    assert list(piece.constants) == list(PIECE_CONSTANTS)  # in the format's order, whatever order was given
    assert piece.constants == {n: Fraction(_K[n]) for n in PIECE_CONSTANTS}
    assert all(type(v) is Fraction for v in piece.constants.values())
    assert _piece().end is None  # ∞
    assert _piece(start=Fraction(-1, 3)).start == Fraction(-1, 3)  # any sign: the order of pieces is a premise


@pytest.mark.parametrize("value", ["0", 0.5, True, None])
def test_a_piece_start_must_be_an_exact_rational(value):
    _refused(lambda: _piece(start=value), f"piece start must be an exact rational; got {value!r}")


@pytest.mark.parametrize("value", ["1/2", 0.5, False])
def test_a_piece_end_must_be_an_exact_rational_or_none(value):
    _refused(lambda: _piece(end=value), f"piece end must be an exact rational; got {value!r}")


@pytest.mark.parametrize("name", PIECE_CONSTANTS)
def test_each_piece_constant_must_be_an_exact_rational(name):
    _refused(lambda: _piece(constants={**_K, name: "1"}), f"piece {name} must be an exact rational; got '1'")


def test_a_piece_has_exactly_its_six_constants():
    missing = {n: v for n, v in _K.items() if n != "gamma"}
    _refused(lambda: _piece(constants=missing),
             "a piece's constants must be exactly k11, k13, k22, k23, k33, gamma; got k11, k13, k22, k23, k33")
    _refused(lambda: _piece(constants={**_K, "k12": 0}),
             "a piece's constants must be exactly k11, k13, k22, k23, k33, gamma; got gamma, k11, k12, k13, k22, k23, k33")


def test_a_certificate_holds_fractions_of_the_ints_it_is_given():
    cert = _certificate()
    made = dataclasses.replace(cert, k_p=3, k_i=4, k_v=Fraction(32, 5), f_c=1, constants={"p": 1, "c2": 2},
                               pieces=list(cert.pieces))
    assert made.parameters == {"k_p": 3, "k_i": 4, "k_v": Fraction(32, 5), "f_c": 1}
    assert all(type(getattr(made, n)) is Fraction for n in PARAMETERS)
    assert list(made.constants) == list(CONSTANTS) and made.constants == {"c2": 2, "p": 1}
    assert all(type(v) is Fraction for v in made.constants.values())
    assert made.pieces == cert.pieces and type(made.pieces) is tuple
    negative = dataclasses.replace(cert, k_i=-4, constants={"c2": -1, "p": 0})  # signs are premises, not format
    assert (negative.k_i, negative.constants) == (-4, {"c2": -1, "p": 0})


@pytest.mark.parametrize("name", PARAMETERS)
def test_each_gain_must_be_an_exact_rational(name):
    _refused(lambda: dataclasses.replace(_certificate(), **{name: "3"}), f"parameters.{name} must be an exact rational; got '3'")


def test_the_constants_are_exactly_c2_and_p_each_exact():
    cert = _certificate()
    tail = "with or without all of tail_p11, tail_p12, tail_p13, tail_p22, tail_p23, tail_p33"
    _refused(lambda: dataclasses.replace(cert, constants={"c2": 2}), f"constants must be exactly c2, p, {tail}; got c2")
    _refused(lambda: dataclasses.replace(cert, constants={"c2": 2, "p": 1, "tail_p11": 1}),
             f"constants must be exactly c2, p, {tail}; got c2, p, tail_p11")
    _refused(lambda: dataclasses.replace(cert, constants={"c2": 2, "p": 1, "q": 0}),
             f"constants must be exactly c2, p, {tail}; got c2, p, q")
    _refused(lambda: dataclasses.replace(cert, constants={"c2": 0.5, "p": 1}), "constants.c2 must be an exact rational; got 0.5")
    _refused(lambda: dataclasses.replace(cert, constants={"c2": 2, "p": "1"}), "constants.p must be an exact rational; got '1'")


def test_a_certificate_has_1_to_max_pieces_pieces():
    cert = _certificate()
    piece = cert.pieces[-1]
    assert len(dataclasses.replace(cert, pieces=(piece,)).pieces) == 1
    assert len(dataclasses.replace(cert, pieces=(piece,) * MAX_PIECES).pieces) == MAX_PIECES == 256
    _refused(lambda: dataclasses.replace(cert, pieces=()), "a sup-flow certificate has 1 to 256 pieces; got 0")
    _refused(lambda: dataclasses.replace(cert, pieces=(piece,) * 257), "a sup-flow certificate has 1 to 256 pieces; got 257")
    _refused(lambda: dataclasses.replace(cert, pieces=(piece, piece.to_dict())),
             "a sup-flow certificate has 1 to 256 pieces; got 2")


def _case_a():
    return json.loads((PROOFS / "case_a.json").read_text(encoding="utf-8"))


def test_the_reader_reads_every_number_of_the_file():
    data = _case_a()
    cert = SupFlowCertificate.from_dict(data)
    assert cert.parameters == {n: Fraction(data["parameters"][n]) for n in PARAMETERS}
    assert cert.constants == {n: Fraction(data["constants"][n]) for n in CONSTANTS + TAIL_CONSTANTS}
    assert len(cert.pieces) == len(data["pieces"]) == 33
    for piece, item in zip(cert.pieces, data["pieces"]):
        assert piece.start == Fraction(item["start"])
        assert piece.end == (None if item["end"] == "inf" else Fraction(item["end"]))
        assert piece.constants == {n: Fraction(item[n]) for n in PIECE_CONSTANTS}
    assert cert.pieces[-1].end is None and cert.pieces[-2].end == cert.pieces[-1].start == 8
    assert cert.overshoot_bound == data["overshoot_bound"] and cert.provenance.to_dict() == data["provenance"]
    assert SupFlowCertificate.from_dict(cert.to_dict()) == cert


def _from(edit, source="f.json"):
    data = _case_a()
    edit(data)
    return lambda: SupFlowCertificate.from_dict(data, source=source)


def test_the_reader_takes_1_to_max_pieces_pieces():
    one = SupFlowCertificate.from_dict({**_case_a(), "pieces": _case_a()["pieces"][-1:]})
    assert len(one.pieces) == 1 and one.pieces[0].end is None
    many = SupFlowCertificate.from_dict({**_case_a(), "pieces": _case_a()["pieces"][-1:] * MAX_PIECES})
    assert len(many.pieces) == MAX_PIECES
    message = "f.json: pieces must be a list of 1 to 256 objects; got {}"
    _refused(_from(lambda d: d.update(pieces=[])), message.format(0))
    _refused(_from(lambda d: d.update(pieces=d["pieces"][-1:] * 257)), message.format(257))
    _refused(_from(lambda d: d.update(pieces={"0": d["pieces"][0]})), message.format("dict"))
    _refused(_from(lambda d: d.update(pieces="pieces"), source="g.json"),
             "g.json: pieces must be a list of 1 to 256 objects; got str")


def test_each_piece_must_be_an_object_with_exactly_its_keys():
    _refused(_from(lambda d: d["pieces"].__setitem__(1, "piece")), "f.json: pieces[1] must be a JSON object; got str")
    _refused(_from(lambda d: d["pieces"][1].pop("k23")), f"missing key 'pieces[1].k23' in pieces[1] (required: {_ALLOWED})")
    _refused(_from(lambda d: d["pieces"][1].pop("start")), f"missing key 'pieces[1].start' in pieces[1] (required: {_ALLOWED})")
    _refused(_from(lambda d: d["pieces"][1].pop("end")), f"missing key 'pieces[1].end' in pieces[1] (required: {_ALLOWED})")
    _refused(_from(lambda d: d["pieces"][1].update(k12="0")), f"unknown key 'k12' in pieces[1] (allowed: {_ALLOWED})")


@pytest.mark.parametrize("key", ["start", "end", *PIECE_CONSTANTS])
def test_each_piece_value_is_an_exact_rational_string_named_by_its_place(key):
    shape = "must be an exact rational string such as '32/5' or '4' (ASCII digits, no decimals, no spaces)"
    _refused(_from(lambda d: d["pieces"][1].update({key: "1.5"})), f"pieces[1].{key} {shape}; got '1.5'")
    _refused(_from(lambda d: d["pieces"][2].update({key: 2})),
             f"pieces[2].{key} must be a string holding an exact rational such as '32/5' or '4'; got the int 2")
    if key != "end":
        _refused(_from(lambda d: d["pieces"][1].update({key: "inf"})), f"pieces[1].{key} {shape}; got 'inf'")


def test_only_the_end_reads_inf_as_infinity_and_only_spelled_inf():
    cert = SupFlowCertificate.from_dict(_case_a())
    assert [p.end is None for p in cert.pieces] == [False] * 32 + [True]
    shape = "must be an exact rational string such as '32/5' or '4' (ASCII digits, no decimals, no spaces)"
    _refused(_from(lambda d: d["pieces"][-1].update(end="Inf")), f"pieces[32].end {shape}; got 'Inf'")


def test_load_reads_the_file_and_names_it(tmp_path):
    good = tmp_path / "case_a.json"
    good.write_text((PROOFS / "case_a.json").read_text(encoding="utf-8"), encoding="utf-8")
    assert load_sup_flow(good) == load_sup_flow(str(good)) == SupFlowCertificate.from_dict(_case_a())
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**_case_a(), "pieces": []}), encoding="utf-8")
    _refused(lambda: load_sup_flow(bad), f"{bad}: pieces must be a list of 1 to 256 objects; got 0")


# -- _lower_ends_clearly_copositive: the arb shortcut proves a form only where the exact decision does ---


def _form(rows):
    import flint

    return tuple(tuple(x if isinstance(x, flint.arb) else flint.arb(Fraction(x).numerator) / Fraction(x).denominator
                       for x in row) for row in rows)


def _exact_lower_ends(form):
    from symbolic_friction._certify.copositive import decide_copositive

    off = min(E._lower(form[0][1]), E._lower(form[1][0]))  # as _exit_holds builds the symmetric matrix
    return decide_copositive(((E._lower(form[0][0]), off), (off, E._lower(form[1][1])))).holds


@pytest.mark.parametrize("rows", [
    [[0, 1], [1, 1]],  # a = 0 is on the boundary of a ≥ 0
    [[1, 1], [1, 0]],  # c = 0
    [[Fraction(1, 4), Fraction(1, 2)], [Fraction(1, 2), Fraction(1, 4)]],  # 0 ≤ b < 1 with b² > ac
    [[1, -1], [-1, 4]],  # b < 0 with b² = 1 ≤ ac = 4 (but > a/c)
    [[1, 0], [0, 1]],
])
def test_the_shortcut_proves_copositive_lower_ends_at_the_boundaries(rows):
    form = _form(rows)
    assert _exact_lower_ends(form) is True
    assert E._lower_ends_clearly_copositive(form) is True


@pytest.mark.parametrize("rows", [
    [[1, 1], [1, "wide"]],  # c's lower end is −2, its upper end 2
    [[1, "wide"], [1, 1]],  # the (1,2) entry reaches −2 (its upper end does not)
    [[1, 1], ["wide", 1]],  # the (2,1) entry reaches −2
    [[1, -2], [1, 1]],  # b is the smaller off-diagonal end, not the diagonal c
    [[1, 1], [-2, 1]],
    [[16, -3], [-3, Fraction(1, 4)]],  # b² = 9 > ac = 4 (though ≤ a/c = 64)
])
def test_the_shortcut_does_not_prove_what_the_exact_decision_refutes(rows):
    import flint

    form = _form([[flint.arb(0, 2) if x == "wide" else x for x in row] for row in rows])
    assert _exact_lower_ends(form) is False
    assert E._lower_ends_clearly_copositive(form) is False


@pytest.mark.parametrize("where", [(0, 0), (0, 1), (1, 1)])
def test_the_shortcut_proves_nothing_with_an_infinite_end(where):
    import flint

    rows = [[1, 0], [0, 1]]
    rows[where[0]][where[1]] = flint.arb(float("inf"))
    if where == (0, 1):
        rows[1][0] = flint.arb(float("inf"))
    form = _form(rows)
    assert form[where[0]][where[1]].lower() >= 0  # +∞: "nonnegative", but no number the exact decision can take
    assert E._lower_ends_clearly_copositive(form) is False


# -- _system_of: A built once per gains and precision, at most 64 kept ---------------------------------


def _entries_text(m):
    return [str(m[i, j]) for i in range(3) for j in range(3)]


def test_the_system_is_the_one_of_its_own_gains_and_built_once(monkeypatch):
    import flint

    from symbolic_friction._certify.flow_bound import _system

    monkeypatch.setattr(E, "_SYSTEMS", {})
    other = SimpleNamespace(k_p=Fraction(3), k_i=Fraction(4), k_v=Fraction(7))  # only k_v differs
    old = flint.ctx.prec
    try:
        flint.ctx.prec = 200
        first = E._system_of(GAINS)
        assert E._system_of(GAINS) is first  # the same balls every time
        assert _entries_text(E._system_of(other)) == _entries_text(_system(other)) != _entries_text(first)
        assert _entries_text(first) == _entries_text(_system(GAINS))
    finally:
        flint.ctx.prec = old


def test_at_most_64_systems_are_kept(monkeypatch):
    monkeypatch.setattr(E, "_SYSTEMS", {})
    for k_v in range(10, 10 + 64):
        E._system_of(SimpleNamespace(k_p=Fraction(3), k_i=Fraction(4), k_v=Fraction(k_v)))
    assert len(E._SYSTEMS) == 64
    E._system_of(SimpleNamespace(k_p=Fraction(3), k_i=Fraction(4), k_v=Fraction(100)))
    assert len(E._SYSTEMS) == 1  # the 65th clears the others


def test_exit_holds_decides_the_other_plane_after_the_shortcut_proves_one():
    # σ > 0: the form on v = 0 is clearly copositive, the one on φ = f_c has the diagonal entry 1 − 2 < 0
    k = _arbs(((1, 0, 0), (0, 1, 0), (0, 0, 1)))
    gram = _arbs(((0, 0, 0), (0, 0, 0), (0, 0, 2)))
    holds, why = E._exit_holds(_v1(k), gram)
    assert holds is False and why.startswith("φ = f_c, sign σ = +: "), why


def test_the_shortcut_spares_the_exact_decision_of_a_clearly_copositive_form(monkeypatch):
    from symbolic_friction._certify import copositive

    def exact(rows):
        raise AssertionError("decided exactly")

    monkeypatch.setattr(copositive, "decide_copositive", exact)
    k = _arbs(((2, 0, 0), (0, 2, 0), (0, 0, 2)))
    assert E._exit_holds(_v1(k), _arbs(((0, 0, 0), (0, 0, 0), (0, 0, 0)))) == (True, "")


def test_the_reader_names_its_source_in_the_shared_checks_and_defaults_to_string():
    _refused(lambda: SupFlowCertificate.from_dict([], source="f.json"), "f.json: a sup-flow certificate is a JSON object; got list")
    _refused(lambda: SupFlowCertificate.from_dict([]), "<string>: a sup-flow certificate is a JSON object; got list")
    _refused(lambda: SupFlowCertificate.from_dict({**_case_a(), "pieces": []}),
             "<string>: pieces must be a list of 1 to 256 objects; got 0")
