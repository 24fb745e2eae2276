"""The Python API under hostile input: every bad argument ends in the package's own error, early and clearly.

The command line's hostile inputs (``test_hostile_inputs.py``, ``test_hostile_options.py``) have their
counterpart here for a user in a notebook: every public name of ``symbolic_friction.__all__`` (and the
ones the issue named: ``Reference``, ``load_scene``, ``Scene``) called with wrong types (str, None, bool,
list, dict, complex, bytes), NaN and ±inf, huge integers (``10**400``, ``10**5000``), huge Decimals and
Fractions (``Decimal("1e999999999")`` would take forever to expand), zero and negative values where a
positive one is required, huge counts (``10**12`` grid points would reach numpy's allocator), wrong
shapes, odd paths (a directory, ``/dev/zero``, a FIFO, a NUL byte, a 2 GB sparse file) and keyword typos.

Each call runs in a process of its own, forked from one warm server that imported the package (so a
hang is killed, not waited for; a runaway allocation meets ``RLIMIT_AS`` instead of the machine), and
must, within :data:`BOUND` seconds:

* raise a :class:`~symbolic_friction.SymbolicFrictionError` (never ``MemoryError``, ``OverflowError``,
  ``AttributeError`` or a ``TypeError``/``ValueError`` from inside the package or its dependencies)
  whose message names the argument and stays short; or, for a keyword typo or a missing argument
  (``kind="signature"``), the ``TypeError`` Python raises *at the call* (no frame of the package on
  the traceback), which names the keyword.

A call that cannot be fixed at once is listed in :data:`KNOWN` with the reason and marked
``xfail(strict=True)``, so that fixing it turns its case into a failure until it leaves the list (none is now).
"""

from __future__ import annotations

import json
import os
import resource
import select
import signal
import subprocess
import sys
import time
import traceback
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
BOUND = 10.0
"""Seconds a hostile call may take before its error (the child is killed then)."""
MEMORY = 3 * 1024**3
"""Address space of each call (numba/llvmlite reserve much of it; a runaway allocation far more)."""

OK_GAINS = "k_p=3, k_i=4, k_v='6.4'"

# (id, expression, a word the message must contain[, kind]).  Names: see _namespace().
CASES: list[tuple] = []


def case(name: str, expr: str, word: str, kind: str = "error") -> None:
    CASES.append((name, expr, word, kind))


# ---- numbers read exactly (Parameters, to_rational, format_rational) --------------------------------------
_BAD_NUMBERS = [
    ("str", "'abc'"), ("none", "None"), ("bool", "True"), ("list", "[3]"), ("dict", "{'a': 1}"), ("complex", "1j"),
    ("bytes", "b'3'"), ("nan", "nan"), ("inf", "inf"), ("minus-inf", "-inf"), ("int-5000-digits", "10**5000"),
    ("decimal-huge-exponent", "D('1e999999999')"), ("decimal-tiny-exponent", "D('-1e-999999999')"),
    ("decimal-nan", "D('NaN')"), ("decimal-snan", "D('sNaN')"), ("decimal-2000-digits", "D('7' * 2000)"),
    ("str-huge-exponent", "'1e999999999'"), ("str-zero-denominator", "'1/0'"), ("str-arabic", "'٣'"),
    ("str-million-chars", "'1' * 10**6"), ("numpy-nan", "np.float64('nan')"), ("array", "np.ones(3)"),
]
for gain in ("k_p", "k_i", "k_v", "f_c"):
    others = {"k_p": "k_p=3", "k_i": "k_i=4", "k_v": "k_v='6.4'", "f_c": "f_c=1"}
    rest = ", ".join(v for k, v in others.items() if k != gain)
    for label, value in _BAD_NUMBERS if gain == "k_p" else _BAD_NUMBERS[::3]:
        case(f"Parameters-{gain}-{label}", f"Parameters({gain}={value}, {rest})", gain)
for gain, value, label in [("k_p", "0", "zero"), ("k_i", "-1", "negative"), ("k_v", "'1/1000'", "routh"),
                           ("f_c", "0", "zero"), ("f_c", "-10**400", "huge-negative")]:
    others = {"k_p": "k_p=3", "k_i": "k_i=4", "k_v": "k_v='6.4'", "f_c": "f_c=1"}
    case(f"Parameters-{gain}-{label}", f"Parameters({gain}={value}, " + ", ".join(v for k, v in others.items() if k != gain) + ")", gain)
for label, value, word in [("below-f_c", "'0.5'", "f_s"), ("str", "'x'", "f_s"), ("decimal-huge", "D('1e999999999')", "f_s"),
                           ("nan", "nan", "f_s")]:
    case(f"Parameters-f_s-{label}", f"Parameters({OK_GAINS}, f_s={value})", word)
for label, value in [("zero", "0"), ("negative", "-1"), ("nan", "nan"), ("str", "'x'"), ("decimal-huge", "D('1e-999999999')"),
                     ("list", "[1]")]:
    case(f"Parameters-reset_dwell-{label}", f"Parameters({OK_GAINS}, reset_dwell={value})", "reset_dwell")
case("Parameters-physical-str", f"Parameters({OK_GAINS}, physical='x')", "physical")
case("Parameters-keyword-typo", "Parameters(kp=3, k_i=4, k_v=7)", "kp", "signature")
case("Parameters-missing-gain", "Parameters(k_p=3, k_i=4)", "k_v", "signature")
for label, kwargs, word in [
    ("m-zero", "m=0", "m"), ("m-str", "m='x'", "m"), ("m-decimal-huge", "m=D('1e999999999')", "m"), ("m-none", "m=None", "m"),
    ("alpha_v-negative", "m=2, alpha_v=-1", "alpha_v"), ("f_c_bar-zero", "m=2, f_c_bar=0", "f_c_bar"),
    ("f_s_bar-below", "m=2, f_s_bar='0.5'", "f_s_bar"), ("k_d_bar-nan", "m=2, k_d_bar=nan", "k_d_bar"),
    ("k_p_bar-5000-digits", "m=2, k_p_bar=10**5000", "k_p_bar"), ("k_i_bar-tiny-decimal", "m=2, k_i_bar=D('1e-999999999')", "k_i_bar"),
]:
    base = {"m": "m=2", "k_p_bar": "k_p_bar=6", "k_i_bar": "k_i_bar=8", "k_d_bar": "k_d_bar='12.3'", "f_c_bar": "f_c_bar=2"}
    given = dict(part.split("=", 1) for part in kwargs.split(", "))
    args = ", ".join([f"{k}={v}" for k, v in given.items()] + [v for k, v in base.items() if k not in given])
    case(f"from_physical-{label}", f"Parameters.from_physical({args})", word)
case("from_physical-typo", "Parameters.from_physical(mass=2, k_p_bar=6, k_i_bar=8, k_d_bar=12, f_c_bar=2)", "mass", "signature")
for label, value in [("unknown", "'c'"), ("none", "None"), ("list", "[]"), ("int", "1"), ("bytes", "b'a'")]:
    case(f"table_i-{label}", f"Parameters.table_i({value})", "Table I")
for label, value in [("decimal-huge", "D('1e999999999')"), ("decimal-tiny", "D('1e-999999999')"), ("decimal-long", "D('9' * 5000)"),
                     ("str-huge-exponent", "'1e999999999'"), ("str-long", "'1' * 10**6"), ("bytes", "b'1'"), ("complex", "1j"),
                     ("list", "[1]"), ("none", "None"), ("bool", "False"), ("int-5000-digits", "10**5000"), ("nan", "nan"),
                     ("array", "np.array([1.0])"), ("sympy-oo", "sympy.oo"), ("sympy-symbol", "sympy.Symbol('x')"),
                     ("zero-denominator", "'3/0'")]:
    case(f"to_rational-{label}", f"to_rational({value}, name='gain')", "gain")
for label, value in [("str", "'x'"), ("none", "None"), ("nan", "nan"), ("inf", "inf"), ("decimal-huge", "D('1e999999999')"),
                     ("list", "[1]"), ("complex", "1j"), ("zero-denominator", "'1/0'")]:
    case(f"format_rational-{label}", f"format_rational({value})", "q")

# ---- the proof ------------------------------------------------------------------------------------------
case("run_obligations-argument", "run_obligations(1)", "run_obligations", "signature")
case("all_obligations-keyword", "all_obligations(only='x')", "only", "signature")
case("all_errata-argument", "all_errata(None)", "all_errata", "signature")

# ---- certificates --------------------------------------------------------------------------------------
for label, value in [("str", "'text'"), ("none", "None"), ("int", "3"), ("dict", "{'k_p': 3}"), ("certificate", "C")]:
    case(f"certify-params-{label}", f"certify({value})", "params")
case("certify-stiction", "certify(PS)", "f_s")
case("certify-gains-5000-digits", "certify(Parameters(k_p=F(10**5000), k_i=4, k_v=7))", "k_p")
case("certify-gains-900-digits", "certify(Parameters(k_p=F(1, 7**1060), k_i=F(1, 5**1280), k_v=7**1060))", "digits")
case("certify-reset", "certify(PR)", "reset")
for label, value in [("str", "'x'"), ("none", "None"), ("list", "[]"), ("int", "3")]:
    case(f"certify-mode-{label}", f"certify(P, mode={value})", "mode")
for label, value in [("str", "'x'"), ("nan", "nan"), ("negative", "-1"), ("zero", "0"), ("huge", "10**400"),
                     ("decimal-huge", "D('1e999999999')"), ("decimal-tiny", "D('1e-999999999')"), ("complex", "1j")]:
    case(f"certify-margin-{label}", f"certify(P, margin={value})", "margin")
case("certify-label-int", "certify(P, label=5)", "label")
case("certify-label-none", "certify(P, label=None)", "label")
case("certify-physical-str", "certify(P, physical='x')", "physical")
case("certify-physical-partial", "certify(P, physical={'m': 'x'})", "physical")
case("certify-search-str", "certify(P, search='x')", "search")
case("certify-search-none", "certify(P, search=None)", "search")
case("certify-search-sdp-bad-margin", "certify(P, search='sdp', margin='x')", "margin")
case("certify-keyword-typo", "certify(P, modes='tightest')", "modes", "signature")
for label, value in [("str", "'x'"), ("none", "None"), ("parameters", "P")]:
    case(f"verify_certificate-{label}", f"verify_certificate({value})", "certificate")
for label, value, word in [
    ("int", "3", "path"), ("none", "None", "path"), ("bytes", "b'/tmp/x.json'", "path"), ("directory", "TMP", "directory"),
    ("fifo", "FIFO", "FIFO"), ("dev-zero", "'/dev/zero'", "/dev/zero"), ("missing", "TMP + '/nope.json'", "no such file"),
    ("nul-byte", "'a\\x00b.json'", "NUL"), ("huge-file", "HUGE", "bytes"), ("not-json", "NOT_JSON", "JSON"),
    ("deep-json", "DEEP_JSON", "nest"), ("trailing-slash", "TMP + '/c.json/'", "directory"),
]:
    case(f"verify_file-{label}", f"verify_file({value})", word)
    case(f"load_certificate-{label}", f"load_certificate({value})", word)
for label, expr, word in [
    ("certificate-str", "write_certificate('x', TMP + '/a.json')", "certificate"),
    ("certificate-none", "write_certificate(None, TMP + '/a.json')", "certificate"),
    ("path-int", "write_certificate(C, 5)", "path"),
    ("path-none", "write_certificate(C, None)", "path"),
    ("path-directory", "write_certificate(C, TMP)", ".json"),
    ("path-through-device", "write_certificate(C, '/dev/zero/x.json')", "directory"),
    ("path-nul-byte", "write_certificate(C, TMP + '/a\\x00.json')", "NUL"),
    ("path-too-long", "write_certificate(C, TMP + '/' + 'n' * 300 + '.json')", "too long"),
]:
    case(f"write_certificate-{label}", expr, word)
for label, value in [("str", "'x'"), ("decimal-huge", "D('1e999999999')"), ("none", "None"), ("float", "1.5")]:
    case(f"Certificate-{label}", f"Certificate(*([{value}] * 13), overshoot_bound='1')", "k_p")

case("VerificationReport-strings", "VerificationReport('x', 'y')", "certificate")
case("VerificationReport-checks-str", "VerificationReport(C, 'y')", "checks")
case("VerificationReport-checks-of-strings", "VerificationReport(C, ('y',))", "checks[0]")
case("VerificationReport-source-int", "VerificationReport(C, (), 5)", "source")

# ---- simulation ----------------------------------------------------------------------------------------
for label, value in [("str", "'x'"), ("none", "None"), ("dict", "{'k_p': 3}")]:
    case(f"simulate-params-{label}", f"simulate({value}, (0, 1, 0), 10)", "params")
for label, value in [("str", "'abc'"), ("none", "None"), ("two", "(1, 2)"), ("nested", "[[1, 2, 3]]"), ("nan", "(nan, 0, 0)"),
                     ("inf", "(0, inf, 0)"), ("int-400-digits", "(10**400, 0, 0)"), ("fraction-huge", "(F(10**400, 3), 0, 0)"),
                     ("complex", "(1j, 0, 0)"), ("dict", "{'a': 1}"), ("decimal-huge", "(D('1e999999999'), 0, 0)"),
                     ("ragged", "[[1], [1, 2], 3]"), ("bytes", "b'abc'")]:
    case(f"simulate-z0-{label}", f"simulate(P, {value}, 10)", "z0")
for label, value in [("str", "'soon'"), ("none", "None"), ("bool", "True"), ("nan", "nan"), ("inf", "inf"), ("negative", "-1"),
                     ("zero", "0"), ("int-400-digits", "10**400"), ("1e308", "1e308"), ("decimal-huge", "D('1e999999999')"),
                     ("fraction-tiny", "F(1, 10**400)"), ("complex", "1j"), ("list", "[1]")]:
    case(f"simulate-t_end-{label}", f"simulate(P, (0, 1, 0), {value})", "t_end")
for label, value in [("str", "'abc'"), ("2d", "[[1.0]]"), ("nan", "[nan]"), ("int-400-digits", "[10**400]"), ("complex", "[1j]"),
                     ("decreasing", "[2, 1]"), ("negative", "[-1, 1]"), ("beyond-t_end", "[0, 100]"), ("empty", "[]")]:
    case(f"simulate-t_eval-{label}", f"simulate(P, (0, 1, 0), 10, t_eval={value})", "t_eval")
for label, expr, word in [
    ("method-unknown", "method='x'", "method"), ("method-none", "method=None", "method"), ("method-int", "method=5", "method"),
    ("method-class", "method=Moreau", "method"), ("option-typo", "hh=1", "hh"), ("grid_points-huge", "grid_points=10**12", "grid_points"),
    ("grid_points-one", "grid_points=1", "grid_points"), ("max_events-zero", "max_events=0", "max_events"),
    ("max_events-400-digits", "max_events=10**400", "max_events"), ("max_events-str", "max_events='x'", "max_events"),
    ("max_events-float", "max_events=2.5", "max_events"), ("max_events-ten-million", "max_events=10**7", "max_events"), ("moreau-h-zero", "method='moreau', h=0", "h"),
    ("moreau-h-tiny", "method='moreau', h=1e-12", "max_steps"),
    ("moreau-steps-memory", "method='moreau', h=1e-8, max_steps=10**9", "h ="),
    ("moreau-max_steps-huge", "method='moreau', max_steps=10**12", "max_steps"),
    ("regularized-epsilon-tiny", "method='regularized', epsilon=1e-300", "epsilon"),
    ("ivp-rtol-huge", "method='ivp-events', rtol=10**400", "rtol"),
]:
    case(f"simulate-{label}", f"simulate(P, (0, 1, 0), 10, {expr})", word)
case("simulate-stiction-moreau", "simulate(PS, (0, 1, 0), 10, method='moreau')", "f_s")
case("simulate-reset-regularized", "simulate(PR, (0, 1, 0), 10, method='regularized')", "reset")
case("simulate-gains-beyond-float", "simulate(Parameters(k_p=10**400, k_i=4, k_v=7), (0, 1, 0), 10)", "k_p")
case("simulate-gains-closed-form-overflow", "simulate(Parameters(k_p=1e100, k_i=1e100, k_v=1e100), (0, 1, 0), 1)", "k_p")
case("simulate-missing-t_end", "simulate(P, (0, 1, 0))", "t_end", "signature")
for label, expr, word, *kind in [
    ("params-str", "simulate_batch('x', [[0, 1, 0]], 10)", "params"),
    ("Z0-str", "simulate_batch(P, 'abc', 10)", "Z0"), ("Z0-none", "simulate_batch(P, None, 10)", "Z0"),
    ("Z0-empty", "simulate_batch(P, [], 10)", "Z0"), ("Z0-rows-of-two", "simulate_batch(P, [[1, 2]], 10)", "Z0"),
    ("Z0-no-rows", "simulate_batch(P, np.zeros((0, 3)), 10)", "Z0"), ("Z0-nan", "simulate_batch(P, [[nan, 0, 0]], 10)", "Z0"),
    ("Z0-int-400-digits", "simulate_batch(P, [[10**400, 0, 0]], 10)", "Z0"),
    ("Z0-billion-rows", "simulate_batch(P, np.broadcast_to(np.zeros(3), (10**9, 3)), 10, t_eval=[0, 1])", "Z0"),
    ("Z0-dict", "simulate_batch(P, {'a': 1}, 10)", "Z0"),
    ("t_end-1e308", "simulate_batch(P, [[0, 1, 0]], 1e308)", "t_end"),
    ("t_end-int-400-digits", "simulate_batch(P, [[0, 1, 0]], 10**400)", "t_end"),
    ("t_end-str", "simulate_batch(P, [[0, 1, 0]], 'x')", "t_end"),
    ("grid-44-GiB", "simulate_batch(P, np.zeros((1000, 3)), 10, grid_points=10**6)", "grid_points"),
    ("grid_points-huge", "simulate_batch(P, [[0, 1, 0]], 10, grid_points=10**12)", "grid_points"),
    ("max_events-huge", "simulate_batch(P, [[0, 1, 0]], 10, max_events=10**12)", "max_events"),
    ("max_events-bool", "simulate_batch(P, [[0, 1, 0]], 10, max_events=True)", "max_events"),
    ("t_eval-str", "simulate_batch(P, [[0, 1, 0]], 10, t_eval='abc')", "t_eval"),
    ("source-str", "simulate_batch(P, [[0, 1, 0], [0, 2, 0]], 10, source='ab')", "source"),
    ("source-wrong-length", "simulate_batch(P, [[0, 1, 0]], 10, source=['a', 'b'])", "source"),
    ("keyword-typo", "simulate_batch(P, [[0, 1, 0]], 10, grid=5)", "grid", "signature"),
]:
    case(f"simulate_batch-{label}", expr, word, *kind)
for label, expr, word, *kind in [
    ("EventDriven-max_events-str", "EventDriven(max_events='x')", "max_events"),
    ("EventDriven-max_events-400-digits", "EventDriven(max_events=10**400)", "max_events"),
    ("EventDriven-max_events-none", "EventDriven(max_events=None)", "max_events"),
    ("EventDriven-grid_points-huge", "EventDriven(grid_points=10**12)", "grid_points"),
    ("EventDriven-grid_points-float", "EventDriven(grid_points=2.5)", "grid_points"),
    ("Moreau-h-zero", "Moreau(h=0)", "h"), ("Moreau-h-negative", "Moreau(h=-1)", "h"), ("Moreau-h-str", "Moreau(h='x')", "h"),
    ("Moreau-h-nan", "Moreau(h=nan)", "h"), ("Moreau-h-400-digits", "Moreau(h=10**400)", "h"), ("Moreau-h-complex", "Moreau(h=1j)", "h"),
    ("Moreau-theta-small", "Moreau(theta=0.2)", "theta"), ("Moreau-theta-nan", "Moreau(theta=nan)", "theta"),
    ("Moreau-theta-400-digits", "Moreau(theta=10**400)", "theta"), ("Moreau-theta-str", "Moreau(theta='x')", "theta"),
    ("Moreau-max_steps-zero", "Moreau(max_steps=0)", "max_steps"), ("Moreau-max_steps-huge", "Moreau(max_steps=10**12)", "max_steps"),
    ("Moreau-max_steps-float", "Moreau(max_steps=2.5)", "max_steps"), ("Moreau-friction-str", "Moreau(friction='x')", "friction"),
    ("Moreau-positional", "Moreau(1e-3)", "positional", "signature"),
    ("Regularized-epsilon-zero", "Regularized(epsilon=0)", "epsilon"), ("Regularized-epsilon-str", "Regularized(epsilon='x')", "epsilon"),
    ("Regularized-epsilon-400-digits", "Regularized(epsilon=10**400)", "epsilon"),
    ("Regularized-law-unknown", "Regularized(law='cubic')", "law"), ("Regularized-law-none", "Regularized(law=None)", "law"),
    ("Regularized-rtol-tiny", "Regularized(rtol=1e-20)", "rtol"), ("Regularized-rtol-400-digits", "Regularized(rtol=10**400)", "rtol"),
    ("Regularized-integrator-explicit", "Regularized(integrator='RK45')", "integrator"),
    ("Regularized-typo", "Regularized(eps=1e-3)", "eps", "signature"),
    ("IvpEvents-rtol-str", "IvpEvents(rtol='x')", "rtol"), ("IvpEvents-rtol-tiny", "IvpEvents(rtol=1e-20)", "rtol"),
    ("IvpEvents-atol-negative", "IvpEvents(atol=-1)", "atol"), ("IvpEvents-atol-400-digits", "IvpEvents(atol=-10**400)", "atol"),
    ("IvpEvents-integrator-unknown", "IvpEvents(integrator='x')", "integrator"),
    ("IvpEvents-max_events-zero", "IvpEvents(max_events=0)", "max_events"),
    ("IvpEvents-max_events-huge", "IvpEvents(max_events=10**12)", "max_events"),
]:
    case(label, expr, word, *kind)
case("IvpEvents-typo", "IvpEvents(rtoll=1e-3)", "rtoll", "signature")
for label, expr, word in [
    ("trajectories-str", "Solution('x', 0)", "trajectories"), ("index-out-of-range", "Solution(BATCH, 5)", "index"),
    ("index-str", "Solution(BATCH, '0')", "index"), ("index-bool", "Solution(BATCH, True)", "index"),
]:
    case(f"Solution-{label}", expr, word)
case("Trajectories-params-str", "Trajectories(*(['x'] * 16))", "params")
case("Trajectories-arrays-str", "Trajectories(P, 'event', *(['x'] * 14))", "array")
case("Trajectories-arrays-lists", "Trajectories(P, 'event', *([[1.0]] * 14))", "array")

# ---- responses -----------------------------------------------------------------------------------------
for label, expr, word in [
    ("params-str", "step_response('x')", "params"), ("params-none", "step_response(None, 10)", "params"),
    ("T-str", "step_response(P, 'x')", "T"), ("T-negative", "step_response(P, -1)", "T"), ("T-nan", "step_response(P, nan)", "T"),
    ("T-int-400-digits", "step_response(P, 10**400)", "T"), ("T-1e308", "step_response(P, 1e308)", "T"),
    ("T-complex-array", "step_response(P, [1j])", "T"), ("T-empty", "step_response(P, [])", "T"),
    ("T-dict", "step_response(P, {1: 2})", "T"), ("T-decreasing", "step_response(P, [0, 2, 1])", "T"),
    ("T-samples-huge", "step_response(P, np.broadcast_to(np.ones(1), (10**9,)))", "sample times"),
    ("input-unknown", "step_response(P, 10, input='force')", "input"), ("input-none", "step_response(P, 10, input=None)", "input"),
    ("amplitude-str", "step_response(P, 10, amplitude='x')", "amplitude"),
    ("amplitude-int-400-digits", "step_response(P, 10, amplitude=10**400)", "amplitude"),
    ("amplitude-decimal-huge", "step_response(P, 10, amplitude=D('1e999999999'))", "amplitude"),
    ("amplitude-nan", "step_response(P, 10, amplitude=nan)", "amplitude"),
    ("amplitude-none", "step_response(P, 10, amplitude=None)", "amplitude"),
    ("disturbance-huge", "step_response(P, 10, input='disturbance', amplitude=10**400)", "amplitude"),
]:
    case(f"step_response-{label}", expr, word)
for label, expr, word in [
    ("params-str", "initial_response('x')", "params"), ("z0-str", "initial_response(P, 10, z0='x')", "z0"),
    ("z0-two", "initial_response(P, 10, z0=(1, 2))", "z0"), ("z0-int-400-digits", "initial_response(P, 10, z0=(10**400, 0, 0))", "z0"),
    ("z0-nan", "initial_response(P, 10, z0=(nan, 0, 0))", "z0"), ("T-int-400-digits", "initial_response(P, 10**400)", "T"),
]:
    case(f"initial_response-{label}", expr, word)
case("Response-strings", "Response(*(['x'] * 8))", "params")
case("Response-arrays-lists", "Response([0.0], [0.0], [[0.0]], [0.0], None, 0, P, None)", "solution")

# ---- studies -------------------------------------------------------------------------------------------
for label, expr, word, *kind in [
    ("params-str", "find_cycles('x')", "params"), ("no-stiction", "find_cycles(P)", "f_s"),
    ("points-huge", "find_cycles(PS, points=10**12)", "points"), ("points-one", "find_cycles(PS, points=1)", "points"),
    ("points-str", "find_cycles(PS, points='x')", "points"), ("points-float", "find_cycles(PS, points=2.5)", "points"),
    ("span-zero", "find_cycles(PS, span=0)", "span"), ("span-nan", "find_cycles(PS, span=nan)", "span"),
    ("span-negative", "find_cycles(PS, span=-5)", "span"), ("span-int-400-digits", "find_cycles(PS, span=10**400)", "span"),
    ("general-str", "find_cycles(PS, general='x')", "general"),
    ("gains-beyond-float", "find_cycles(Parameters(k_p=1e100, k_i=1e100, k_v=1e100, f_s=2))", "float64"),
    ("keyword-typo", "find_cycles(PS, point=10)", "point", "signature"),
]:
    case(f"find_cycles-{label}", expr, word, *kind)
for label, expr, word in [
    ("box-str", "prove_cycle(PS, 'x')", "box"), ("params-str", "prove_cycle('x', None)", "params"),
    ("box-none", "prove_cycle(PS, None)", "box"),
    ("box-float-corners", "prove_cycle(PS, BOX(sigma=(0.1, 0.2), tau=(F(2), F(3)), monotone_from=F(1)))", "box.sigma"),
    ("box-str-corner", "prove_cycle(PS, BOX(sigma=(F(1, 8), F(3, 8)), tau=(F(2), F(3)), monotone_from='x'))", "monotone_from"),
    ("box-one-corner", "prove_cycle(PS, BOX(sigma=(F(1, 8),), tau=(F(2), F(3)), monotone_from=F(1)))", "box.sigma"),
    ("precision-huge", "prove_cycle(PS, BOX(sigma=(F(1, 8), F(3, 8)), tau=(F(2), F(3)), monotone_from=F(1)), precision=10**9)",
     "precision"),
    ("precision-str", "prove_cycle(PS, BOX(sigma=(F(1, 8), F(3, 8)), tau=(F(2), F(3)), monotone_from=F(1)), precision='x')",
     "precision"),
]:
    case(f"prove_cycle-{label}", expr, word)
for label, expr, word in [
    ("none", "crosscheck(None)", "certificates"), ("missing-file", "crosscheck('nope.json')", "nope.json"),
    ("empty", "crosscheck([])", "certificate"), ("parameters", "crosscheck([P])", "certificate"),
    ("trajectories-huge", "crosscheck([C], trajectories=10**12)", "trajectories"),
    ("samples-huge", "crosscheck([C], samples=10**9)", "samples"),
    ("horizon-nan", "crosscheck([C], horizon=nan)", "horizon"),
    ("seed-str", "crosscheck([C], seed='x')", "seed"),
    # chunk=0 was read as 1: 10⁵ trajectories simulated one at a time, a run that seemed to loop forever
    ("chunk-zero", "crosscheck([C], chunk=0)", "chunk"), ("chunk-negative", "crosscheck([C], chunk=-5)", "chunk"),
    ("chunk-huge", "crosscheck([C], chunk=10**12)", "chunk"), ("chunk-str", "crosscheck([C], chunk='x')", "chunk"),
    ("chunk-float", "crosscheck([C], chunk=2.5)", "chunk"),
    ("seed-negative", "crosscheck([C], seed=-1)", "seed"), ("seed-beyond-scipy", "crosscheck([C], seed=2**40)", "seed"),
    ("horizon-int-400-digits", "crosscheck([C], horizon=10**400)", "horizon"),
    ("trajectories-times-samples", "crosscheck([C], trajectories=10**6, samples=10**5)", "samples"),
    ("max_events-huge", "crosscheck([C], max_events=10**12)", "max_events"),
    ("iss_search-str", "crosscheck([C], iss=True, iss_search='x')", "iss_search"),
    ("int", "crosscheck(3)", "certificates"), ("bytes", "crosscheck(b'x.json')", "certificates"),
    ("dict", "crosscheck({'a': C})", "certificates"), ("endless-generator", "crosscheck(iter(lambda: C, None))", "certificates"),
    ("directory", "crosscheck(TMP)", "directory"),
]:
    case(f"crosscheck-{label}", expr, word)
case("CrosscheckReport-strings", "CrosscheckReport('x', 1, 1, 1, 1)", "checks")
case("CrosscheckReport-checks-of-strings", "CrosscheckReport(['x'], 0.5, 0.5, 0, 1.0)", "checks[0]")
case("CrosscheckReport-seed-negative", "CrosscheckReport((), 0.5, 0.5, -1, 1.0)", "seed")
case("CrosscheckReport-rtol-str", "CrosscheckReport((), 'x', 0.5, 0, 1.0)", "rtol")
case("CrosscheckReport-seconds-nan", "CrosscheckReport((), 0.5, 0.5, 0, nan)", "seconds")
for label, expr, word in [
    ("params-str", "measure_tradeoff('x', [(0, 1, 0)], 10)", "params"),
    ("z0s-str", "measure_tradeoff(P, 'x', 10)", "z0s"),
    ("t_end-int-400-digits", "measure_tradeoff(P, [(0, 1, 0)], 10**400)", "t_end"),
    ("samples-huge", "measure_tradeoff(P, [(0, 1, 0)], 10, samples=10**12)", "samples"),
    ("z0s-none", "measure_tradeoff(P, None, 10)", "z0s"), ("z0s-row-of-two", "measure_tradeoff(P, [(0, 1)], 10)", "z0s[0]"),
    ("z0s-int-400-digits", "measure_tradeoff(P, [(10**400, 1, 0)], 10)", "z0s[0]"),
    ("z0s-billion-rows", "measure_tradeoff(P, np.broadcast_to(np.zeros(3), (10**9, 3)), 10)", "z0s"),
    ("t_end-nan", "measure_tradeoff(P, [(0, 1, 0)], nan)", "t_end"), ("t_end-str", "measure_tradeoff(P, [(0, 1, 0)], 'x')", "t_end"),
    ("repeats-huge", "measure_tradeoff(P, [(0, 1, 0)], 10, repeats=10**12)", "repeats"),
    ("budget-nan", "measure_tradeoff(P, [(0, 1, 0)], 10, budget=nan)", "budget"),
    ("thetas-str", "measure_tradeoff(P, [(0, 1, 0)], 10, thetas='x')", "thetas"),
    ("sweeps-str", "measure_tradeoff(P, [(0, 1, 0)], 10, sweeps='x')", "sweeps"),
    ("label-int", "measure_tradeoff(P, [(0, 1, 0)], 10, label=5)", "label"),
]:
    case(f"measure_tradeoff-{label}", expr, word)
for label, expr, word in [
    ("methods-str", "run_extremes(methods='x')", "methods"), ("only-unknown", "run_extremes(only=['nope'])", "nope"),
    ("limit-nan", "run_extremes(limit=nan)", "limit"), ("theta-large", "run_extremes(theta=5)", "theta"),
    ("methods-int", "run_extremes(methods=5)", "methods"), ("methods-list-of-int", "run_extremes(methods=['event', 3])", "methods[1]"),
    ("methods-too-many", "run_extremes(methods=['event'] * 1000)", "methods"), ("only-int", "run_extremes(only=5)", "only"),
    ("only-list-of-int", "run_extremes(only=[1])", "only[0]"), ("limit-int-400-digits", "run_extremes(limit=10**400)", "limit"),
    ("limit-zero", "run_extremes(limit=0)", "limit"),
]:
    case(f"run_extremes-{label}", expr, word)
for label, expr, word in [
    ("params-str", "Reference('x', (0, 1, 0), 1)", "params"), ("z0-nan", "Reference(P, (nan, 1, 0), 1)", "z0"),
    ("z0-str", "Reference(P, 'abc', 1)", "z0"), ("z0-two", "Reference(P, (0, 1), 1)", "z0"),
    ("z0-decimal-huge", "Reference(P, (D('1e999999999'), 1, 0), 1)", "z0"),
    ("z0-int-400-digits", "Reference(P, (10**400, 1, 0), 1)", "z0"),
    ("t_end-1e308", "Reference(P, (0, 1, 0), 1e308)", "t_end"), ("t_end-int-400-digits", "Reference(P, (0, 1, 0), 10**400)", "t_end"),
    ("t_end-negative", "Reference(P, (0, 1, 0), -1)", "t_end"), ("t_end-str", "Reference(P, (0, 1, 0), 'x')", "t_end"),
    ("t_end-stiff", "Reference(Parameters(k_p=3, k_i=4, k_v=10**400), (0, 1, 0), 1)", "t_end"),
    ("dps-huge", "Reference(P, (0, 1, 0), 1, dps=10**9)", "dps"), ("dps-small", "Reference(P, (0, 1, 0), 1, dps=30)", "dps"),
    ("dps-str", "Reference(P, (0, 1, 0), 1, dps='x')", "dps"), ("dps-none", "Reference(P, (0, 1, 0), 1, dps=None)", "dps"),
    ("max_events-huge", "Reference(P, (0, 1, 0), 1, max_events=10**12)", "max_events"),
    ("max_events-zero", "Reference(P, (0, 1, 0), 1, max_events=0)", "max_events"),
]:
    case(f"Reference-{label}", expr, word)
for label, expr, word in [
    ("int", "load_scene(3)", "scene"), ("none", "load_scene(None)", "scene"), ("bytes", "load_scene(b'paper-a')", "scene"),
    ("nul-byte", "load_scene('a\\x00b')", "NUL"), ("directory", "load_scene(TMP)", "directory"), ("fifo", "load_scene(FIFO)", "FIFO"),
    ("dev-zero", "load_scene('/dev/zero')", "/dev/zero"), ("unknown", "load_scene('no-such-scene')", "no-such-scene"),
    ("huge-file", "load_scene(HUGE)", "bytes"), ("not-toml", "load_scene(NOT_JSON)", "TOML"),
    ("samples-huge", "load_scene(SCENE_SAMPLES)", "samples"), ("t_end-huge", "load_scene(SCENE_T_END)", "t_end"),
    ("state-huge", "load_scene(SCENE_STATE)", "initial_states"),
]:
    case(f"load_scene-{label}", expr, word)
_SCENE = "Scene(name='x', params=P, initial_states=[(0, 1, 0)], t_end=1"
for label, expr, word in [
    ("samples-huge", _SCENE + ", samples=10**12)", "samples"), ("t_end-int-400-digits", _SCENE.replace("t_end=1", "t_end=10**400") + ")", "t_end"),
    ("state-int-400-digits", _SCENE.replace("(0, 1, 0)", "(10**400, 1, 0)") + ")", "initial_states"),
    ("million-states", _SCENE.replace("[(0, 1, 0)]", "[(0, 1, 0)] * 10**6") + ")", "initial_states"),
    ("states-str", _SCENE.replace("[(0, 1, 0)]", "'abc'") + ")", "initial_states"),
    ("params-str", _SCENE.replace("params=P", "params='x'") + ")", "params"),
    ("state-decimal-huge", _SCENE.replace("(0, 1, 0)", "(D('1e999999999'), 1, 0)") + ")", "initial_states"),
]:
    case(f"Scene-{label}", expr, word)

KNOWN: dict[str, str] = {}
"""Calls that still fail their case, each with the reason (marked ``xfail(strict=True)``): none."""


# ---- the server: one warm interpreter, a fork per call ------------------------------------------------------
_GAINS = "initial_states = [[0, 1, 0]]\n[gains]\nk_p = 3\nk_i = 4\nk_v = 6.4\nf_c = 1\n"


def _namespace(tmp: str) -> dict:
    """What the expressions may name: the public API, gains, a certificate, odd files under ``tmp``."""
    import math
    from decimal import Decimal
    from fractions import Fraction

    import numpy as np
    import scipy.integrate
    import scipy.optimize
    import sympy

    import symbolic_friction as sf
    import symbolic_friction._extremes
    import symbolic_friction._simulation.ivp_events
    import symbolic_friction._simulation.regularized
    from symbolic_friction._certify.hunting_proof import Box
    from symbolic_friction.simulation import Reference
    from symbolic_friction.studies import Scene, load_scene

    del scipy, symbolic_friction  # imported once here, not in every child
    ns = {name: getattr(sf, name) for name in sf.__all__ if not name.startswith("_")}
    P = sf.Parameters.table_i("a")
    ns.update(
        sf=sf, np=np, sympy=sympy, D=Decimal, F=Fraction, nan=math.nan, inf=math.inf, TMP=tmp, P=P,
        PS=sf.Parameters(k_p=3, k_i=4, k_v="6.4", f_s="1.2"), PR=sf.Parameters(k_p=3, k_i=4, k_v="6.4", reset_dwell="0.01"),
        C=sf.certify(P), Reference=Reference, Scene=Scene, load_scene=load_scene, BOX=Box,
        BATCH=sf.simulate_batch(P, [[0, 1, 0]], 1.0, t_eval=[0.0, 1.0]),
    )
    files = {
        "NOT_JSON": ("bad.json", "this is [not json or toml"),
        "DEEP_JSON": ("deep.json", "[" * 100_000),
        "SCENE_SAMPLES": ("samples.toml", "t_end = 1\nsamples = 1000000000000\n" + _GAINS),
        "SCENE_T_END": ("t_end.toml", "t_end = 1e400\n" + _GAINS),
        "SCENE_STATE": ("state.toml", "t_end = 1\n" + _GAINS.replace("[[0, 1, 0]]", "[[0, '1e400', 0]]")),
    }
    for key, (name, text) in files.items():
        Path(tmp, name).write_text(text, encoding="utf-8")
        ns[key] = str(Path(tmp, name))
    os.mkfifo(Path(tmp, "fifo.json"))
    ns["FIFO"] = str(Path(tmp, "fifo.json"))
    with open(Path(tmp, "huge.json"), "wb") as fh:  # sparse: 2 GB that take no space
        fh.truncate(2 * 1024**3)
    ns["HUGE"] = str(Path(tmp, "huge.json"))
    return ns


def serve() -> None:  # pragma: no cover - runs in the server process
    """Build the namespace once, then evaluate each expression read from stdin in a fork; answer one JSON line each."""
    import shutil
    import tempfile
    import warnings

    wire_in = os.fdopen(os.dup(0), "r", encoding="utf-8")
    wire_out = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)  # a stray print must not corrupt the wire
    warnings.simplefilter("ignore")
    tmp = tempfile.mkdtemp(prefix="hostile-api-")
    try:
        ns = _namespace(tmp)
        wire_out.write("ready\n")
        wire_out.flush()
        for line in wire_in:
            wire_out.write(json.dumps(_run_one(json.loads(line), ns)) + "\n")
            wire_out.flush()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def _run_one(expr: str, ns: dict) -> dict:  # pragma: no cover - runs in the server process
    read, write = os.pipe()
    start = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        _child(expr, ns, write)
    os.close(write)
    ready, _, _ = select.select([read], [], [], BOUND)
    data = b""
    if ready:
        while chunk := os.read(read, 65536):
            data += chunk
    else:
        os.kill(pid, signal.SIGKILL)
    os.close(read)
    _, status = os.waitpid(pid, 0)
    seconds = time.perf_counter() - start
    if not ready:
        return {"kind": "timeout", "seconds": seconds}
    if not data:
        return {"kind": "died", "status": os.waitstatus_to_exitcode(status), "seconds": seconds}
    result = json.loads(data)
    result["seconds"] = seconds
    return result


def _child(expr: str, ns: dict, fd: int) -> None:  # pragma: no cover - the forked child
    result: dict = {"kind": "died"}
    try:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
        from symbolic_friction import SymbolicFrictionError

        code = compile(expr, "<case>", "eval")
        try:
            value = eval(code, dict(ns))
            result = {"kind": "return", "repr": type(value).__name__}
        except BaseException as exc:  # noqa: BLE001 - every exception is the observation
            # files and line numbers only: reading the frames' source lines (extract_tb) took a third of a case's time
            frames = traceback.StackSummary.extract(traceback.walk_tb(exc.__traceback__), lookup_lines=False)
            result = {
                "kind": "raise", "type": type(exc).__name__, "ours": isinstance(exc, SymbolicFrictionError),
                "message": str(exc)[:5000], "last_frame": frames[-1].filename if frames else "",
                "frames": [f"{f.filename}:{f.lineno}" for f in frames[-4:]],
            }
    finally:
        with os.fdopen(fd, "w", encoding="utf-8") as out:
            out.write(json.dumps(result))
        os._exit(0)


class Server:
    def __init__(self) -> None:
        env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
        self.proc = subprocess.Popen(
            [sys.executable, "-c", "from tests.test_hostile_api import serve; serve()"], cwd=str(REPO), env=env,
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, encoding="utf-8",
        )
        assert self.proc.stdout.readline().strip() == "ready"

    def run(self, expr: str) -> dict:
        self.proc.stdin.write(json.dumps(expr) + "\n")
        self.proc.stdin.flush()
        return json.loads(self.proc.stdout.readline())

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=30)


@pytest.fixture(scope="module")
def server():
    forks = Server()
    yield forks
    forks.close()


def test_the_corpus_is_large_and_covers_the_public_api():
    import symbolic_friction as sf

    ids = [c[0] for c in CASES]
    assert len(ids) == len(set(ids)) and len(ids) >= 200, len(ids)
    assert set(KNOWN) <= set(ids)
    called = " ".join(c[1] for c in CASES)
    public = [n for n in sf.__all__ if not n.startswith("_") and n not in sf._MODULES and n not in ("TABLE_I", "SymbolicFrictionError")]
    missing = [n for n in public if f"{n}(" not in called and f"{n}." not in called]
    assert not missing, f"public names no hostile call exercises: {missing}"


@pytest.mark.parametrize(
    "name, expr, word, kind",
    [pytest.param(*c, id=c[0], marks=[pytest.mark.xfail(reason=KNOWN[c[0]], strict=True)] if c[0] in KNOWN else [])
     for c in CASES],
)
def test_hostile_call_raises_the_packages_error_early(server, name, expr, word, kind):
    result = server.run(expr)
    assert result["kind"] != "timeout", f"{expr}: no answer within {BOUND} s"
    assert result["kind"] == "raise", f"{expr}: {result}"
    assert result["seconds"] < BOUND
    message = result["message"]
    if kind == "signature":
        # Python's own TypeError at the call: nothing of the package (or a dependency) on the traceback
        assert result["type"] == "TypeError" and result["last_frame"] == "<case>", result
    else:
        assert result["ours"], f"{expr}: {result['type']}: {message[:500]} at {result['frames']}"
        assert len(message) <= 600 and "\n" not in message, message[:2000]
    assert word.lower() in message.lower(), f"{expr}: the message does not name {word!r}: {message}"


def test_numpy_integers_are_read_as_python_integers():
    """``to_rational(np.int64(3))`` is a Fraction of Python ints: an ``np.int64`` numerator would wrap around in the
    exact arithmetic that follows (``Fraction(np.int64(2**62)) * 4``)."""
    import numpy as np

    from symbolic_friction import to_rational

    for value in (np.int64(3), np.uint8(200), np.int32(-7), np.int64(2**62)):
        q = to_rational(value, name="gain")
        assert q == int(value) and type(q.numerator) is int and type(q.denominator) is int, (value, q)
    assert to_rational(np.int64(2**62), name="gain") * 4 == 2**64
