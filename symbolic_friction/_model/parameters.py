"""Normalised PID and friction parameters (paper §II-A, eq. (basic)) and
Assumption 1.

The paper normalises the physical model by the mass ``m``:

.. math::

    k_p = \\bar k_p/m,\\quad k_v = (\\bar k_d + \\alpha_v)/m,\\quad
    k_i = \\bar k_i/m,\\quad f_c = \\bar f_c/m,

and every result holds under **Assumption 1**: ``k_i > 0``, ``k_p > 0`` and
``k_v k_p > k_i`` (with ``f_c > 0`` from the friction model).  The
parameters are held as exact :class:`~fractions.Fraction` values; floats appear
only at the numerical boundary (:meth:`Parameters.as_floats`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from fractions import Fraction
from typing import ClassVar

from .._infra.errors import AssumptionError
from .._infra.rational import format_integer, format_rational, short_rational, to_rational

__all__ = ["Parameters", "PhysicalParameters", "TABLE_I"]


def _float(q: Fraction, name: str) -> float:
    from .._infra.errors import ParameterError

    try:
        value = float(q)
    except OverflowError:
        value = float("inf")
    if value == 0.0 or value == float("inf"):
        raise ParameterError(
            f"{name} = {_fmt(q)} is outside the range of floating point "
            "(about 1e-308 to 1e308) that the numerical search and the simulators use"
        )
    return value


def _repr(self) -> str:
    """The dataclass repr, with an integer beyond Python's 4300-digit ``str`` limit written out all the same."""
    def value(v: object) -> str:
        try:
            return repr(v)
        except ValueError:  # Fraction(10**5000): repr() refuses, the exact digits are still there
            return f"Fraction({format_integer(v.numerator)}, {format_integer(v.denominator)})"  # type: ignore[attr-defined]

    inner = ", ".join(f"{f.name}={value(getattr(self, f.name))}" for f in fields(self) if f.repr)
    return f"{type(self).__name__}({inner})"


def _fmt(q: Fraction) -> str:
    # messages stay one readable line: a 300-digit value is shown as ≈1e-300
    return short_rational(q)


@dataclass(frozen=True)
class PhysicalParameters:
    """Physical mass, PID gains and friction levels (paper §II-A), held exactly.

    Built by :meth:`Parameters.from_physical` and kept in
    :attr:`Parameters.physical`.  The normalisation is
    ``k_p = k̄_p/m``, ``k_i = k̄_i/m``, ``k_v = (k̄_d + α_v)/m``, ``f_c = f̄_c/m``.

    Raises
    ------
    InvalidNumberError, NonFiniteError
        If a value is not a finite number.
    AssumptionError
        If ``m ≤ 0``, ``alpha_v < 0``, ``f_c_bar ≤ 0`` or ``f_s_bar < f_c_bar``.

    Examples
    --------
    >>> PhysicalParameters(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2).normalised()["k_v"]
    Fraction(32, 5)
    """

    m: Fraction
    k_p_bar: Fraction
    k_i_bar: Fraction
    k_d_bar: Fraction
    alpha_v: Fraction = field(default=Fraction(0))
    f_c_bar: Fraction = field(default=Fraction(1))
    f_s_bar: Fraction | None = field(default=None)

    NAMES: ClassVar[tuple[str, ...]] = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar")
    __repr__ = _repr

    def __post_init__(self) -> None:
        for name in self.NAMES:
            object.__setattr__(self, name, to_rational(getattr(self, name), name=name))
        if self.f_s_bar is not None:
            object.__setattr__(self, "f_s_bar", to_rational(self.f_s_bar, name="f_s_bar"))
        if not self.m > 0:
            raise AssumptionError(f"the mass needs m > 0; got m = {_fmt(self.m)}")
        if self.alpha_v < 0:
            raise AssumptionError(f"the viscous coefficient needs alpha_v ≥ 0; got alpha_v = {_fmt(self.alpha_v)}")
        if not self.f_c_bar > 0:
            raise AssumptionError(f"the Coulomb force needs f_c_bar > 0; got f_c_bar = {_fmt(self.f_c_bar)}")
        if self.f_s_bar is not None and not self.f_s_bar >= self.f_c_bar:
            raise AssumptionError(
                f"the static force needs f_s_bar ≥ f_c_bar; got f_s_bar = {_fmt(self.f_s_bar)} < f_c_bar = {_fmt(self.f_c_bar)}"
            )

    def normalised(self) -> dict[str, Fraction]:
        """``{"k_p": k̄_p/m, "k_i": k̄_i/m, "k_v": (k̄_d + α_v)/m, "f_c": f̄_c/m}`` (paper §II-A, exact)."""
        m = self.m
        return {"k_p": self.k_p_bar / m, "k_i": self.k_i_bar / m, "k_v": (self.k_d_bar + self.alpha_v) / m,
                "f_c": self.f_c_bar / m}

    def as_dict(self) -> dict[str, Fraction]:
        """The six values a certificate records (``m``, ``k_p_bar``, ``k_i_bar``, ``k_d_bar``, ``alpha_v``, ``f_c_bar``)."""
        return {name: getattr(self, name) for name in self.NAMES}


@dataclass(frozen=True)
class Parameters:
    """Normalised gains ``(k_p, k_i, k_v)``, Coulomb level ``f_c`` and static level ``f_s``.

    Parameters
    ----------
    k_p, k_i, k_v, f_c : int, Fraction, sympy Rational, str or float
        Normalised proportional, integral and velocity gains and Coulomb
        friction level.  Converted exactly with :func:`to_rational` (a float
        through its decimal ``repr``).
    f_s : number or None, default None (``f_s = f_c``)
        Normalised static friction level, ``f_s ≥ f_c``: the mass at rest
        sticks while ``|k_i e_i + k_p s| ≤ f_s`` and slips with kinetic
        friction ``f_c``.  ``f_s = f_c`` is the paper's model (eq. basic);
        ``f_s > f_c`` is the stiction its conclusion names as future work
        (see :mod:`symbolic_friction._hunting`).  A gain set with
        ``f_s = f_c`` compares, hashes and prints exactly as one without it.
    reset_dwell : number or None, default None (plain PID)
        Reset PID (beyond the paper; the package's own law, the idea of
        Bisoffi et al., *To stick or to slip*, Annu. Rev. Control 49, 2020):
        during a stick (``v = 0``, ``|φ| ≤ f_s``) while ``φ`` is short of
        ``f_c·sign(σ)``, the integrator ``e_i`` jumps so that
        ``φ⁺ = f_c·sign(σ)``, at most once per ``reset_dwell > 0`` time units (the dwell timer that excludes
        Zeno solutions).  ``V`` of eq. (lyapLikeV) is unchanged by a jump
        (:mod:`symbolic_friction._model.reset`).  ``None`` is the paper's PID,
        which compares, hashes and prints exactly as before.
    physical : PhysicalParameters or None, default None
        The physical values the gains were normalised from (set by
        :meth:`from_physical`); checked to normalise to the gains, and
        ignored by ``==`` and ``hash`` (the dynamics are the gains').

    Raises
    ------
    InvalidNumberError, NonFiniteError
        If a value is not a finite number.
    AssumptionError
        If Assumption 1 (``k_i > 0``, ``k_p > 0``, ``k_v k_p > k_i``),
        ``f_c > 0``, ``f_s ≥ f_c`` or ``reset_dwell > 0`` is violated; the
        message gives the numbers.

    Examples
    --------
    >>> p = Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1)
    >>> p.k_v
    Fraction(32, 5)
    >>> p.c
    Fraction(152, 5)
    """

    k_p: Fraction
    k_i: Fraction
    k_v: Fraction
    f_c: Fraction = field(default=Fraction(1))
    f_s: Fraction = field(default=None)  # type: ignore[assignment]  # None: f_s = f_c
    reset_dwell: Fraction | None = field(default=None)
    # the physical values the gains were normalised from (from_physical); the dynamics are the gains',
    # so two gain sets compare and hash alike whether or not they remember where they came from
    physical: "PhysicalParameters | None" = field(default=None, compare=False, repr=False)

    _names: ClassVar[tuple[str, ...]] = ("k_p", "k_i", "k_v", "f_c")
    __repr__ = _repr

    def __post_init__(self) -> None:
        for name in self._names:
            object.__setattr__(self, name, to_rational(getattr(self, name), name=name))
        k_p, k_i, k_v, f_c = self.k_p, self.k_i, self.k_v, self.f_c
        if not k_i > 0:
            raise AssumptionError(f"Assumption 1 needs k_i > 0; got k_i = {_fmt(k_i)}")
        if not k_p > 0:
            raise AssumptionError(f"Assumption 1 needs k_p > 0; got k_p = {_fmt(k_p)}")
        if not k_v * k_p > k_i:
            raise AssumptionError(
                "Assumption 1 needs k_v·k_p > k_i; got "
                f"{_fmt(k_v * k_p)} ≤ {_fmt(k_i)} (k_v = {_fmt(k_v)}, k_p = {_fmt(k_p)}, k_i = {_fmt(k_i)})"
            )
        if not f_c > 0:
            raise AssumptionError(f"the Coulomb level needs f_c > 0; got f_c = {_fmt(f_c)}")
        f_s = f_c if self.f_s is None else to_rational(self.f_s, name="f_s")
        if not f_s >= f_c:
            raise AssumptionError(
                f"the static level needs f_s ≥ f_c; got f_s = {_fmt(f_s)} < f_c = {_fmt(f_c)}"
            )
        object.__setattr__(self, "f_s", f_s)
        if self.reset_dwell is not None:
            dwell = to_rational(self.reset_dwell, name="reset_dwell")
            if not dwell > 0:
                raise AssumptionError(
                    f"the reset's dwell time needs reset_dwell > 0 (it excludes Zeno solutions); got {_fmt(dwell)}"
                )
            object.__setattr__(self, "reset_dwell", dwell)
        if self.physical is not None:
            self._check_physical()

    def _check_physical(self) -> None:
        """The recorded physical values must normalise to the gains (paper §II-A)."""
        if not isinstance(self.physical, PhysicalParameters):
            raise AssumptionError(
                f"physical must be a PhysicalParameters (see Parameters.from_physical); got {type(self.physical).__name__}"
            )
        expected = self.physical.normalised()
        wrong = [f"{n} = {_fmt(getattr(self, n))} but the physical values give {_fmt(q)}"
                 for n, q in expected.items() if getattr(self, n) != q]
        if wrong:
            raise AssumptionError("the physical parameters do not normalise to the gains: " + "; ".join(wrong))

    def __hash__(self) -> int:
        # hashing four Fractions costs microseconds, and every simulation looks its gains up
        cached = self.__dict__.get("_hash")
        if cached is None:
            key = (self.k_p, self.k_i, self.k_v, self.f_c)
            if self.f_s != self.f_c:
                key += (self.f_s,)
            if self.reset_dwell is not None:
                key += ("reset", self.reset_dwell)
            cached = hash(key)
            object.__setattr__(self, "_hash", cached)
        return cached

    @classmethod
    def from_physical(
        cls,
        *,
        m: object,
        k_p_bar: object,
        k_i_bar: object,
        k_d_bar: object,
        alpha_v: object = 0,
        f_c_bar: object,
        f_s_bar: object = None,
    ) -> "Parameters":
        """Build normalised parameters from physical ones (paper §II-A).

        Parameters
        ----------
        m : number, keyword-only
            Mass, ``m > 0``.
        k_p_bar, k_i_bar, k_d_bar : number, keyword-only
            Physical PID gains.
        alpha_v : number, keyword-only
            Viscous friction coefficient, ``alpha_v >= 0`` (default 0).
        f_c_bar : number, keyword-only
            Coulomb friction force, ``f_c_bar > 0``.
        f_s_bar : number or None, keyword-only
            Static friction force, ``f_s_bar ≥ f_c_bar`` (default: ``f_c_bar``).

        Raises
        ------
        AssumptionError
            If ``m <= 0``, ``alpha_v < 0`` or the normalised gains violate
            Assumption 1 or ``f_c > 0``.

        Returns
        -------
        Parameters
            The normalised gains, with the physical values kept exactly in
            :attr:`physical` (:func:`~symbolic_friction.certify` records them in
            the certificate, whose verifier checks that they normalise).

        Examples
        --------
        >>> p = Parameters.from_physical(m=2, k_p_bar=6, k_i_bar=8, k_d_bar="12.3", alpha_v="0.5", f_c_bar=2)
        >>> p.k_v
        Fraction(32, 5)
        >>> p.physical.m, p.physical.k_d_bar
        (Fraction(2, 1), Fraction(123, 10))
        >>> p == Parameters(k_p=3, k_i=4, k_v="6.4", f_c=1)  # the same dynamics
        True
        """
        physical = PhysicalParameters(
            m=m, k_p_bar=k_p_bar, k_i_bar=k_i_bar, k_d_bar=k_d_bar, alpha_v=alpha_v, f_c_bar=f_c_bar, f_s_bar=f_s_bar
        )
        gains = physical.normalised()
        return cls(
            **gains,
            f_s=None if physical.f_s_bar is None else physical.f_s_bar / physical.m,
            physical=physical,
        )

    @classmethod
    def table_i(cls, case: str) -> "Parameters":
        """The paper's Table I gains, ``case`` ``"a"`` or ``"b"``, with ``f_c = 1``.

        >>> Parameters.table_i("b").k_p
        Fraction(33, 50)
        """
        try:
            return TABLE_I[case]
        except (KeyError, TypeError):  # TypeError: an unhashable case such as a list
            raise AssumptionError(f"Table I has cases 'a' and 'b'; got {case!r}") from None

    @property
    def c(self) -> Fraction:
        """Decrease rate ``c = 2(k_v k_p - k_i)`` of Lemma 2, item 2."""
        return 2 * (self.k_v * self.k_p - self.k_i)

    @property
    def stiction(self) -> bool:
        """``f_s > f_c``: static friction above the Coulomb level (the paper's model has ``f_s = f_c``)."""
        return self.f_s > self.f_c

    @property
    def rho(self) -> Fraction:
        """``ρ = (f_s - f_c)/f_c``: the stiction law lies in ``f_c SGN_ρ`` of Corollary 1 (eq. perturbed)."""
        return (self.f_s - self.f_c) / self.f_c

    @property
    def reset(self) -> bool:
        """Whether this is reset PID (``reset_dwell`` given) rather than the paper's PID."""
        return self.reset_dwell is not None

    def without_reset(self) -> "Parameters":
        """The same gains and friction with the paper's PID (no reset)."""
        if self.reset_dwell is None:
            return self
        return Parameters(k_p=self.k_p, k_i=self.k_i, k_v=self.k_v, f_c=self.f_c, f_s=self.f_s, physical=self.physical)

    def check_paper_model(self, what: str = "a stability certificate") -> None:
        """Refuse, naming ``what``, gains that are not the paper's model: ``f_s > f_c`` or reset PID.

        Proposition 1 and its certificates are about eq. (basic) with the
        paper's PID; with ``f_s > f_c`` the loop hunts, and reset PID is
        another (hybrid) closed loop.

        Raises
        ------
        ParameterError
            Naming the value that leaves the paper's model.
        """
        from .._infra.errors import ParameterError

        if self.stiction:
            raise ParameterError(
                f"{what} is for the paper's model f_s = f_c; got f_s = {_fmt(self.f_s)} > f_c = {_fmt(self.f_c)}: "
                "with static friction above Coulomb the loop hunts (symbolic-friction hunting)"
            )
        if self.reset_dwell is not None:
            raise ParameterError(
                f"{what} is for the paper's PID; got reset PID (reset_dwell = {_fmt(self.reset_dwell)}): "
                "its settling is certified by symbolic-friction settling"
            )

    @property
    def routh_margin(self) -> Fraction:
        """``k_v k_p / k_i``; Assumption 1 holds iff this exceeds 1."""
        return self.k_v * self.k_p / self.k_i

    def as_floats(self) -> tuple[float, float, float, float]:
        """``(k_p, k_i, k_v, f_c)`` as floats, for numerical code.

        Raises
        ------
        ParameterError
            If a value is beyond the range of float64 or so small it rounds to 0
            (numerical code would compute with inf or 0, not with the gain).
        """
        cached = self.__dict__.get("_floats")
        if cached is None:
            cached = tuple(_float(getattr(self, name), name) for name in self._names)
            object.__setattr__(self, "_floats", cached)
        return cached  # type: ignore[return-value]

    def as_strings(self) -> dict[str, str]:
        """The parameters as exact ``"p/q"`` strings (file format); ``f_s`` only when it differs from ``f_c``."""
        out = {name: format_rational(getattr(self, name)) for name in self._names}
        if self.stiction:
            out["f_s"] = format_rational(self.f_s)
        if self.reset_dwell is not None:
            out["reset_dwell"] = format_rational(self.reset_dwell)
        return out

    def __str__(self) -> str:
        names = (*self._names, "f_s") if self.stiction else self._names
        if self.reset_dwell is not None:
            names = (*names, "reset_dwell")
        inner = ", ".join(f"{k}={_fmt(getattr(self, k))}" for k in names)
        return f"Parameters({inner})"

    @classmethod
    def from_control(cls, plant: object, controller: object, *, f_c_bar: object, f_s_bar: object = None,
                     binary: bool = False, filter_tolerance: object = Fraction(1, 100)) -> "Parameters":
        """Gains from python-control's plant ``1/(m s² + α_v s)`` and PID ``k̄_p + k̄_i/s + k̄_d s`` (§II-A, eq. uPID).

        ``plant`` and ``controller`` are SISO continuous-time ``TransferFunction`` or
        ``StateSpace``; the controller may filter its derivative, ``k̄_d s/(τ s + 1)``, if
        ``τ·max|λ(A)| ≤ filter_tolerance`` (the filter is then dropped).  Coefficients are
        read exactly (floats by their shortest decimal, or their binary value if ``binary``),
        normalised exactly, and passed to :meth:`from_physical` with the physical Coulomb
        force ``f_c_bar`` (and static force ``f_s_bar``).  Needs ``symbolic-friction[control]``;
        details: :func:`symbolic_friction._model.python_control.from_control`.

        Raises
        ------
        ParameterError
            Naming what does not fit (type, MIMO, discrete time, order, zero, spring, mass, filter).

        Examples
        --------
        >>> import control
        >>> s = control.tf("s")
        >>> p = Parameters.from_control(1 / (2 * s**2 + 0.5 * s), 6 + 8 / s + 12.3 * s, f_c_bar=2)
        >>> p == Parameters.table_i("a"), p.physical.k_d_bar
        (True, Fraction(123, 10))
        """
        from .python_control import from_control

        return from_control(cls, plant, controller, f_c_bar=f_c_bar, f_s_bar=f_s_bar, binary=binary,
                            filter_tolerance=filter_tolerance)

    def to_control(self, *, kind: str = "closed_loop", input: str = "reference") -> object:
        """The friction-free closed loop of eq. (xDot) as a ``control.StateSpace``, or ``(plant, controller)``.

        ``kind="closed_loop"``: ``ẋ = A x + B w``, ``y = -σ/k_i`` (the position), the paper's
        ``A`` and ``x = (σ, φ, v)`` (eq. CoC); ``input`` ``"reference"`` (a position setpoint,
        ``B = (0, k_i, k_p)``) or ``"disturbance"`` (a force over ``m``, ``B = (0, 0, 1)``).
        ``kind="plant_controller"``: two ``TransferFunction``, ``1/(m s² + α_v s)`` and
        ``(k̄_d s² + k̄_p s + k̄_i)/s`` (physical values if known, else ``m = 1``).  Needs
        ``symbolic-friction[control]``; details: :func:`symbolic_friction._model.python_control.to_control`.

        Examples
        --------
        >>> loop = Parameters.table_i("a").to_control()
        >>> loop.A
        array([[ 0. ,  0. , -4. ],
               [ 1. ,  0. , -3. ],
               [ 0. ,  1. , -6.4]])
        >>> plant, pid = Parameters.table_i("b").to_control(kind="plant_controller")
        >>> Parameters.from_control(plant, pid, f_c_bar=1) == Parameters.table_i("b")
        True
        """
        from .python_control import to_control

        return to_control(self, kind=kind, input=input)

TABLE_I: dict[str, Parameters] = {
    "a": Parameters(k_v="6.4", k_p=3, k_i=4, f_c=1),
    "b": Parameters(k_v="1.5", k_p="0.66", k_i="0.08", f_c=1),
}
"""Table I of the paper: case (a) complex roots, case (b) three real roots."""
