"""Gain maps: Proposition 1's overshoot bound κ (eq. stabState) over a grid or a random sample of gains.

A map is described by a :class:`MapSpec`: one :class:`Axis` per quantity,
either the normalised gains of §II-A (``k_p``, ``k_i``, ``k_v``, ``f_c`` and
optionally the static level ``f_s``) or the physical ones (``m``, ``k̄_p``,
``k̄_i``, ``k̄_d``, ``α_v``, ``f̄_c``, optionally ``f̄_s``).  An axis is a fixed
value or a range, linear or logarithmic.  A grid takes the product of the
ranges; a sample draws every range independently (uniformly, or uniformly in
the logarithm), seeded per chunk so that any chunk can be recomputed alone.

Every point is an exact rational gain set.  Linear grid points are exact
(``lo + (hi − lo)·j/(n − 1)``); logarithmic grid points and sampled points are
rounded to :data:`SAMPLE_DIGITS` significant decimal digits, so the
certificate is for the short decimal the dataset reports.

For each point (:func:`evaluate_point`):

* Assumption 1 (``k_i > 0``, ``k_p > 0``, ``k_v·k_p > k_i``); a point outside
  it is marked, not an error;
* the closed-form certificate of Lemma 3
  (:func:`~.._certify.closed_form.closed_form_certificate`), whose status is
  decided by the exact verifier (:func:`~.._certify.verify.verify_certificate`)
  alone; κ is the certificate's decimal bound, reported as the smallest
  float not below it (so the float is still an upper bound);
* optionally the SDP's tightest κ (:func:`~.._certify.pipeline.certify` with ``search="sdp"``);
* optionally the worst overshoot that the cross-check's adversary
  (:func:`~.._crosscheck._overshoot.search_overshoot`) finds on a small budget,
  and the tightness ``worst/κ`` (found, never proved);
* with ``f_s``: the symmetric hunting cycles found and those proved in arb
  balls (:func:`~.._certify.hunting_proof.prove_cycle`).

κ and its certificate are for the paper's model (``f_s = f_c``) with the
point's gains; ``f_s`` only enters the hunting columns.

:mod:`.gainmap_run` runs a spec in chunks on any executor and writes the dataset.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Mapping

import numpy as np

from .._certify.closed_form import DEFAULT_MU
from .._infra.errors import ParameterError
from .._infra.rational import format_rational, short_rational, to_rational

__all__ = [
    "Axis", "MapSpec", "parse_axis", "map_spec", "evaluate_point", "evaluate_chunk", "chunk_gains", "normalised",
    "NORMALISED", "PHYSICAL", "STATUS", "MAX_POINTS", "SAMPLE_DIGITS",
]

NORMALISED: tuple[str, ...] = ("k_p", "k_i", "k_v", "f_c", "f_s")
PHYSICAL: tuple[str, ...] = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar", "f_s_bar")
_REQUIRED = {False: ("k_p", "k_i", "k_v"), True: ("m", "k_p_bar", "k_i_bar", "k_d_bar", "f_c_bar")}
_DEFAULTS = {"f_c": Fraction(1), "alpha_v": Fraction(0)}
STATUS: tuple[str, ...] = ("proved", "not_proved", "outside_assumption_1")
"""Status codes of a point (its index): the closed-form certificate proved, refused, or Assumption 1 fails."""
MAX_POINTS = 10**7
"""Most points a map may have (checked before anything is allocated)."""
MAX_CHUNK = 10**6
SAMPLE_DIGITS = 10
"""Significant decimal digits of logarithmic grid points and of sampled points."""
MAX_ADVERSARY = 100_000
MAX_TIGHT = 600.0
"""Most seconds per point for the tight bound (``--tight``)."""
_SCALES = ("lin", "log")


@dataclass(frozen=True)
class Axis:
    """One quantity of a map: a fixed value (``lo == hi``) or a range with ``n`` grid points.

    Attributes
    ----------
    name : str
        One of :data:`NORMALISED` or :data:`PHYSICAL`.
    lo, hi : Fraction
        The range, exact; ``lo ≤ hi``.
    n : int
        Grid points of a range (``≥ 2``); ``1`` for a fixed value, and for a
        range of a random sample, which draws its own points.
    scale : {"lin", "log"}
        Spacing of the grid, or the law of the draw (uniform in the value or in its logarithm).
    """

    name: str
    lo: Fraction
    hi: Fraction
    n: int = 1
    scale: str = "lin"

    def __post_init__(self) -> None:
        if self.name not in NORMALISED + PHYSICAL:
            raise ParameterError(f"unknown map axis {self.name!r}; known: {', '.join(NORMALISED + PHYSICAL)}")
        object.__setattr__(self, "lo", to_rational(self.lo, name=self.name))
        object.__setattr__(self, "hi", to_rational(self.hi, name=self.name))
        if not self.lo <= self.hi:
            raise ParameterError(f"{self.name}: a range needs lo ≤ hi; got {short_rational(self.lo)}:{short_rational(self.hi)}")
        if self.scale not in _SCALES:
            raise ParameterError(f"{self.name}: the scale must be 'lin' or 'log'; got {self.scale!r}")
        if isinstance(self.n, bool) or not isinstance(self.n, int) or not 1 <= self.n <= MAX_POINTS:
            raise ParameterError(f"{self.name}: the number of grid points must be an integer in 1..{MAX_POINTS}; got {self.n!r}")
        for end in (self.lo, self.hi):
            try:
                float(end)
            except OverflowError:
                raise ParameterError(f"{self.name} = {short_rational(end)} is beyond the range of floating point") from None
        if self.scale == "log" and not (self.lo > 0 and float(self.lo) > 0.0):
            raise ParameterError(f"{self.name}: a log range needs 0 < lo (a positive float); got lo = {short_rational(self.lo)}")

    @property
    def ranged(self) -> bool:
        return self.lo != self.hi

    def value(self, j: int) -> Fraction:
        """Grid point ``j`` of ``0 … n−1`` (exact for ``lin``; :data:`SAMPLE_DIGITS` digits inside a ``log`` range)."""
        if self.n == 1 or j == 0:
            return self.lo
        if j == self.n - 1:
            return self.hi
        if self.scale == "lin":
            return self.lo + (self.hi - self.lo) * Fraction(j, self.n - 1)
        return self._log(j / (self.n - 1))

    def draw(self, u: np.ndarray) -> list[Fraction]:
        """The points for uniform numbers ``u ∈ [0, 1)`` (a random sample), exact and inside ``[lo, hi]``."""
        if not self.ranged:
            return [self.lo] * len(u)
        if self.scale == "lin":
            unit = 10**SAMPLE_DIGITS
            width = self.hi - self.lo
            return [self.lo + width * Fraction(int(k), unit) for k in np.rint(u * unit).astype(np.int64)]
        return [self._log(float(t)) for t in u]

    def _log(self, t: float) -> Fraction:
        lo, hi = float(self.lo), float(self.hi)
        x = math.exp(math.log(lo) + t * (math.log(hi) - math.log(lo)))
        return min(max(Fraction(f"{x:.{SAMPLE_DIGITS}g}"), self.lo), self.hi)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "lo": format_rational(self.lo), "hi": format_rational(self.hi), "n": self.n,
                "scale": self.scale}


def parse_axis(name: str, text: str, *, sample: bool = False) -> Axis:
    """An axis from ``"6.4"`` (fixed), ``"LO:HI:N"`` or ``"LO:HI:N:log"`` (a grid), ``"LO:HI[:log]"`` (a sample).

    Raises
    ------
    ParameterError
        Naming the axis and the text, for anything else.

    Examples
    --------
    >>> parse_axis("k_p", "0.1:10:5:log").value(2)
    Fraction(1, 1)
    >>> parse_axis("k_v", "6.4").lo
    Fraction(32, 5)
    """
    flag = "--" + name.replace("_", "-")
    if not isinstance(text, str) or len(text) > 400:
        raise ParameterError(f"{flag} must be a value or LO:HI[:N][:lin|log] of at most 400 characters")
    parts = [p.strip() for p in text.split(":")]
    scale = "lin"
    if len(parts) > 1 and parts[-1].lower() in _SCALES:
        scale = parts.pop().lower()
    if len(parts) == 1:
        if scale != "lin" and len(text.split(":")) > 1:
            raise ParameterError(f"{flag}: a scale needs a range LO:HI; got {text!r}")
        return Axis(name, to_rational(parts[0], name=flag), to_rational(parts[0], name=flag))
    if len(parts) not in (2, 3):
        raise ParameterError(f"{flag} must be a value, LO:HI:N[:log] (grid) or LO:HI[:log] (--sample); got {text!r}")
    lo, hi = (to_rational(p, name=flag) for p in parts[:2])
    if sample:
        if len(parts) == 3:
            raise ParameterError(f"{flag}: a random sample draws its own points; give LO:HI[:log] without N; got {text!r}")
        return Axis(name, lo, hi, 1, scale)
    if len(parts) == 2:
        raise ParameterError(f"{flag}: a grid range needs its number of points, LO:HI:N[:log]; got {text!r}")
    try:
        n = int(parts[2])
    except ValueError:
        raise ParameterError(f"{flag}: the number of points must be an integer; got {parts[2]!r}") from None
    if lo == hi:
        raise ParameterError(f"{flag}: a range needs lo < hi; got {text!r} (give one value for a fixed {name})")
    if n < 2:
        raise ParameterError(f"{flag}: a grid range needs at least 2 points; got {n}")
    return Axis(name, lo, hi, n, scale)


@dataclass(frozen=True)
class MapSpec:
    """What a map evaluates: axes, grid or sample, and which columns.

    Attributes
    ----------
    axes : tuple of Axis
        All normalised or all physical; ``f_c`` (normalised) defaults to 1 and ``α_v`` to 0.
    sample : int
        ``0`` for the grid of the ranges, else the number of random points.
    seed : int
        Seed of a sample (chunk ``c`` draws from ``numpy.random.default_rng([seed, c])``) and of the adversary.
    sdp : bool
        Also the SDP's tightest κ (about 3 ms a point).
    tight : float
        Seconds per point for the tight bound of default ``certify`` (the
        columns ``kappa_tight``, ``kappa_lin`` and ``tight_ratio``; 0: off).
    adversary : int
        Trajectory budget of the overshoot adversary per point (0: off).
    chunk : int
        Points per chunk (the unit written to disk and sent to a worker).
    mu : Fraction
        Margin of the closed-form constants.
    """

    axes: tuple[Axis, ...]
    sample: int = 0
    seed: int = 0
    sdp: bool = False
    tight: float = 0.0
    adversary: int = 0
    chunk: int = 1000
    mu: Fraction = field(default=DEFAULT_MU)

    def __post_init__(self) -> None:
        axes = tuple(self.axes)
        object.__setattr__(self, "axes", axes)
        names = [a.name for a in axes]
        if len(set(names)) != len(names):
            raise ParameterError(f"an axis is given twice: {', '.join(names)}")
        physical = any(n in PHYSICAL for n in names)
        if physical and any(n in NORMALISED for n in names):
            raise ParameterError(
                "give either normalised gains (k_p, k_i, k_v, f_c, f_s) or physical parameters "
                f"(m, k_p_bar, k_i_bar, k_d_bar, alpha_v, f_c_bar, f_s_bar), not both; got {', '.join(names)}"
            )
        missing = [n for n in _REQUIRED[physical] if n not in names]
        if missing:
            raise ParameterError(f"a {'physical' if physical else 'normalised'} map needs {', '.join(missing)}")
        for name in (n for n in ("f_c", "alpha_v") if n in (PHYSICAL if physical else NORMALISED) and n not in names):
            axes += (Axis(name, _DEFAULTS[name], _DEFAULTS[name]),)
        object.__setattr__(self, "axes", tuple(sorted(axes, key=lambda a: (NORMALISED + PHYSICAL).index(a.name))))
        self._check_values(physical)
        for name, value, lo in (("sample", self.sample, 0), ("seed", self.seed, 0), ("adversary", self.adversary, 0),
                                ("chunk", self.chunk, 1)):
            if isinstance(value, bool) or not isinstance(value, int) or value < lo:
                raise ParameterError(f"{name} must be an integer ≥ {lo}; got {value!r}")
        if self.adversary > MAX_ADVERSARY:
            raise ParameterError(f"adversary budget must be at most {MAX_ADVERSARY} trajectories a point; got {self.adversary}")
        if self.chunk > MAX_CHUNK:
            raise ParameterError(f"chunk must be at most {MAX_CHUNK} points; got {self.chunk}")
        if isinstance(self.tight, bool) or not isinstance(self.tight, (int, float)) or not 0 <= self.tight <= MAX_TIGHT:
            raise ParameterError(f"tight must be seconds per point in [0, {MAX_TIGHT:g}]; got {self.tight!r}")
        object.__setattr__(self, "tight", float(self.tight))
        object.__setattr__(self, "mu", to_rational(self.mu, name="mu"))
        if not self.mu > 0:
            raise ParameterError(f"the margin mu must be positive; got {short_rational(self.mu)}")
        if self.sample:
            if self.sample > MAX_POINTS:
                raise ParameterError(f"a map has at most {MAX_POINTS:,} points; --sample {self.sample:,} asks for more")
            grid = [a.name for a in axes if a.n > 1]
            if grid:
                raise ParameterError(f"a random sample draws its own points; {', '.join(grid)} has a number of grid points")
        else:
            points = math.prod(a.n for a in self.axes)
            if points > MAX_POINTS:
                shape = " × ".join(f"{a.n} ({a.name})" for a in self.axes if a.n > 1)
                raise ParameterError(f"a map has at most {MAX_POINTS:,} points; the grid {shape} has {points:,}")
            flat = [a.name for a in self.axes if a.ranged and a.n < 2]
            if flat:
                raise ParameterError(f"a grid range needs its number of points (LO:HI:N); {', '.join(flat)} has none")

    def _check_values(self, physical: bool) -> None:
        """Ranges that cannot give a model at all are bad input (Assumption 1 failing is not: it is marked)."""
        ax = {a.name: a for a in self.axes}
        positive = ("m", "f_c_bar") if physical else ("f_c",)
        for name in positive:
            if not ax[name].lo > 0:
                raise ParameterError(f"{name} must be positive over its range; got lo = {short_rational(ax[name].lo)}")
        if physical and ax["alpha_v"].lo < 0:
            raise ParameterError(f"alpha_v must be ≥ 0 over its range; got lo = {short_rational(ax['alpha_v'].lo)}")
        s, c = ("f_s_bar", "f_c_bar") if physical else ("f_s", "f_c")
        if s in ax and not ax[s].lo >= ax[c].hi:
            raise ParameterError(
                f"static friction needs {s} ≥ {c} at every point; got {s} from {short_rational(ax[s].lo)} "
                f"below {c} up to {short_rational(ax[c].hi)}"
            )

    # -- derived ---------------------------------------------------------------------------------
    @property
    def physical(self) -> bool:
        return self.axes[0].name in PHYSICAL

    @property
    def ranged(self) -> tuple[Axis, ...]:
        """The axes that vary (a grid's dimensions, in order)."""
        return tuple(a for a in self.axes if a.ranged)

    @property
    def shape(self) -> tuple[int, ...]:
        return (self.sample,) if self.sample else tuple(a.n for a in self.ranged)

    @property
    def points(self) -> int:
        return self.sample if self.sample else math.prod(a.n for a in self.axes)

    @property
    def chunks(self) -> int:
        return -(-self.points // self.chunk)

    @property
    def hunting(self) -> bool:
        return any(a.name in ("f_s", "f_s_bar") for a in self.axes)

    def axis(self, name: str) -> Axis:
        for a in self.axes:
            if a.name == name:
                return a
        raise ParameterError(f"the map has no axis {name!r}; it has {', '.join(a.name for a in self.axes)}")

    def columns(self) -> tuple[tuple[str, str], ...]:
        """``(name, numpy dtype)`` of every column of the dataset, in order."""
        cols = [(a.name, "f8") for a in self.axes]
        if self.physical:
            cols += [(n, "f8") for n in ("k_p", "k_i", "k_v", "f_c") + (("f_s",) if self.hunting else ())]
        cols += [("status", "i1"), ("kappa", "f8")]
        if self.sdp:
            cols.append(("kappa_sdp", "f8"))
        if self.tight:
            cols += [("kappa_tight", "f8"), ("kappa_lin", "f8"), ("tight_ratio", "f8"), ("tight_template", "i1")]
        if self.adversary:
            cols += [("worst_overshoot", "f8"), ("tightness", "f8")]
        if self.hunting:
            cols += [("hunting_found", "i2"), ("hunting_proved", "i2")]
        return tuple(cols)

    def to_dict(self) -> dict[str, Any]:
        out = {"axes": [a.to_dict() for a in self.axes], "sample": self.sample, "seed": self.seed, "sdp": self.sdp,
               "adversary": self.adversary, "chunk": self.chunk, "mu": format_rational(self.mu),
               "sample_digits": SAMPLE_DIGITS}
        if self.tight:  # only when on: a map without it keeps its digest, so its chunks stay reusable
            out["tight"] = self.tight
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "MapSpec":
        """The spec :meth:`to_dict` wrote (e.g. in a map's manifest).

        Raises
        ------
        ParameterError
            If ``data`` is not such a mapping.
        """
        try:
            axes = tuple(Axis(a["name"], a["lo"], a["hi"], a["n"], a["scale"]) for a in data["axes"])
            return cls(axes, sample=data["sample"], seed=data["seed"], sdp=data["sdp"], adversary=data["adversary"],
                       chunk=data["chunk"], mu=data["mu"], tight=data.get("tight", 0.0))
        except (KeyError, TypeError) as exc:
            raise ParameterError(f"not a gain-map spec: {type(exc).__name__} {exc}") from None

    def digest(self) -> str:
        """SHA-256 of the canonical JSON of :meth:`to_dict`: two runs may share chunks only if this agrees."""
        return hashlib.sha256(json.dumps(self.to_dict(), sort_keys=True).encode()).hexdigest()


def map_spec(values: Mapping[str, str | Axis], *, sample: int = 0, **options: Any) -> MapSpec:
    """A :class:`MapSpec` from ``{"k_p": "0.1:10:50:log", "k_i": "1:20:40", "k_v": "6.4"}`` (texts as :func:`parse_axis`)."""
    axes = tuple(v if isinstance(v, Axis) else parse_axis(k, v, sample=bool(sample)) for k, v in values.items())
    return MapSpec(axes, sample=sample, **options)


def normalised(v: Mapping[str, Any]) -> dict[str, Any]:
    """The normalised ``k_p, k_i, k_v, f_c`` (and ``f_s``) of §II-A from a point's values.

    ``k_p = k̄_p/m``, ``k_i = k̄_i/m``, ``k_v = (k̄_d + α_v)/m``, ``f_c = f̄_c/m``,
    ``f_s = f̄_s/m`` (as :meth:`~symbolic_friction.Parameters.from_physical`, which
    a test binds this to); plain arithmetic, so Fractions and float arrays both work.
    """
    if "m" not in v:
        return {n: v[n] for n in NORMALISED if n in v}
    m = v["m"]
    out = {"k_p": v["k_p_bar"] / m, "k_i": v["k_i_bar"] / m, "k_v": (v["k_d_bar"] + v["alpha_v"]) / m,
           "f_c": v["f_c_bar"] / m}
    if "f_s_bar" in v:
        out["f_s"] = v["f_s_bar"] / m
    return out


def chunk_gains(spec: MapSpec, c: int) -> list[dict[str, Fraction]]:
    """The exact values of every point of chunk ``c`` (each a mapping axis name → value)."""
    lo, hi = c * spec.chunk, min((c + 1) * spec.chunk, spec.points)
    if not 0 <= lo < hi:
        raise ParameterError(f"chunk {c} is outside 0..{spec.chunks - 1}")
    size = hi - lo
    columns: dict[str, list[Fraction]] = {}
    if spec.sample:
        rng = np.random.default_rng([spec.seed, c])
        for a in spec.axes:
            columns[a.name] = a.draw(rng.random(size)) if a.ranged else [a.lo] * size
    else:
        ranged = spec.ranged
        index = np.unravel_index(np.arange(lo, hi), spec.shape) if ranged else ()
        for a in spec.axes:
            if a.ranged:
                # each grid value is computed once per chunk, however often the chunk repeats it
                unique, inverse = np.unique(index[ranged.index(a)], return_inverse=True)
                vals = [a.value(k) for k in unique.tolist()]
                columns[a.name] = [vals[i] for i in inverse.tolist()]
            else:
                columns[a.name] = [a.lo] * size
    names = list(columns)
    return [dict(zip(names, row)) for row in zip(*columns.values())]


def evaluate_point(spec: MapSpec, values: Mapping[str, Fraction]) -> dict[str, float | int]:
    """Every column of one point (see the module docstring); ``NaN`` or ``-1`` where a column does not apply."""
    from .._certify.verify import verify_certificate
    from .._infra.errors import SymbolicFrictionError
    from .._certify.closed_form import closed_form_certificate
    from .gainmap_point import float_up, hunting_cycles, worst_overshoot

    g = normalised(values)
    row: dict[str, float | int] = {n: float(v) for n, v in values.items()}
    row.update({n: float(v) for n, v in g.items()})
    row.update(status=STATUS.index("outside_assumption_1"), kappa=math.nan)
    nan_cols = {"kappa_sdp": spec.sdp, "worst_overshoot": spec.adversary, "tightness": spec.adversary,
                "kappa_tight": spec.tight, "kappa_lin": spec.tight, "tight_ratio": spec.tight}
    row.update({n: math.nan for n, on in nan_cols.items() if on})
    if spec.tight:
        row["tight_template"] = 0
    if spec.hunting:
        row.update(hunting_found=-1, hunting_proved=-1)
    k_p, k_i, k_v, f_c = g["k_p"], g["k_i"], g["k_v"], g["f_c"]
    from .._infra.errors import AssumptionError
    from .._model.parameters import Parameters

    try:
        params = Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c)
    except AssumptionError:  # the spec keeps f_c > 0, so this is Assumption 1: marked, nothing to certify
        return row
    try:
        cert = closed_form_certificate(params, mode="tightest", margin=spec.mu)
        proved = verify_certificate(cert).proved
    except (SymbolicFrictionError, ValueError):
        proved = False
    row["status"] = STATUS.index("proved" if proved else "not_proved")
    if proved:
        row["kappa"] = float_up(cert.overshoot_bound)
    if spec.sdp:
        from .._certify.pipeline import certify

        try:
            row["kappa_sdp"] = float_up(certify(params, mode="tightest", search="sdp").overshoot_bound)
        except SymbolicFrictionError:
            pass
    if spec.tight:
        from .gainmap_point import tight_kappa

        row["kappa_tight"], row["kappa_lin"], row["tight_template"] = tight_kappa(params, budget=spec.tight)
        row["tight_ratio"] = row["kappa_tight"] / row["kappa_lin"]  # NaN where either is
    if spec.adversary:
        worst = worst_overshoot(params, budget=spec.adversary, seed=spec.seed)
        row["worst_overshoot"] = worst
        row["tightness"] = worst / row["kappa"] if proved else math.nan
    if spec.hunting and g["f_s"] > f_c:
        row["hunting_found"], row["hunting_proved"] = hunting_cycles(Parameters(k_p=k_p, k_i=k_i, k_v=k_v, f_c=f_c, f_s=g["f_s"]))
    elif spec.hunting:
        row["hunting_found"] = row["hunting_proved"] = 0  # f_s = f_c: Proposition 1, no cycle
    return row


def evaluate_chunk(spec: MapSpec, c: int) -> dict[str, np.ndarray]:
    """The columns of chunk ``c`` (module level, so process pools and dask workers can run it)."""
    rows = [evaluate_point(spec, v) for v in chunk_gains(spec, c)]
    return {name: np.array([r[name] for r in rows], dtype=dtype) for name, dtype in spec.columns()}
