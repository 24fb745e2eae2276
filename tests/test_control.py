"""python-control in and out: ``Parameters.from_control`` and ``Parameters.to_control``
(symbolic_friction/_model/python_control.py, paper §II-A, eqs. uPID, CoC, xDot).

Table I's gains go through python-control and come back exactly where the input
is exact; both system types are read; a negligible derivative filter is dropped
and another refused; every refusal names what does not fit; the closed loop's
``A`` is the paper's, exactly, and its poles and step response are ``A``'s.
"""

from __future__ import annotations

import re
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import sympy

from symbolic_friction import Parameters, step_response
from symbolic_friction._model.coordinates import (
    system_matrix,
    system_matrix_entries,
    x_to_z,
)
from symbolic_friction._model.python_control import closed_loop_matrices
from symbolic_friction._model.transfer_function import read_transfer_function
from symbolic_friction.errors import AssumptionError, NonFiniteError, ParameterError

# python-control (with scipy.signal and matplotlib, about 1.5 s) is imported when the module's first test runs, not
# at collection, which every pytest-xdist worker does for every module: `_control` below binds these names
ct = s = GOOD_PID = GOOD_PLANT = None


@pytest.fixture(scope="module", autouse=True)
def _control():
    """python-control (each test skipped without it), its Laplace variable and the refusals' good plant and PID."""
    global ct, s, GOOD_PID, GOOD_PLANT
    ct = pytest.importorskip("control")
    s = ct.tf("s")
    GOOD_PID = 6 + 8 / s + 12.3 * s
    GOOD_PLANT = 1 / (2 * s**2 + 0.5 * s)


# Table I of the paper as typed there: (k_p, k_i, k_v) with f_c = 1 (the floats python-control holds)
TABLE_I_TYPED = {"a": (3, 4, 6.4), "b": (0.66, 0.08, 1.5)}
SNIPPET = Path(__file__).resolve().parents[1] / "docs" / "_snippets" / "control.md"


# ---------------------------------------------------------------- in: round trips


@pytest.mark.parametrize("case", ["a", "b"])
def test_table_i_typed_into_python_control_comes_back_exactly(case):
    k_p, k_i, k_v = TABLE_I_TYPED[case]
    p = Parameters.from_control(1 / s**2, k_p + k_i / s + k_v * s, f_c_bar=1)
    assert p == Parameters.table_i(case)
    assert (p.k_p, p.k_i, p.k_v, p.f_c) == (Parameters.table_i(case).k_p, Parameters.table_i(case).k_i,
                                            Parameters.table_i(case).k_v, 1)
    assert p.physical.m == 1 and p.physical.alpha_v == 0 and p.physical.f_c_bar == 1


@pytest.mark.parametrize("case", ["a", "b"])
def test_table_i_round_trips_through_to_control(case):
    p = Parameters.table_i(case)
    plant, controller = p.to_control(kind="plant_controller")
    assert isinstance(plant, ct.TransferFunction) and isinstance(controller, ct.TransferFunction)
    assert Parameters.from_control(plant, controller, f_c_bar=p.f_c) == p


def test_physical_values_round_trip_and_normalise_once():
    p = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2, f_s_bar=3)
    plant, controller = p.to_control(kind="plant_controller")
    q = Parameters.from_control(plant, controller, f_c_bar=2, f_s_bar=3)
    assert q == p and q.physical == p.physical and q.f_s == Fraction(3, 2)
    assert Parameters.from_control(1 / (2 * s**2 + 0.5 * s), 6 + 8 / s + 12.3 * s, f_c_bar=2) == Parameters.table_i("a")


def test_a_gain_and_common_factors_are_normalised_exactly():
    plant = (s + 0.3) * 4 / ((s + 0.3) * (8 * s**2 + 2 * s))  # 1/(2 s² + s/2) with a common factor and a gain
    controller = (s + 1) * (6 + 8 / s + 12.3 * s) / (s + 1)
    p = Parameters.from_control(plant, controller, f_c_bar=2)
    assert p == Parameters.table_i("a") and p.physical.m == 2 and p.physical.alpha_v == Fraction(1, 2)


def test_floats_are_read_by_their_shortest_decimal_or_their_binary_value():
    typed = 1 / s**2, 3 + 4 / s + 6.4 * s
    assert Parameters.from_control(*typed, f_c_bar=1).k_v == Fraction(32, 5)
    binary = Parameters.from_control(*typed, f_c_bar=1, binary=True)
    assert binary.k_v == Fraction(6.4) != Fraction(32, 5)
    assert binary.physical.k_d_bar == Fraction(6.4)


def test_state_space_inputs_are_read_exactly():
    # Table I (a) with the damping in the plant: 1/(s² + 6.4 s) and the PI 3 + 4/s, both as StateSpace
    plant = ct.ss([[0, 1], [0, -6.4]], [[0], [1]], [[1, 0]], [[0]])
    pi = ct.ss([[0]], [[1]], [[4]], [[3]])
    p = Parameters.from_control(plant, pi, f_c_bar=1)
    assert p == Parameters.table_i("a") and p.physical.alpha_v == Fraction(32, 5) and p.physical.k_d_bar == 0
    # a non-minimal realisation: a decoupled third state cancels exactly
    redundant = ct.ss([[0, 1, 0], [0, -6.4, 0], [0, 0, -1]], [[0], [1], [1]], [[1, 0, 0]], [[0]])
    assert Parameters.from_control(redundant, pi, f_c_bar=1) == p
    # python-control's own realisations of the transfer functions
    assert Parameters.from_control(ct.ss(1 / (2 * s**2 + 0.5 * s)), 6 + 8 / s + 12.3 * s, f_c_bar=2) == p


def test_read_transfer_function_is_exact_for_the_closed_loop():
    # to_control's closed loop read back exactly: y/r = (k_p s + k_i)/(s³ + k_v s² + k_p s + k_i), y/d = s/(…)
    for case in ("a", "b"):
        p = Parameters.table_i(case)
        charpoly = [1, p.k_v, p.k_p, p.k_i]
        assert read_transfer_function(p.to_control(), "loop") == ([p.k_p, p.k_i], charpoly)
        assert read_transfer_function(p.to_control(input="disturbance"), "loop") == ([1, 0], charpoly)


# ---------------------------------------------------------------- the derivative filter


def test_a_negligible_derivative_filter_is_dropped():
    p = Parameters.table_i("a")  # max|λ(A)| ≈ 5.17
    pid = 3 + 4 / s + 6.4 * s / (0.001 * s + 1)
    assert Parameters.from_control(1 / s**2, pid, f_c_bar=1) == p
    assert Parameters.from_control(1 / s**2, ct.ss(pid), f_c_bar=1) == p  # the filtered PID is proper: a StateSpace
    physical = 6 + 8 / s + 12.3 * s / (0.0005 * s + 1)
    assert Parameters.from_control(1 / (2 * s**2 + 0.5 * s), physical, f_c_bar=2) == p


def test_a_filter_that_is_not_negligible_is_refused_with_what_was_found():
    pid = 3 + 4 / s + 6.4 * s / (0.05 * s + 1)
    with pytest.raises(ParameterError) as info:
        Parameters.from_control(1 / s**2, pid, f_c_bar=1)
    message = str(info.value)
    assert "not negligible" in message and "tau = 1/20" in message and "filter_tolerance = 1/100" in message
    rate = max(abs(np.linalg.eigvals(system_matrix(Parameters.table_i("a")))))
    assert f"max|lambda(A)| = {rate:.4g}" in message and f"{0.05 * rate:.4g} >" in message
    assert Parameters.from_control(1 / s**2, pid, f_c_bar=1, filter_tolerance="0.4") == Parameters.table_i("a")
    with pytest.raises(ParameterError, match="not negligible"):
        Parameters.from_control(1 / s**2, 3 + 4 / s + 6.4 * s / (1e-9 * s + 1), f_c_bar=1, filter_tolerance=0)


# ---------------------------------------------------------------- refusals


# Each case's plant and controller are made when it runs (a lambda of the names `_control` binds); the ids are
# those pytest gives the systems themselves (plant0, controller0, …).
REFUSED = [
    (lambda: ct.ss(np.zeros((2, 2)), np.eye(2), np.eye(2), np.zeros((2, 2))), lambda: GOOD_PID,
     r"plant is MIMO \(2 inputs, 2 outputs\)"),
    (lambda: ct.tf([1], [1, 0, 0], 0.1), lambda: GOOD_PID,
     r"plant is a discrete-time transfer function \(dt = 0.1\)"),
    (lambda: GOOD_PLANT, lambda: ct.tf([1, 1], [1, 0], True), r"controller is a discrete-time"),
    (3.0, lambda: GOOD_PID, "plant must be a python-control TransferFunction or StateSpace; got float"),
    (lambda: ct.frd([1, 1], [1, 2]), lambda: GOOD_PID, "got FrequencyResponseData"),
    (lambda: (s + 1) / s**2, lambda: GOOD_PID, r"plant \(s \+ 1\)/\(s\^2\) has a zero at s = -1"),
    (lambda: 1 / (s**3 + s**2), lambda: GOOD_PID, r"plant 1/\(s\^3 \+ s\^2\) is of order 3"),
    (lambda: 1 / s, lambda: GOOD_PID, "is of order 1"),
    (lambda: 1 / (s**2 + s + 2), lambda: GOOD_PID,
     "nonzero constant term in its denominator .a spring of stiffness 2"),
    (lambda: -1 / s**2, lambda: GOOD_PID, "negative mass m = -1"),
    (lambda: 1 / (s**2 - 0.5 * s), lambda: GOOD_PID, "negative viscous coefficient alpha_v = -1/2"),
    (lambda: GOOD_PLANT, lambda: 6 + 12.3 * s, r"controller 123/10 s \+ 6 has no integral action"),
    (lambda: GOOD_PLANT, lambda: (s + 2) / (s + 3), "nonzero constant term 3 in its denominator: no integrator"),
    (lambda: GOOD_PLANT, lambda: GOOD_PID * s, "no integral action"),
    (lambda: GOOD_PLANT, lambda: GOOD_PID / s,
     r"wrong order \(numerator degree 2, denominator degree 2\)|double integrator"),
    (lambda: GOOD_PLANT, lambda: (s**2 + s + 1) / s**2, "double integrator"),
    (lambda: GOOD_PLANT, lambda: GOOD_PID * (s + 1), r"wrong order \(numerator degree 3, denominator degree 1\)"),
    (lambda: GOOD_PLANT, lambda: 6 + 8 / s + 12.3 * s / (-0.001 * s + 1), "negative time constant tau = -1/1000"),
    (lambda: GOOD_PLANT, lambda: ct.tf([0], [1]), "controller is zero"),
    (lambda: Parameters.table_i("a").to_control(), lambda: GOOD_PID, "has a zero at s = -1.333"),
    (lambda: ct.ss(np.diag(np.arange(11.0)), np.ones((11, 1)), np.ones((1, 11)), 0), lambda: GOOD_PID,
     "has 11 states; at most 10"),
]


@pytest.mark.parametrize(
    ("plant", "controller", "fragment"), REFUSED,
    ids=[f"{'3.0' if plant == 3.0 else f'plant{n}'}-controller{n}-{fragment}"
         for n, (plant, _, fragment) in enumerate(REFUSED)],
)
def test_what_does_not_fit_is_refused_by_name(plant, controller, fragment):
    plant, controller = (x() if callable(x) else x for x in (plant, controller))
    with pytest.raises(ParameterError, match=fragment):
        Parameters.from_control(plant, controller, f_c_bar=1)


def test_gains_outside_assumption_1_are_refused_with_the_values_read():
    with pytest.raises(AssumptionError, match=r"k_v·k_p > k_i.*read from python-control: m = 2, alpha_v = 1/2"):
        Parameters.from_control(GOOD_PLANT, 1 + 8 / s + 0.3 * s, f_c_bar=1)
    with pytest.raises(AssumptionError, match="f_c_bar > 0"):
        Parameters.from_control(GOOD_PLANT, GOOD_PID, f_c_bar=0)


def test_non_finite_coefficients_and_a_negative_tolerance_are_refused():
    with pytest.raises(NonFiniteError, match="plant's denominator coefficient must be finite"):
        Parameters.from_control(ct.tf([1], [float("nan"), 0, 0]), GOOD_PID, f_c_bar=1)
    with pytest.raises(ParameterError, match="filter_tolerance must be >= 0"):
        Parameters.from_control(GOOD_PLANT, GOOD_PID, f_c_bar=1, filter_tolerance=-1)


# ---------------------------------------------------------------- out


def test_the_closed_loop_has_the_papers_A_exactly():
    for case in ("a", "b"):
        p = Parameters.table_i(case)
        loop = p.to_control()
        assert isinstance(loop, ct.StateSpace) and loop.nstates == 3
        assert np.array_equal(loop.A, system_matrix(p))
        A, _, _, D = closed_loop_matrices(p)
        assert A == system_matrix_entries(p.k_p, p.k_i, p.k_v) and D == 0
        assert loop.state_labels == ["sigma", "phi", "v"] and loop.output_labels == ["y"]


def test_closed_loop_matrices_are_the_coordinates_module_for_symbolic_gains():
    # the binding: python_control.py writes A itself (an import would be a loop); it is eq. (xDot)'s A
    k_p, k_i, k_v = sympy.symbols("k_p k_i k_v", positive=True)

    class Symbolic:  # closed_loop_matrices reads only k_p, k_i, k_v
        pass

    gains = Symbolic()
    gains.k_p, gains.k_i, gains.k_v = k_p, k_i, k_v
    A, B, C, _ = closed_loop_matrices(gains, input="disturbance")
    assert sympy.Matrix(A) == sympy.Matrix(system_matrix_entries(k_p, k_i, k_v))
    assert B == (0, 0, 1)
    # the output is the position: C x = s of x_to_z (eq. CoC), exactly
    p = Parameters.table_i("b")
    x = np.array([Fraction(1, 3), Fraction(-2, 7), Fraction(5, 11)], dtype=object)
    _, _, C, _ = closed_loop_matrices(p)
    assert sum(c * xi for c, xi in zip(C, x)) == x_to_z(p, x)[1]


def test_poles_are_the_eigenvalues_of_A():
    for case in ("a", "b"):
        p = Parameters.table_i(case)
        eig = np.sort_complex(np.linalg.eigvals(system_matrix(p)))
        for loop in (p.to_control(), p.to_control(input="disturbance")):
            np.testing.assert_allclose(np.sort_complex(ct.poles(loop)), eig, rtol=1e-12)
        plant, controller = p.to_control(kind="plant_controller")
        np.testing.assert_allclose(np.sort_complex(ct.poles(ct.feedback(plant * controller, 1))), eig, rtol=1e-9)


def test_step_response_is_that_of_A():
    from scipy.linalg import expm

    p = Parameters.table_i("a")
    t = np.linspace(0, 10, 201)
    for input in ("reference", "disturbance"):
        loop = p.to_control(input=input)
        y = ct.step_response(loop, t).outputs
        A, B, C = system_matrix(p), loop.B[:, 0], loop.C[0]
        exact = [C @ np.linalg.solve(A, (expm(A * ti) - np.eye(3)) @ B) for ti in t]  # ∫ e^{Aτ} B dτ
        np.testing.assert_allclose(y, exact, atol=1e-10)
    # the integral action: a reference step is tracked, a constant force rejected
    assert np.isclose(ct.dcgain(p.to_control()), 1) and np.isclose(ct.dcgain(p.to_control(input="disturbance")), 0)


def test_reference_loop_is_the_simulators_step_response_without_friction():
    p = Parameters.table_i("a")
    almost_no_friction = Parameters(k_p=p.k_p, k_i=p.k_i, k_v=p.k_v, f_c="1e-6")
    t = np.linspace(0, 10, 201)
    linear = ct.step_response(p.to_control(), t).outputs
    np.testing.assert_allclose(step_response(almost_no_friction, t).outputs, linear, atol=1e-5)


def test_plant_and_controller_close_the_same_loop():
    p = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
    plant, controller = p.to_control(kind="plant_controller")
    disturbance = p.to_control(input="disturbance")
    for w in (0.1, 1.0, 7.0):  # feedback(P, C) is force → position: the disturbance loop over m
        assert np.isclose(complex(ct.feedback(plant, controller)(1j * w)), complex(disturbance(1j * w)) / 2)
    assert plant.input_labels == ["u"] and controller.output_labels == ["u"]


def test_kind_and_input_are_checked():
    with pytest.raises(ParameterError, match="kind must be one of closed_loop, plant_controller; got 'open'"):
        Parameters.table_i("a").to_control(kind="open")
    with pytest.raises(ParameterError, match="input must be one of reference, disturbance"):
        Parameters.table_i("a").to_control(input="noise")


# ---------------------------------------------------------------- without python-control


def test_without_python_control_the_error_says_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "control", None)  # `import control` raises ImportError
    with pytest.raises(ImportError, match=re.escape("pip install 'symbolic-friction[control]'")):
        Parameters.table_i("a").to_control()
    with pytest.raises(ImportError, match=re.escape("pip install 'symbolic-friction[control]'")):
        Parameters.from_control(GOOD_PLANT, GOOD_PID, f_c_bar=1)


# ---------------------------------------------------------------- the docs snippet


def test_the_docs_snippet_prints_what_it_shows(capsys):
    text = SNIPPET.read_text(encoding="utf-8")
    code = re.search(r"```python\n(.*?)```", text, re.DOTALL).group(1)
    shown = re.search(r"```text\n(.*?)```", text, re.DOTALL).group(1)
    exec(compile(code, str(SNIPPET), "exec"), {})  # noqa: S102  (the snippet is this repository's own)
    assert capsys.readouterr().out == shown
