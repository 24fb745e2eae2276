"""The independent checker's paper, box and quadratic modules (issue 33).

* every committed certificate of these kinds, and every true control of the self-check, is proved;
* every false file of the self-check is refused, naming the premises the manifest names (the main
  verifier's format rule ``c = 2(k_v·k_p − k_i)`` becomes the premise ``c ≤ 2(k_v·k_p − k_i)`` here);
* every premise decides: with the other premises a false certificate breaks held true, the premise alone
  refuses it, and made always-true as well it lets the false certificate through;
* the modules import the standard library, python-flint and the checker's own modules only;
* on edited copies of the committed files the two verifiers agree, but for the main verifier's format rules.
"""

from __future__ import annotations

import ast
import copy
import json
import random
import re
import sys
import time
from fractions import Fraction
from pathlib import Path

import pytest

from symbolic_friction import independent
from symbolic_friction.independent import box, paper, quadratic
from symbolic_friction.independent._core import Malformed, Verdict

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "symbolic_friction" / "independent"
FALSE = ROOT / "symbolic_friction" / "_certify" / "false_certificates"
MANIFEST = json.loads((FALSE / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
MODULES = {"paper": paper, "box": box, "quadratic": quadratic}
SELF_CHECK = {"stability": paper, "quadratic": quadratic}  # the manifest's templates of these kinds (no box files)
C_EQUATION, C_BOUND = "c = 2(k_v·k_p − k_i)", "c ≤ 2(k_v·k_p − k_i)"


def kind(data: dict):
    """The module of this checker that decides ``data`` (None for the other kinds)."""
    template = data.get("template") or independent._SCHEMAS.get(data.get("schema"))
    return MODULES.get(independent.KINDS.get(template))


def read(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


PROOFS = sorted(p for p in (ROOT / "proofs").rglob("*.json") if kind(read(p)) is not None)
FALSE_FILES = [e for e in MANIFEST if e["template"] in SELF_CHECK and e["premise"] is not None]
TRUE_FILES = [e for e in MANIFEST if e["template"] in SELF_CHECK and e["premise"] is None]


def verdict_of(module, data: dict) -> Verdict | None:
    """The module's verdict, or None when it finds the file malformed (not proved either)."""
    try:
        return module.check(data)
    except Malformed:
        return None


def masking(names: set[str]) -> type[Verdict]:
    """A ``Verdict`` whose premises called ``names`` always hold (a premise made always-true)."""

    class Masked(Verdict):
        def add(self, name: str, holds, why: str = "") -> bool:
            return super().add(name, True if name in names else holds, why)

    return Masked


# -- the committed certificates and the self-check ------------------------------------------------------------


def test_every_kind_has_committed_files():
    assert {kind(read(p)) for p in PROOFS} == set(MODULES.values())


@pytest.mark.parametrize("path", PROOFS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_committed_certificate_is_proved(path):
    start = time.perf_counter()
    verdict = independent.check_file(str(path))
    assert verdict.proved, verdict.failing
    assert time.perf_counter() - start < 0.5  # milliseconds in fact (a box of 16 pieces: about 15 ms)


@pytest.mark.parametrize("entry", TRUE_FILES, ids=lambda e: e["file"])
def test_the_true_controls_are_proved(entry):
    verdict = SELF_CHECK[entry["template"]].check(read(FALSE / entry["file"]))
    assert verdict.proved, verdict.failing


def expected_failures(entry: dict) -> set[str]:
    """The manifest's failing premises, with the main verifier's equation for ``c`` as this checker's bound."""
    fails = set(entry["fails"])
    if C_EQUATION in fails:
        fails.discard(C_EQUATION)
        data = read(FALSE / entry["file"])
        g = {n: Fraction(v) for n, v in data["parameters"].items()}
        if Fraction(data["constants"]["c"]) > 2 * (g["k_v"] * g["k_p"] - g["k_i"]):
            fails.add(C_BOUND)
    return fails


@pytest.mark.parametrize("entry", FALSE_FILES, ids=lambda e: e["file"])
def test_every_false_file_is_refused_naming_its_premises(entry):
    verdict = verdict_of(SELF_CHECK[entry["template"]], read(FALSE / entry["file"]))
    assert verdict is not None and not verdict.proved
    assert set(verdict.failing) == expected_failures(entry)


def test_the_c_equation_is_decided_as_lemma_2_needs_it():
    # a smaller positive rate still gives dV/dt ≤ −c·v² (the main verifier's equation is a format rule)
    data = read(FALSE / "true_stability.json")
    data["constants"]["c"] = "1"
    assert paper.check(data).proved


# -- crafted false certificates for the premises the self-check does not break alone --------------------------


def stability_with_physical(**edit: str) -> dict:
    """The true stability control, recording physical parameters (m = 2) that normalise to its gains."""
    data = read(FALSE / "true_stability.json")
    g = {n: Fraction(v) for n, v in data["parameters"].items()}
    m = Fraction(2)
    data["physical"] = {"m": "2", "k_p_bar": str(g["k_p"] * m), "k_i_bar": str(g["k_i"] * m),
                        "k_d_bar": str(g["k_v"] * m - Fraction(1, 5)), "alpha_v": "1/5", "f_c_bar": str(g["f_c"] * m)}
    data["physical"].update(edit)
    return data


def test_a_recorded_physical_gain_set_is_checked():
    assert paper.check(stability_with_physical()).proved
    data = stability_with_physical(m="-2", k_p_bar="-6", k_i_bar="-8", k_d_bar="-13", alpha_v="1/5", f_c_bar="-2")
    assert paper.check(data).failing == ["physical: m > 0, alpha_v ≥ 0"]


BOX_A = ROOT / "proofs" / "box_case_a_10pct.json"
BOX_PHYSICAL = ROOT / "proofs" / "box_physical.json"


def box_edit(path: Path, edit) -> dict:
    data = read(path)
    edit(data)
    return data


def _drop_piece(d):
    del d["pieces"][1]


def _duplicate_sibling(d):
    d["pieces"][2] = copy.deepcopy(d["pieces"][1])  # the halves of one bisection: same volume, one region missing


def _shift_out(d):
    # moved below the box (same volume, its region missing), with constants that hold there
    d["pieces"][0].update(k_p=["12/5", "27/10"])
    d["pieces"][0]["constants"].update(c1="4/5", c2="17/5")


def flat_in_k_p(d):
    """The slice k_p = 3 of the 10 % box, covered by the three pieces that hold it (the third can be dropped)."""
    d["box"]["k_p"] = ["3", "3"]
    d["pieces"] = [dict(p, k_p=["3", "3"]) for p in d["pieces"][:3]]


def _flat_dropped(d):
    flat_in_k_p(d)
    del d["pieces"][2]


def _f_c_from_zero(d):
    d["box"]["f_c"][0] = "0"


def _physical(name, hi):
    def edit(d):
        d["physical"][name][1] = hi
    return edit


def _negative_alpha(d):  # the same k_d + α_v, with a negative viscous coefficient
    d["physical"]["alpha_v"][0] = "-1/10"
    d["physical"]["k_d_bar"][0] = str(Fraction(d["physical"]["k_d_bar"][0]) + Fraction(1, 2))


def _quadratic_c(value):
    data = read(FALSE / "true_quadratic.json")
    data["constants"]["c"] = value  # dV/dt ≤ −c·v² claimed with too large a c
    return data


def _constant(i, name, value):
    def edit(d):
        d["pieces"][i]["constants"][name] = value
    return edit


CRAFTED = {
    "stability physical k_p": (paper, lambda: stability_with_physical(k_p_bar="7")),
    "stability physical k_i": (paper, lambda: stability_with_physical(k_i_bar="9")),
    "stability physical k_v": (paper, lambda: stability_with_physical(k_d_bar="13")),
    "stability physical f_c": (paper, lambda: stability_with_physical(f_c_bar="3")),
    "stability physical m": (paper, lambda: stability_with_physical(
        m="-2", k_p_bar="-6", k_i_bar="-8", k_d_bar="-13", f_c_bar="-2")),
    "quadratic: c above the decrease": (quadratic, lambda: _quadratic_c("1")),
    "box: a piece dropped": (box, lambda: box_edit(BOX_A, _drop_piece)),
    "box: flat in k_p, a piece dropped": (box, lambda: box_edit(BOX_A, _flat_dropped)),
    "box: f_c from 0": (box, lambda: box_edit(BOX_A, _f_c_from_zero)),
    "box: a piece twice": (box, lambda: box_edit(BOX_A, _duplicate_sibling)),
    "box: a piece outside": (box, lambda: box_edit(BOX_A, _shift_out)),
    "box: c1 above λ_min at a corner": (box, lambda: box_edit(BOX_A, _constant(0, "c1", "23/25"))),
    "box: physical k_p": (box, lambda: box_edit(BOX_PHYSICAL, _physical("k_p_bar", "7"))),
    "box: physical k_i": (box, lambda: box_edit(BOX_PHYSICAL, _physical("k_i_bar", "9"))),
    "box: physical k_v": (box, lambda: box_edit(BOX_PHYSICAL, _physical("k_d_bar", "14"))),
    "box: physical f_c": (box, lambda: box_edit(BOX_PHYSICAL, _physical("f_c_bar", "3"))),
    "box: physical alpha_v": (box, lambda: box_edit(BOX_PHYSICAL, _negative_alpha)),
}
"""False certificates not in the self-check (it ships no box file), each breaking the premises it names."""


def false_cases():
    for entry in FALSE_FILES:
        yield entry["file"], SELF_CHECK[entry["template"]], read(FALSE / entry["file"])
    for name, (module, make) in CRAFTED.items():
        yield name, module, make()


CASES = list(false_cases())


@pytest.mark.parametrize("name, module, data", CASES, ids=[c[0] for c in CASES])
def test_each_failing_premise_alone_refuses_and_made_true_accepts(monkeypatch, name, module, data):
    failing = set(module.check(data).failing)
    assert failing, f"{name} is proved"
    monkeypatch.setattr(module, "Verdict", masking(failing))
    assert module.check(data).proved, "with every failing premise held true the file is accepted"
    for premise in failing:
        monkeypatch.setattr(module, "Verdict", masking(failing - {premise}))
        assert module.check(data).failing == [premise], f"{premise} alone refuses {name}"


@pytest.mark.parametrize("name", CRAFTED)
def test_the_crafted_files_are_refused_by_the_main_verifier_too(name):
    assert main_verdict(CRAFTED[name][1]()) is not True


def _generic(name: str) -> str:
    return re.sub(r"^piece \d+", "piece N", name)


@pytest.mark.parametrize("module", MODULES.values(), ids=MODULES)
def test_every_premise_is_broken_by_some_false_certificate(module):
    named = set()
    for path in PROOFS + [FALSE / e["file"] for e in TRUE_FILES]:
        if kind(read(path)) is module:
            named |= {_generic(n) for n, _, _ in module.check(read(path)).premises}
    named |= {_generic(n) for n, _, _ in module.check(stability_with_physical()).premises} if module is paper else set()
    broken = {_generic(n) for _, m, data in CASES if m is module for n in m.check(data).failing}
    assert named and named <= broken, f"no false certificate breaks {sorted(named - broken)}"


# -- the forms stand for what the proofs say: checked against the dynamics at random exact points ---------


def _random(rng, lo=-5, hi=5) -> Fraction:
    return Fraction(rng.randint(lo * 1000, hi * 1000), rng.randint(1, 1000))


def _form(m, y) -> Fraction:
    return sum(m[i][j] * y[i] * y[j] for i in range(len(y)) for j in range(len(y)))


@pytest.mark.parametrize("seed", range(20))
def test_the_quadratic_forms_are_the_rates_and_differences_they_stand_for(seed):
    rng = random.Random(seed)
    g = {"k_p": _random(rng, 0), "k_i": _random(rng, 0), "k_v": _random(rng, 0), "f_c": _random(rng, 0) + 1}
    k = {n: _random(rng) for n in quadratic.CONSTANTS}
    kp, ki, kv, fc = g["k_p"], g["k_i"], g["k_v"], g["f_c"]
    forms = quadratic.matrices(g, k)
    p23 = ki * k["p11"] - kv * k["p22"]
    P = [[k["p11"], 0, -k["p22"]], [0, k["p22"], p23], [-k["p22"], p23, k["p33"]]]
    K = [[k["k11"], 0, k["k13"]], [0, k["k22"], k["k23"]], [k["k13"], k["k23"], k["k33"]]]

    def U(y):
        return _form(K, y)

    def V(x):  # eq. (lyapLikeV) at v ≠ 0, where the friction is f_c·sign(v)
        w = (x[0], x[1] - fc * (1 if x[2] > 0 else -1), x[2])
        return _form(P, w)

    def flow(x):  # eq. (xDot) during a slip: σ' = −k_i v, φ' = σ − k_p v, v' = φ − k_v v − f_c sign(v)
        return (-ki * x[2], x[0] - kp * x[2], x[1] - kv * x[2] - fc * (1 if x[2] > 0 else -1))

    w = [_random(rng) for _ in range(3)]
    w_dot = (-ki * w[2], w[0] - kp * w[2], w[1] - kv * w[2])  # ẇ = Aw
    rate = 2 * sum(P[i][j] * w[i] * w_dot[j] for i in range(3) for j in range(3))
    assert _form(forms["−(AᵀP + PA) − c·e3e3ᵀ ⪰ 0"], w) == -rate - k["c"] * w[2] ** 2
    v = _random(rng, 0) + Fraction(1, 1000)
    for s, sign in ((1, "+"), (-1, "−")):
        sigma = s * (_random(rng, 0) + Fraction(1, 1000))
        # outside the band (φ < −f_c): y = (|σ|, −φ − f_c, v), f = 2f_c
        x = (sigma, -fc - _random(rng, 0) - Fraction(1, 1000), v)
        y, x_dot = (abs(x[0]), -x[1] - fc, v), flow(x)
        y_dot = (s * x_dot[0], -x_dot[1], x_dot[2])
        u_dot = 2 * sum(K[i][j] * y[i] * y_dot[j] for i in range(3) for j in range(3))
        friction = 2 * (K[2][0] * y[0] + K[2][1] * y[1] + K[2][2] * y[2]) * 2 * fc
        assert u_dot == -_form(forms[f"−(K·B{sign} + B{sign}ᵀ·K) copositive"], y) - friction
        # inside the band (|φ| ≤ f_c): y₂ = 0, f = f_c − φ
        x = (sigma, fc * (2 * _random(rng, 0, 1) - 1), v)
        y, x_dot = (abs(x[0]), 0, v), flow(x)
        y_dot = (s * x_dot[0], 0, x_dot[2])
        u_dot = 2 * sum(K[i][j] * y[i] * y_dot[j] for i in range(3) for j in range(3))
        friction = 2 * (K[2][0] * y[0] + K[2][2] * y[2]) * (fc - x[1])
        assert u_dot == -_form(forms[f"band form (s = {sign}1) copositive"], (y[0], v)) - friction
    # the exits of R̂: at v = 0 (V's friction is sat(φ), so V = p11σ² + p22·dz(φ)²) and at φ = f_c·sign(v)
    sigma, phi = _random(rng), _random(rng)
    dz = phi - max(-fc, min(fc, phi))
    at_rest = _form(K, (abs(sigma), abs(dz), 0)) - _form(P, (sigma, dz, 0))
    assert _form(forms["U − V copositive at v = 0"], (abs(sigma), abs(dz))) == at_rest
    for v in (_random(rng), -_random(rng)):
        x = (sigma, fc * (1 if v > 0 else -1), v)
        gap, bound = U((abs(sigma), 0, abs(v))) - V(x), _form(forms["U − V copositive at φ = ±f_c"], (abs(sigma), abs(v)))
        if k["p22"] >= 0:
            assert gap >= bound
        assert gap == bound or sigma * v > 0  # equal at the worse sign of σv


@pytest.mark.parametrize("seed", range(50))
def test_the_paper_blocks_decide_as_the_whole_matrices(seed):
    from symbolic_friction.independent._core import psd

    rng = random.Random(seed)
    g = {"k_p": _random(rng, 0, 4), "k_i": _random(rng, 0, 4) + 1, "k_v": _random(rng, 0, 8), "f_c": Fraction(1)}
    k = {n: _random(rng, 0, 4) for n in paper.CONSTANTS}
    got = dict(paper.premises(g, k, Fraction(1), Fraction(10)))
    a, kp, c1, c2, h2 = g["k_v"] / g["k_i"], g["k_p"], k["c1"], k["c2"], k["c2_hat"]
    P = [[a, 0, -1], [0, 1, 0], [-1, 0, kp]]
    K = [[k["k1"], 0, k["k3"]], [0, k["k2"], 0], [k["k3"], 0, k["k4"]]]
    assert got["P − c1·I ⪰ 0"] == psd([[P[i][j] - c1 * (i == j) for j in range(3)] for i in range(3)])
    assert got["c2·I − P ⪰ 0"] == psd([[c2 * (i == j) - P[i][j] for j in range(3)] for i in range(3)])
    assert got["c2_hat·I − K/2 ⪰ 0"] == psd([[h2 * (i == j) - K[i][j] / 2 for j in range(3)] for i in range(3)])


# -- the box: four corners, the cover, malformed intervals -------------------------------------------------


@pytest.mark.parametrize("corner, edit", [(3, _constant(0, "c1", "23/25")), (0, _constant(0, "c2", "71/20"))],
                         ids=["c1 fails at the least corner only", "c2 fails at the largest corner only"])
def test_every_decisive_corner_is_evaluated(monkeypatch, corner, edit):
    data = box_edit(BOX_A, edit)
    assert box.check(data).failing == ["piece 1: every premise at its 4 corners"]
    whole = box.corners
    monkeypatch.setattr(box, "corners", lambda piece, f_c: [whole(piece, f_c)[corner]])
    assert box.check(data).proved  # the other corner alone would accept it


def test_a_box_flat_in_one_gain_is_covered_in_the_others():
    data = box_edit(BOX_A, flat_in_k_p)
    assert box.check(data).proved and main_verdict(data) is True


def test_a_cover_must_reach_every_part_of_the_box():
    data = read(BOX_A)
    data["box"]["k_p"][1] = "17/5"
    assert box.check(data).failing == ["the pieces' volumes sum to the box's"]


@pytest.mark.parametrize("edit", [
    lambda d: d["box"]["k_p"].reverse(),
    lambda d: d["pieces"][0].pop("k_v"),
    lambda d: d["pieces"][0]["constants"].pop("c2"),
    lambda d: d.update(pieces={}),
    lambda d: d["box"].update(k_i=["1"]),
    lambda d: d.update(overshoot_bound=3.9),
], ids=["lo > hi", "no k_v", "no c2", "pieces not a list", "not an interval", "a float"])
def test_a_malformed_box_is_refused(edit):
    with pytest.raises(Malformed):
        box.check(box_edit(BOX_A, edit))


# -- the quadratic template: undecided copositivity is not proved -------------------------------------------


def test_an_undecided_copositivity_is_not_proved(monkeypatch):
    data = read(FALSE / "true_quadratic.json")
    monkeypatch.setattr(quadratic, "copositive", lambda m: None)
    verdict = quadratic.check(data)
    assert not verdict.proved and all("copositive" in n for n in verdict.failing) and len(verdict.failing) == 8


# -- what the modules import ------------------------------------------------------------------------------


@pytest.mark.parametrize("name", MODULES)
def test_the_modules_import_the_standard_library_flint_and_the_checker_only(name):
    tree = ast.parse((PACKAGE / f"{name}.py").read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots = [a.name.split(".")[0] for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                assert node.level == 1 and node.module in ("_core", "paper"), ast.unparse(node)
                continue
            roots = [node.module.split(".")[0]]
        else:
            continue
        assert all(r in sys.stdlib_module_names or r == "flint" for r in roots), ast.unparse(node)


# -- agreement with the main verifier on edited copies ------------------------------------------------------


def main_verdict(data: dict):
    """The main verifier's verdict: True, or the names of the checks that fail (``"malformed"`` if unread)."""
    from symbolic_friction._certify import box as main_box
    from symbolic_friction._certify import quadratic as main_quadratic
    from symbolic_friction._certify.certificate import from_data
    from symbolic_friction._certify.verify import verify_certificate
    from symbolic_friction._infra.errors import SymbolicFrictionError

    try:
        module = kind(data)
        if module is box:
            report = main_box.verify_box(main_box.box_from_data(data))
        elif module is quadratic:
            report = main_quadratic.verify_quadratic(main_quadratic.QuadraticCertificate.from_dict(data))
        else:
            report = verify_certificate(from_data(data))
    except SymbolicFrictionError:
        return "malformed"
    return True if report.proved else [c.name for c in report.failures]


def _numbers(obj, path=()):
    if isinstance(obj, dict):
        for key, value in obj.items():
            if key not in ("provenance", "schema", "template"):
                yield from _numbers(value, (*path, key))
    elif isinstance(obj, list):
        for i, value in enumerate(obj):
            yield from _numbers(value, (*path, i))
    elif isinstance(obj, str):
        yield path


FORMAT_RULES = (C_EQUATION, "label ")
"""The main verifier's checks that are rules of the format, not premises: the equation for ``c``, labels."""


@pytest.mark.parametrize("path", PROOFS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_edited_copies_are_decided_as_the_main_verifier_decides_them(path):
    rng = random.Random(path.name)
    original = read(path)
    places = list(_numbers(original))
    for _ in range(25):
        data = copy.deepcopy(original)
        where = rng.choice(places)
        holder = data
        for key in where[:-1]:
            holder = holder[key]
        x = Fraction(holder[where[-1]])
        y = rng.choice([x * (1 + Fraction(rng.choice([-1, 1]), 10 ** rng.randrange(1, 10))), -x, Fraction(0), 2 * x, x / 2])
        holder[where[-1]] = f"{float(y):.5f}" if where == ("overshoot_bound",) else str(y)
        verdict = verdict_of(kind(data), data)
        mine, main = verdict is not None and verdict.proved, main_verdict(data)
        if mine and main is not True:  # only a format rule of the main verifier may refuse what this one proves
            assert all(name.startswith(FORMAT_RULES) for name in main), (where, str(y), main)
        if main is True:
            assert mine, (where, str(y), verdict and verdict.failing)
