"""The independent checker's hunting and reset-contraction modules (``hunting-cycle/v1``, ``reset-contraction/v1``; issue 33).

* every committed certificate of these kinds (``proofs/hunting``, ``proofs/reset``) and every true control of the
  self-check is proved, quickly;
* every false file of these kinds in the self-check is refused, naming exactly the premises the manifest names;
* every premise decides: with the other premises a false certificate breaks held true, the premise it is meant to
  break alone refuses it, and made always-true as well it lets the false certificate through; the self-check
  breaks every premise but ``stick``, which a crafted file breaks (``stick`` and ``first_zero.start`` hold at every
  true zero where Assumption 1 holds, so no false file breaks them alone);
* undecided is not proved (the positivity search, the exact fallback of ``rho^cycles``); malformed files are refused;
* the modules import the standard library, python-flint and the checker's own modules only;
* on edited copies of the committed files the two verifiers agree, but for the main verifier's format rules.
"""

from __future__ import annotations

import ast
import copy
import json
import random
import sys
import time
from fractions import Fraction
from pathlib import Path

import flint
import pytest

from symbolic_friction import independent
from symbolic_friction.independent import hunting, reset_contraction
from symbolic_friction.independent._core import Malformed, Verdict, ball

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "symbolic_friction" / "independent"
FALSE = ROOT / "symbolic_friction" / "_certify" / "false_certificates"
MANIFEST = json.loads((FALSE / "manifest.json").read_text(encoding="utf-8"))["false_certificates"]
MODULES = {"hunting": hunting, "reset_contraction": reset_contraction}
SELF_CHECK = {"hunting": hunting, "reset-contraction": reset_contraction}  # the manifest's templates of these kinds


def read(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def kind(data: dict):
    """The module of this checker that decides ``data`` (None for the other kinds)."""
    template = data.get("template") or independent._SCHEMAS.get(data.get("schema"))
    return MODULES.get(independent.KINDS.get(template))


PROOFS = sorted(p for p in (ROOT / "proofs").rglob("*.json") if isinstance(read(p), dict) and kind(read(p)))
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
    data = read(path)
    start = time.perf_counter()
    verdict = independent.check_data(data)
    assert verdict.proved, verdict.failing
    assert time.perf_counter() - start < 0.5  # about 5–10 ms in fact


@pytest.mark.parametrize("entry", TRUE_FILES, ids=lambda e: e["file"])
def test_the_true_controls_are_proved(entry):
    verdict = SELF_CHECK[entry["template"]].check(read(FALSE / entry["file"]))
    assert verdict.proved, verdict.failing


@pytest.mark.parametrize("entry", FALSE_FILES, ids=lambda e: e["file"])
def test_every_false_file_is_refused_naming_its_premises(entry):
    verdict = verdict_of(SELF_CHECK[entry["template"]], read(FALSE / entry["file"]))
    assert verdict is not None and not verdict.proved
    assert set(verdict.failing) == set(entry["fails"])


def test_a_shared_block_decides_every_file_as_a_fresh_check():
    """``shared()`` (``check``'s) hands the searches of a file whose gains and interval were seen before their
    verdict (the false files are edits of a few true ones): every verdict is the fresh check's, why included."""
    files = [read(p) for p in PROOFS] + [read(FALSE / e["file"]) for e in TRUE_FILES + FALSE_FILES]
    fresh = [verdict_of(kind(d), d) for d in files]
    with independent.shared():
        kept = [verdict_of(kind(d), d) for d in files + files]
    assert [v and v.premises for v in kept] == [v and v.premises for v in fresh + fresh]


# -- every premise decides ---------------------------------------------------------------------------------------

NON_HURWITZ = {
    "schema": "symbolic-friction/hunting-certificate/v1", "claim": "symmetric hunting cycle",
    "parameters": {"k_p": "1", "k_i": "3/10", "k_v": "1/10", "f_c": "1/10", "f_s": "11/10"},
    "box": {"sigma": ["18151241558045473/50000000000000000", "18151241594345473/50000000000000000"],
            "tau": ["15789863447709349/5000000000000000", "15789863763709349/5000000000000000"],
            "monotone_from": "315697/100000"},
    "precision_bits": 128, "verdict": "proved",
}
"""A true zero of ``F`` that is the first zero of ``v``, for gains with ``k_v·k_p < k_i``: ``V`` grows along the
slip, which ends at ``φ₁ ≈ −1.285 < −f_s`` (the mass does not stick: no stick–slip cycle).  It breaks ``box``
(Assumption 1) and ``stick``, which is implied by the others where Assumption 1 holds."""

CRAFTED = {"hunting: stick, with k_v·k_p < k_i": (hunting, "stick", NON_HURWITZ)}


def cases():
    for entry in FALSE_FILES:
        yield entry["file"], SELF_CHECK[entry["template"]], entry["premise"], read(FALSE / entry["file"])
    for name, (module, premise, data) in CRAFTED.items():
        yield name, module, premise, data


CASES = list(cases())


def broken(module, data: dict) -> set[str]:
    """The premises ``data`` breaks: those failing, then those failing once these are held true, and so on (a
    premise that is decided only when an earlier one holds, as the positivity search after the Krawczyk test)."""
    failing: set[str] = set()
    while True:
        more = set(verdict_of_masked(module, data, failing).failing) - failing
        if not more:
            return failing
        failing |= more


def verdict_of_masked(module, data: dict, held: set[str]) -> Verdict:
    saved = module.Verdict
    module.Verdict = masking(held)
    try:
        return module.check(data)
    finally:
        module.Verdict = saved


@pytest.mark.parametrize("name, module, premise, data", CASES, ids=[c[0] for c in CASES])
def test_the_broken_premise_alone_refuses_and_made_true_accepts(name, module, premise, data):
    failing = broken(module, data)
    assert premise in failing
    assert verdict_of_masked(module, data, failing - {premise}).failing == [premise], f"{premise} alone refuses {name}"
    assert verdict_of_masked(module, data, failing).proved, "with every premise it breaks held true it passes"


def test_the_crafted_file_is_a_true_zero_where_only_the_gains_and_the_stick_fail():
    assert set(hunting.check(copy.deepcopy(NON_HURWITZ)).failing) == {"box"}  # the rest is not evaluated then
    assert main_verdict(NON_HURWITZ) == "malformed"  # the main reader refuses gains outside Assumption 1


@pytest.mark.parametrize("module", MODULES.values(), ids=MODULES)
def test_every_premise_is_broken_by_some_false_certificate(module):
    assert {premise for _, m, premise, _ in CASES if m is module} == set(module.PREMISES)
    for path in PROOFS + [FALSE / e["file"] for e in TRUE_FILES]:  # PREMISES are all the names a file meets
        if kind(read(path)) is module:
            assert {n for n, _, _ in module.check(read(path)).premises} <= set(module.PREMISES)


def test_the_positivity_search_is_load_bearing(monkeypatch):
    for module in MODULES.values():
        monkeypatch.setattr(module, "positive", lambda g, lo, hi: True)
    for name in ("hunting_later_zero.json", "reset-contraction_later_zero.json"):
        data = read(FALSE / name)
        assert kind(data).check(data).proved, f"{name}: a later zero of v passes without the search"


# -- undecided is not proved ------------------------------------------------------------------------------------


def _value(centre: Fraction, minus: Fraction):
    def g(a: Fraction, b: Fraction):
        t = hunting.interval(a, b) - ball(centre)
        return t * t - ball(minus)
    return g


@pytest.mark.parametrize("g, shown", [
    (_value(Fraction(1, 3), Fraction(0)), False),  # touches 0: every ball near 1/3 holds 0 (gives up)
    (_value(Fraction(127, 128), Fraction(1, 10**6)), False),  # negative near the right end only
    (_value(Fraction(1, 128), Fraction(1, 10**6)), False),  # negative near the left end only
    (lambda a, b: flint.arb(0, 1), False),  # never decided: the budget ends it
    (lambda a, b: hunting.interval(a, b) + 1, True),
], ids=["touching 0", "negative at the right", "negative at the left", "undecided", "positive"])
def test_the_positivity_search(g, shown):
    assert hunting.positive(g, Fraction(0), Fraction(1)) is shown


def test_an_interval_ball_holds_both_ends():
    for lo, hi in [(Fraction(1, 3), Fraction(2, 3)), (Fraction(-5, 3), Fraction(-4, 3)),
                   (Fraction(1, 7 * 10**30), Fraction(1, 7 * 10**30) + Fraction(1, 3 * 10**60))]:
        b = hunting.interval(lo, hi)
        assert all(b.contains(flint.fmpq(x.numerator, x.denominator)) for x in (lo, hi))


def test_the_start_is_not_shown_where_the_derivative_is_not_positive():
    assert hunting.start(lambda a, b: 1 - hunting.interval(a, b), Fraction(1)) is not None
    assert hunting.start(lambda a, b: hunting.interval(a, b), Fraction(1)) is None  # 0 at τ = 0


def _reset(**edit) -> dict:
    data = read(FALSE / "true_reset_contraction.json")
    data["settling"].update(edit)
    return data


def test_rho_to_the_cycles_is_decided_exactly_where_the_ball_does_not_decide():
    rho = Fraction(read(FALSE / "true_reset_contraction.json")["rho"])
    assert reset_contraction.check(_reset(tol=str(rho ** 9))).proved  # equality: no ball decides it
    assert reset_contraction.check(_reset(tol=str(rho ** 9 - Fraction(1, 10**80)))).failing == ["rho^cycles ≤ tol"]


def test_an_undecided_power_is_not_proved():
    data = read(FALSE / "true_reset_contraction.json")
    rho = Fraction(458633 * 10**44 + 1, 10**50)  # 101 characters: rho^2000 is too long to raise exactly here
    power = rho ** 2000
    bits = 200 - power.numerator.bit_length() + power.denominator.bit_length()
    tol = Fraction(-((-power.numerator << bits) // power.denominator), 1 << bits)  # power rounded up to 200 bits
    assert power <= tol < power * (1 + Fraction(1, 10**50))  # within any 128-bit ball of power
    data.update(rho=str(rho))
    data["settling"].update(cycles=2000, tol=str(tol), time=str(2000 * Fraction(data["cycle_time"])))
    verdict = reset_contraction.check(data)
    assert verdict.failing == ["rho^cycles ≤ tol"]
    assert {n: h for n, h, _ in verdict.premises}["rho^cycles ≤ tol"] is None


def test_an_undecided_stability_claims_nothing():
    data = read(FALSE / "true_hunting.json")
    data["cycle"]["stable"] = None
    assert hunting.check(data).proved


def test_the_precision_is_the_files_and_too_few_bits_decide_nothing():
    data = read(FALSE / "true_hunting.json")
    data["precision_bits"] = 53  # the multiplier's ball is then wider than its 12 written digits: not proved
    before = flint.ctx.prec
    assert hunting.check(data).failing == ["cycle.multiplier"]
    assert flint.ctx.prec == before  # the module restores the context's precision
    assert main_verdict(data) == ["cycle.multiplier"]


@pytest.mark.parametrize("module, edit", [
    (hunting, lambda d: d.pop("box")),
    (hunting, lambda d: d["box"].update(sigma=["1/10"])),
    (hunting, lambda d: d.update(claim="an asymmetric cycle")),
    (hunting, lambda d: d.update(precision_bits=True)),
    (hunting, lambda d: d.update(precision_bits=8192)),
    (hunting, lambda d: d["cycle"].update(stable=1)),
    (hunting, lambda d: d["cycle"].pop("period")),
    (hunting, lambda d: d["parameters"].update(f_s=1.2)),
    (reset_contraction, lambda d: d.update(overshoot="yes")),
    (reset_contraction, lambda d: d["settling"].update(cycles=True)),
    (reset_contraction, lambda d: d["settling"].update(cycles=10_001)),
    (reset_contraction, lambda d: d["slip"].update(tau=["4"])),
    (reset_contraction, lambda d: d.pop("rho")),
], ids=["no box", "not an interval", "another claim", "bits a bool", "too many bits", "stable not a bool",
        "no period", "a float", "overshoot not a bool", "cycles a bool", "too many cycles", "tau not a pair", "no rho"])
def test_a_malformed_file_is_refused(module, edit):
    data = read(FALSE / ("true_hunting.json" if module is hunting else "true_reset_contraction.json"))
    edit(data)
    with pytest.raises(Malformed):
        module.check(data)


# -- what the modules import ----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", MODULES)
def test_the_modules_import_the_standard_library_flint_and_the_checker_only(name):
    tree = ast.parse((PACKAGE / f"{name}.py").read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            roots = [a.name.split(".")[0] for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                assert node.level == 1 and node.module in ("_core", "hunting"), ast.unparse(node)
                continue
            roots = [node.module.split(".")[0]]
        else:
            continue
        assert all(r in sys.stdlib_module_names or r == "flint" for r in roots), ast.unparse(node)


# -- agreement with the main verifier on edited copies ----------------------------------------------------------


def main_verdict(data: dict):
    """The main verifier's verdict: True, or the names of the checks that fail (``"malformed"`` if unread)."""
    from symbolic_friction._certify.hunting import hunting_from_data, verify_hunting
    from symbolic_friction._certify.reset_contraction import ContractionCertificate, verify_contraction
    from symbolic_friction._infra.errors import SymbolicFrictionError

    try:
        if kind(data) is hunting:
            report = verify_hunting(hunting_from_data(data))
            return True if report.proved else [c.name for c in report.checks if not c.holds] or ["verdict"]
        report = verify_contraction(ContractionCertificate.from_dict(data))
    except SymbolicFrictionError:
        return "malformed"
    return True if report.proved else [c.name for c in report.failures]


def _numbers(obj, path=()):
    if isinstance(obj, dict):
        for key, value in obj.items():
            if key not in ("provenance", "schema", "template", "claim", "verdict"):
                yield from _numbers(value, (*path, key))
    elif isinstance(obj, list):
        for i, value in enumerate(obj):
            yield from _numbers(value, (*path, i))
    elif isinstance(obj, str):
        yield path


EDITED = PROOFS + [FALSE / e["file"] for e in TRUE_FILES if e["file"] != "true_hunting.json"]  # (a committed copy)


@pytest.mark.parametrize("path", EDITED, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_edited_copies_are_decided_as_the_main_verifier_decides_them(path):
    rng = random.Random(path.name)
    original = read(path)
    places = list(_numbers(original))
    for _ in range(12):
        data = copy.deepcopy(original)
        where = rng.choice(places)
        holder = data
        for key in where[:-1]:
            holder = holder[key]
        x = Fraction(holder[where[-1]])
        y = rng.choice([x * (1 + Fraction(rng.choice([-1, 1]), 10 ** rng.randrange(1, 13))), -x, Fraction(0), 2 * x, x / 2])
        holder[where[-1]] = str(y)
        verdict = verdict_of(kind(data), data)
        mine, main = verdict is not None and verdict.proved, main_verdict(data)
        if mine:  # only a format rule of the main verifier (its reader: Assumption 1, key sets) may refuse it
            assert main is True or main == "malformed", (where, str(y), main)
        if main is True:
            assert mine, (where, str(y), verdict and verdict.failing)
