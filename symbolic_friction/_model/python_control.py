"""python-control systems in and out of :class:`~symbolic_friction.Parameters`
(paper §II-A, eqs. uPID, basic, CoC and xDot).

**In** (:func:`from_control`): the plant of §II-A, a mass with viscous friction
driven by the force ``u``, ``P(s) = 1/(m s² + α_v s)``, and the PID of eq. (uPID)
acting on the error ``-s``, ``C(s) = k̄_p + k̄_i/s + k̄_d s``, perhaps with a
negligible derivative filter ``k̄_d s/(τ s + 1)``.  The floats python-control holds
are read exactly and normalised in exact arithmetic
(:mod:`~symbolic_friction._model.transfer_function`: ``6.4`` is 32/5, or its binary
value with ``binary=True``), the gains read off.  The physical values go through
:meth:`Parameters.from_physical <symbolic_friction.Parameters.from_physical>`, the
package's one normalisation.  Anything else is refused with a
:class:`~symbolic_friction.errors.ParameterError` naming what does not fit.

**Out** (:func:`to_control`): the friction-free closed loop, the linear part of
eq. (xDot) in the paper's ``x = (σ, φ, v)`` (eq. CoC), as a ``control.StateSpace``,
or the plant and controller as ``control.TransferFunction``.

python-control (``pip install 'symbolic-friction[control]'``) is imported inside
the functions only.  ``A`` is :func:`~symbolic_friction._model.coordinates.system_matrix_entries`,
the model's one definition of eq. (xDot).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from .._infra.errors import ParameterError
from .._infra.rational import short_rational, to_rational
from .coordinates import system_matrix_entries
from .transfer_function import control_module, read_transfer_function, tf_str

__all__ = ["from_control", "to_control", "closed_loop_matrices",
           "DEFAULT_FILTER_TOLERANCE", "KINDS", "INPUTS"]

DEFAULT_FILTER_TOLERANCE = Fraction(1, 100)
"""A derivative filter ``τ`` is negligible when ``τ·ω_max ≤`` this (``ω_max = max |λ(A)|``)."""
KINDS = ("closed_loop", "plant_controller")
INPUTS = ("reference", "disturbance")


def _read_plant(plant: Any, binary: bool) -> tuple[Fraction, Fraction]:
    """``(m, α_v)`` of ``1/(m s² + α_v s)``."""
    num, den = read_transfer_function(plant, "plant", binary=binary)
    shown = tf_str(num, den)
    if len(num) > 1:
        import numpy as np

        zeros = ", ".join(f"{z:.4g}" for z in np.roots([float(c) for c in num]))
        raise ParameterError(
            f"the plant {shown} has a zero at s = {zeros}; "
            "the paper's plant 1/(m s^2 + alpha_v s) has none"
        )
    if len(den) != 3:
        raise ParameterError(
            f"the plant {shown} is of order {len(den) - 1}; the paper's plant 1/(m s^2 + alpha_v s) is of order 2 "
            "(a mass driven by a force, position out)"
        )
    gain = num[0]
    m, alpha_v, spring = den[0] / gain, den[1] / gain, den[2] / gain
    if spring != 0:
        raise ParameterError(
            f"the plant {shown} has a nonzero constant term in its denominator (a spring of stiffness "
            f"{short_rational(spring)} in m s^2 + alpha_v s + k); the paper's plant 1/(m s^2 + alpha_v s) has none"
        )
    if m <= 0:
        raise ParameterError(
            f"the plant {shown} has a negative mass m = {short_rational(m)}; the paper's plant 1/(m s^2 + alpha_v s) "
            "needs m > 0 (a positive force pushes the mass forward)"
        )
    if alpha_v < 0:
        raise ParameterError(
            f"the plant {shown} has a negative viscous coefficient alpha_v = {short_rational(alpha_v)}; "
            "the paper's plant 1/(m s^2 + alpha_v s) needs alpha_v >= 0"
        )
    return m, alpha_v


def _read_controller(controller: Any, binary: bool) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    """``(k̄_p, k̄_i, k̄_d, τ)`` of the parallel PID ``k̄_p + k̄_i/s + k̄_d s/(τ s + 1)`` (``τ = 0``: no filter)."""
    num, den = read_transfer_function(controller, "controller", binary=binary)
    shown = tf_str(num, den)
    pid = "the paper's PID k_p_bar + k_i_bar/s + k_d_bar s (eq. uPID)"
    if len(den) == 1:
        raise ParameterError(
            f"the controller {shown} has no integral action (no pole at s = 0 after cancelling common factors: "
            f"k_i_bar = 0); {pid} needs k_i_bar > 0"
        )
    if len(den) > 3 or len(num) > 3:
        raise ParameterError(
            f"the controller {shown} is of the wrong order (numerator degree {len(num) - 1}, denominator degree "
            f"{len(den) - 1}); {pid} is (k_d_bar s^2 + k_p_bar s + k_i_bar)/s, at most with a derivative filter "
            "(denominator s (tau s + 1))"
        )
    if den[-1] != 0:
        raise ParameterError(
            f"the controller {shown} has a nonzero constant term {short_rational(den[-1])} in its denominator: "
            f"no integrator (pole at s = 0); {pid} has one"
        )
    if len(den) == 2:  # s: the ideal PID
        padded = [Fraction(0)] * (3 - len(num)) + num
        return padded[1], padded[2], padded[0], Fraction(0)
    if den[1] == 0:
        raise ParameterError(f"the controller {shown} has a double integrator (s^2 in its denominator); {pid} has one")
    tau = den[0] / den[1]
    if tau < 0:
        raise ParameterError(
            f"the controller {shown} has a derivative filter with negative time constant tau = {short_rational(tau)} "
            "(an unstable pole); a filter s/(tau s + 1) needs tau > 0"
        )
    n2, n1, n0 = ([Fraction(0)] * (3 - len(num)) + num)
    n2, n1, n0 = n2 / den[1], n1 / den[1], n0 / den[1]
    k_p_bar = n1 - n0 * tau
    k_d_bar = n2 - k_p_bar * tau
    if not binary:  # python-control rounded k̄_i τ + k̄_p and k̄_p τ + k̄_d: recover the typed decimals
        k_p_bar = _shortest_near(k_p_bar, n1, n0 * tau)
        k_d_bar = _shortest_near(k_d_bar, n2, k_p_bar * tau)
    return k_p_bar, n0, k_d_bar, tau


def _shortest_near(q: Fraction, *terms: Fraction) -> Fraction:
    """The shortest decimal within 4 units in the last place of ``terms`` of ``q`` (their float sum's rounding), else ``q``."""
    try:
        slack = 4 * sum(Fraction(math.ulp(float(t))) for t in terms)
        x = float(q)
    except OverflowError:
        return q
    for digits in range(17):
        candidate = Fraction(f"{x:.{digits}e}")
        if abs(candidate - q) <= slack:
            return candidate
    return q


def _fastest_rate(params: Any) -> float:
    """``ω_max = max |λ|`` over the eigenvalues of ``A`` (roots of ``s³ + k_v s² + k_p s + k_i``)."""
    import numpy as np

    from .coordinates import system_matrix

    return float(np.max(np.abs(np.linalg.eigvals(system_matrix(params)))))


def from_control(cls: Any, plant: Any, controller: Any, *, f_c_bar: Any, f_s_bar: Any = None, binary: bool = False,
                 filter_tolerance: Any = DEFAULT_FILTER_TOLERANCE) -> Any:
    """Gains from a python-control plant and PID (paper §II-A, eq. uPID), for
    :meth:`Parameters.from_control <symbolic_friction.Parameters.from_control>`.

    Parameters
    ----------
    cls : type
        :class:`~symbolic_friction.Parameters` (passed in: this module does not import it).
    plant : control.TransferFunction or control.StateSpace
        SISO, continuous time: ``1/(m s² + α_v s)`` from the force to the position,
        ``m > 0``, ``α_v ≥ 0``, up to a common factor and a constant gain
        (``2/(4 s² + s)`` is ``m = 2``, ``α_v = 1/2``).
    controller : control.TransferFunction or control.StateSpace
        SISO, continuous time, from the error ``-s`` to the force: the PID
        ``k̄_p + k̄_i/s + k̄_d s`` of eq. (uPID), or ``k̄_p + k̄_i/s + k̄_d s/(τ s + 1)``
        with a negligible derivative filter (any ``(n₂ s² + n₁ s + n₀)/(s (τ s + 1))``
        is read as this parallel form: ``k̄_i = n₀``, ``k̄_p = n₁ - k̄_i τ``,
        ``k̄_d = n₂ - k̄_p τ``, each the shortest decimal within the rounding of
        python-control's float products, so ``12.3 s/(0.05 s + 1)`` gives ``k̄_d = 123/10``).
    f_c_bar : number, keyword-only
        Physical Coulomb force ``f̄_c > 0``, in the units of the plant's input;
        :meth:`~symbolic_friction.Parameters.from_physical` normalises it, ``f_c = f̄_c/m``.
    f_s_bar : number or None, keyword-only
        Physical static friction force ``f̄_s ≥ f̄_c`` (default ``f̄_c``).
    binary : bool, keyword-only
        Read each float coefficient through its exact binary value
        (``Fraction(6.4)``); by default through its shortest round-tripping decimal,
        as :func:`~symbolic_friction.to_rational` reads floats (``6.4`` is 32/5).
        Both are exact readings of the float; the decimal one recovers what was typed.
    filter_tolerance : number, keyword-only
        When a derivative filter ``τ > 0`` is *negligible*: ``τ·ω_max ≤ filter_tolerance``,
        ``ω_max = max |λ(A)|`` over the eigenvalues of the friction-free closed loop
        ``A`` (eq. xDot) of the gains read with the filter dropped, so ``1/ω_max`` is
        its fastest time scale.  Default 1/100: the filter is a hundred times faster
        than the loop.  A negligible filter is dropped; another is refused.

    Returns
    -------
    Parameters
        From :meth:`~symbolic_friction.Parameters.from_physical` (``physical`` records
        ``m``, ``α_v``, ``k̄_p``, ``k̄_i``, ``k̄_d``, ``f̄_c``).

    Raises
    ------
    ParameterError
        Naming what does not fit: not a TransferFunction or StateSpace, MIMO,
        discrete time, a plant with a zero, of another order, with a spring
        (a nonzero constant term in its denominator), a negative mass or damping; a
        controller without integrator, of another order, with a double integrator,
        an unstable or a non-negligible filter (with ``τ`` and ``1/ω_max`` found).
        :class:`~symbolic_friction.errors.AssumptionError` (a subclass) if the gains
        violate Assumption 1, with the values read.
    ImportError
        If python-control is not installed.

    Examples
    --------
    >>> import control
    >>> from symbolic_friction import Parameters
    >>> s = control.tf("s")
    >>> from_control(Parameters, 1 / s**2, 3 + 4 / s + 6.4 * s, f_c_bar=1) == Parameters.table_i("a")
    True
    >>> from_control(Parameters, 1 / s**2, 3 + 4 / s + 6.4 * s, f_c_bar=1, binary=True).k_v == Fraction(6.4)
    True
    >>> pid = 3 + 4 / s + 6.4 * s / (0.001 * s + 1)  # a filter 1/(0.001·5.17) ≈ 190 times faster than the loop
    >>> from_control(Parameters, 1 / s**2, pid, f_c_bar=1) == Parameters.table_i("a")
    True
    """
    tolerance = to_rational(filter_tolerance, name="filter_tolerance")
    if tolerance < 0:
        raise ParameterError(f"filter_tolerance must be >= 0; got {short_rational(tolerance)}")
    m, alpha_v = _read_plant(plant, binary)
    k_p_bar, k_i_bar, k_d_bar, tau = _read_controller(controller, binary)
    read = (f"m = {short_rational(m)}, alpha_v = {short_rational(alpha_v)} (plant), k_p_bar = {short_rational(k_p_bar)}, "
            f"k_i_bar = {short_rational(k_i_bar)}, k_d_bar = {short_rational(k_d_bar)} (controller)")
    try:
        params = cls.from_physical(m=m, k_p_bar=k_p_bar, k_i_bar=k_i_bar, k_d_bar=k_d_bar, alpha_v=alpha_v,
                                   f_c_bar=f_c_bar, f_s_bar=f_s_bar)
    except ParameterError as exc:
        raise type(exc)(f"{exc} [read from python-control: {read}]") from None
    if tau > 0:
        rate = _fastest_rate(params)
        product = float(tau) * rate
        if not product <= float(tolerance):
            raise ParameterError(
                f"the controller's derivative filter is not negligible: tau = {short_rational(tau)}, the closed "
                f"loop's fastest time scale is 1/max|lambda(A)| = {1 / rate:.4g} (max|lambda(A)| = {rate:.4g}), so "
                f"tau·max|lambda(A)| = {product:.4g} > filter_tolerance = {short_rational(tolerance)}; the paper's PID "
                "(eq. uPID) has an unfiltered derivative: make tau smaller or raise filter_tolerance"
            )
    return params


# ---------------------------------------------------------------- out


def closed_loop_matrices(params: Any, *, input: str = "reference") -> tuple[tuple, tuple, tuple, Fraction]:
    """``(A, B, C, D)`` of the friction-free closed loop, exact (module docstring; eq. xDot).

    ``A`` is the paper's matrix of eq. (xDot); for ``input="reference"``
    ``B = (0, k_i, k_p)`` (a position reference ``r``, derivative on the
    measurement), for ``"disturbance"`` ``B = (0, 0, 1)`` (a force on the mass
    over ``m``, like ``f_c``); the output is the position, ``y = -σ/k_i``.

    Examples
    --------
    >>> from symbolic_friction import Parameters
    >>> A, B, C, D = closed_loop_matrices(Parameters.table_i("a"))
    >>> [[str(a) for a in row] for row in A], [str(b) for b in B], [str(c) for c in C], D
    ([['0', '0', '-4'], ['1', '0', '-3'], ['0', '1', '-32/5']], ['0', '4', '3'], ['-1/4', '0', '0'], Fraction(0, 1))
    """
    if input not in INPUTS:
        raise ParameterError(f"input must be one of {', '.join(INPUTS)}; got {input!r}")
    k_p, k_i, k_v = params.k_p, params.k_i, params.k_v
    zero, one = Fraction(0), Fraction(1)
    A = tuple(tuple(zero + a for a in row) for row in system_matrix_entries(k_p, k_i, k_v))  # eq. (xDot), exact
    B = (zero, k_i, k_p) if input == "reference" else (zero, zero, one)
    C = (-1 / k_i, zero, zero)  # s = -σ/k_i (eq. CoC)
    return A, B, C, zero


def _float(q: Fraction, name: str) -> float:
    try:
        value = float(q)
    except OverflowError:
        value = float("inf")
    if value in (float("inf"), float("-inf")) or (value == 0.0 and q != 0):
        raise ParameterError(f"{name} = {short_rational(q)} is outside the range of floating point that python-control holds")
    return value


def to_control(params: Any, *, kind: str = "closed_loop", input: str = "reference") -> Any:
    """python-control systems of ``params``, for
    :meth:`Parameters.to_control <symbolic_friction.Parameters.to_control>`.

    Parameters
    ----------
    params : Parameters
    kind : {"closed_loop", "plant_controller"}, keyword-only
        ``"closed_loop"``: a ``control.StateSpace`` named ``closed_loop``, the linear
        part of eq. (xDot) (friction removed), ``ẋ = A x + B w``, ``y = C x``, with the
        paper's ``A`` (the floats nearest its exact entries; :func:`closed_loop_matrices`
        gives them exactly), states ``sigma, phi, v`` (eq. CoC), output ``y``, the
        position, ``C = (-1/k_i, 0, 0)``; its poles are the roots of
        ``s³ + k_v s² + k_p s + k_i``.  ``f_c``, ``f_s`` and a reset do not enter.
        ``"plant_controller"``: ``(plant, controller)``, ``control.TransferFunction``
        ``1/(m s² + α_v s)`` (input ``u``, output ``y``) and ``(k̄_d s² + k̄_p s + k̄_i)/s``
        (input ``e``, output ``u``), from ``params.physical`` if known, else with
        ``m = 1``, ``α_v = 0`` and the normalised gains; :func:`from_control` reads them
        back, and ``control.feedback(plant, controller)`` is the disturbance loop in force units.
    input : {"reference", "disturbance"}, keyword-only
        The closed loop's input.  ``"reference"`` (input ``r``): a position setpoint,
        ``B = (0, k_i, k_p)``, the derivative acting on the measured velocity, so a
        step from rest takes no derivative kick, as in
        :func:`~symbolic_friction.step_response`; the states are the paper's ``x``
        with the position counted from 0, ``x - (k_i r, k_p r, 0)``, and
        ``y/r = (k_p s + k_i)/(s³ + k_v s² + k_p s + k_i)``.  ``"disturbance"``
        (input ``d``): a force on the mass divided by ``m``, in the units of ``f_c``
        (friction is ``d = -f_c SGN(v)``, eq. xDot's ``-b SGN(v)``), ``B = (0, 0, 1)``,
        ``y/d = s/(s³ + k_v s² + k_p s + k_i)``.

    Returns
    -------
    control.StateSpace or tuple of control.TransferFunction

    Raises
    ------
    ParameterError
        If ``kind`` or ``input`` is not one of the above, or a value is outside float range.
    ImportError
        If python-control is not installed.

    Examples
    --------
    >>> import control
    >>> from symbolic_friction import Parameters
    >>> loop = to_control(Parameters.table_i("b"), input="disturbance")
    >>> loop.nstates, loop.input_labels, loop.output_labels
    (3, ['d'], ['y'])
    >>> round(float(control.dcgain(loop)), 12)  # the integrator rejects a constant force
    0.0
    """
    if kind not in KINDS:
        raise ParameterError(f"kind must be one of {', '.join(KINDS)}; got {kind!r}")
    if input not in INPUTS:
        raise ParameterError(f"input must be one of {', '.join(INPUTS)}; got {input!r}")
    ct = control_module()
    if kind == "closed_loop":
        A, B, C, D = closed_loop_matrices(params, input=input)
        return ct.ss([[_float(a, "A") for a in row] for row in A], [[_float(b, "B")] for b in B],
                     [[_float(c, "C") for c in C]], [[_float(D, "D")]],
                     states=["sigma", "phi", "v"], inputs=["r" if input == "reference" else "d"], outputs=["y"],
                     name="closed_loop")
    physical = params.physical
    if physical is None:
        m, alpha_v, k_p_bar, k_i_bar, k_d_bar = Fraction(1), Fraction(0), params.k_p, params.k_i, params.k_v
    else:
        m, alpha_v = physical.m, physical.alpha_v
        k_p_bar, k_i_bar, k_d_bar = physical.k_p_bar, physical.k_i_bar, physical.k_d_bar
    plant = ct.tf([1.0], [_float(m, "m"), _float(alpha_v, "alpha_v"), 0.0], inputs=["u"], outputs=["y"], name="plant")
    controller = ct.tf([_float(k_d_bar, "k_d_bar"), _float(k_p_bar, "k_p_bar"), _float(k_i_bar, "k_i_bar")], [1.0, 0.0],
                       inputs=["e"], outputs=["u"], name="controller")
    return plant, controller
