"""Reading a scene file (TOML): exact numbers, tables with known keys, the gains, initial states, friction law and method of a :class:`~.scenes.Scene`, each error naming where it is."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from fractions import Fraction
from typing import Any

from .._infra.config import toml_syntax_count
from .._infra.errors import SceneError, SymbolicFrictionError
from .._model.parameters import Parameters
from .._infra.rational import format_rational, short_rational, shown, to_rational

FRICTION_LAWS = ("coulomb", "stribeck", "inflated")


MAX_STATES = 100_000
"""Most initial states in one scene."""
MAX_ARRAYS = MAX_STATES + 1_000
"""Most ``[`` (arrays and table headers) a scene's TOML may open: one per initial state, and a few for the rest."""


MAX_INTEGER_KNOB = 10_000_000
"""Largest integer method knob (``grid_points``, ``max_events`` …) a scene may set."""
MAX_SAMPLES = 1_000_000
"""Most sample times a scene may ask for per trajectory (a bound on memory, said in the error)."""
MAX_TOTAL_SAMPLES = 20_000_000
"""Most sample times over all trajectories of a scene (states × samples), a bound on memory."""


def _check_array_count(text: str) -> None:
    """Refuse a scene that opens more arrays than :data:`MAX_STATES` states need, before the TOML parser allocates them.

    Parsing a 2 MB list of states takes seconds and a million objects before :func:`_parse_states` can count them;
    the ``[`` outside strings and comments bound the arrays from above, so no scene the reader would accept is refused.
    """
    arrays = toml_syntax_count(text, "[", above=MAX_ARRAYS)
    if arrays > MAX_ARRAYS:
        raise SceneError(f"initial_states: at most {MAX_STATES} initial states per scene are supported; the file opens "
                         f"{arrays} arrays (at most {MAX_ARRAYS})")


# ---------------------------------------------------------------- parsing helpers
def _type_name(value: Any) -> str:
    return type(value).__name__


def _number(value: Any, path: str) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, (int, float, str, Fraction)):
        raise SceneError(f"{path}: expected a number (or a decimal string such as \"6.4\"); got {_type_name(value)} {shown(value)}")
    try:
        return to_rational(value, name=path)
    except SymbolicFrictionError as exc:
        raise SceneError(str(exc)) from None


def _check_samples(samples: Any, states: int, given: str) -> None:
    """``samples`` (None, or an integer ≥ 2) within :data:`MAX_SAMPLES` and, over ``states``, :data:`MAX_TOTAL_SAMPLES`."""
    if samples is not None and (isinstance(samples, bool) or not isinstance(samples, int) or samples < 2):
        raise SceneError(f"samples: expected an integer ≥ 2; got {given}")
    if samples is not None and samples > MAX_SAMPLES:
        raise SceneError(f"samples: at most {MAX_SAMPLES} sample times per trajectory are supported; got {shown(samples)}")
    if samples is not None and states * samples > MAX_TOTAL_SAMPLES:
        raise SceneError(f"samples: {states} initial states × {samples} samples = {states * samples} sample times; "
                         f"at most {MAX_TOTAL_SAMPLES} per scene are supported (a bound on memory)")


_FLOAT_MAX = Fraction(1.7976931348623157e308)


def _float_range(q: Fraction, path: str) -> Fraction:
    """``q`` if a simulation can use it: within the range of float64 (the state and the horizon; not the gains)."""
    if abs(q) > _FLOAT_MAX:
        raise SceneError(f"{path}: expected a number within the range of float64 (about ±1.8e308); got {short_rational(q)}")
    return q


def _positive(value: Any, path: str) -> Fraction:
    q = _number(value, path)
    if not q > 0:
        raise SceneError(f"{path}: expected a number > 0; got {format_rational(q)}")
    return q


def _table(value: Any, path: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise SceneError(f"{path}: expected a table; got {_type_name(value)} {value!r}")
    return value


def _check_keys(table: Mapping[str, Any], path: str, allowed: Sequence[str], required: Sequence[str] = ()) -> None:
    prefix = f"{path}." if path else ""
    for key in table:
        if key not in allowed:
            raise SceneError(f"{prefix}{key}: unknown key; expected one of {', '.join(allowed)}")
    for key in required:
        if key not in table:
            raise SceneError(f"{prefix}{key}: missing key (required)")


def _string(value: Any, path: str, choices: Sequence[str] | None = None) -> str:
    if not isinstance(value, str):
        raise SceneError(f"{path}: expected a string; got {_type_name(value)} {value!r}")
    if choices is not None and value not in choices:
        raise SceneError(f"{path}: expected one of {', '.join(map(repr, choices))}; got {value!r}")
    return value


def _parse_params(doc: Mapping[str, Any]) -> Parameters:
    if "gains" in doc and "physical" in doc:
        raise SceneError("gains, physical: give the gains in one table only ([gains] normalised or [physical])")
    if "gains" in doc:
        table = _table(doc["gains"], "gains")
        keys = ("k_p", "k_i", "k_v", "f_c")
        # f_s: static level above Coulomb; reset_dwell: reset PID's dwell time (both optional)
        _check_keys(table, "gains", keys + ("f_s", "reset_dwell"), keys)
        values = {k: _number(table[k], f"gains.{k}") for k in keys + ("f_s", "reset_dwell") if k in table}
        try:
            return Parameters(**values)
        except SymbolicFrictionError as exc:
            raise SceneError(f"gains: {exc}") from None
    if "physical" in doc:
        table = _table(doc["physical"], "physical")
        keys = ("m", "k_p_bar", "k_i_bar", "k_d_bar", "alpha_v", "f_c_bar", "f_s_bar")
        _check_keys(table, "physical", keys + ("reset_dwell",), ("m", "k_p_bar", "k_i_bar", "k_d_bar", "f_c_bar"))
        values = {k: _number(table[k], f"physical.{k}") for k in keys if k in table}
        try:
            params = Parameters.from_physical(**values)
            if "reset_dwell" in table:
                import dataclasses

                params = dataclasses.replace(params, reset_dwell=_number(table["reset_dwell"], "physical.reset_dwell"))
            return params
        except SymbolicFrictionError as exc:
            raise SceneError(f"physical: {exc}") from None
    raise SceneError("gains: missing table; give [gains] (k_p, k_i, k_v, f_c) or [physical] (m, k_p_bar, ...)")


def _parse_states(value: Any) -> tuple[tuple[Fraction, Fraction, Fraction], ...]:
    path = "initial_states"
    if not isinstance(value, list) or not value:
        raise SceneError(f"{path}: expected a non-empty list of [e_i, s, v]; got {_type_name(value)} {str(value)[:60]}")
    if len(value) > MAX_STATES:
        raise SceneError(f"{path}: at most {MAX_STATES} initial states per scene are supported; got {len(value)}")
    states = []
    for i, row in enumerate(value):
        p = f"{path}[{i}]"
        if not isinstance(row, list) or len(row) != 3:
            got = f"{len(row)} values" if isinstance(row, list) else f"{_type_name(row)} {row!r}"
            raise SceneError(f"{p}: expected [e_i, s, v] (3 numbers); got {got}")
        states.append(tuple(_number(c, f"{p}[{j}]") for j, c in enumerate(row)))
    return tuple(states)  # type: ignore[return-value]


def _parse_friction(value: Any) -> Any:
    from .._simulation.friction import InflatedCoulomb, Stribeck

    table = _table(value, "friction")
    law = _string(table.get("law", "coulomb"), "friction.law", FRICTION_LAWS)
    if law == "coulomb":
        _check_keys(table, "friction", ("law",))
        return None
    try:
        if law == "stribeck":
            _check_keys(table, "friction", ("law", "f_s", "v_s", "viscous"), ("f_s", "v_s"))
            return Stribeck(
                f_s=_number(table["f_s"], "friction.f_s"),
                v_s=_number(table["v_s"], "friction.v_s"),
                viscous=_number(table.get("viscous", 0), "friction.viscous"),
            )
        _check_keys(table, "friction", ("law", "rho", "selection", "d", "e"), ("rho",))
        rho = _number(table["rho"], "friction.rho")
        selection = _string(table.get("selection", "worst-case"), "friction.selection", ("worst-case", "constant"))
        if selection == "worst-case":
            for key in ("d", "e"):
                if key in table:
                    raise SceneError(f"friction.{key}: only used with selection = \"constant\"")
            return InflatedCoulomb(rho)
        for key in ("d", "e"):
            if key not in table:
                raise SceneError(f"friction.{key}: missing key (required by selection = \"constant\")")
        return InflatedCoulomb(rho, selection=(_number(table["d"], "friction.d"), _number(table["e"], "friction.e")))
    except SceneError:
        raise
    except SymbolicFrictionError as exc:
        raise SceneError(f"friction: {exc}") from None


def _parse_method(value: Any) -> tuple[str, tuple[tuple[str, Any], ...]]:
    from .._simulation import METHODS, get_method

    table = _table(value, "method")
    name = _string(table.get("name", "event"), "method.name", tuple(METHODS))
    defaults = get_method(name).options
    knobs: list[tuple[str, Any]] = []
    for key, raw in table.items():
        if key == "name":
            continue
        path = f"method.{key}"
        if key == "friction" and key in defaults:
            raise SceneError(f"{path}: declare the friction law in the [friction] table, not among the method knobs")
        if key not in defaults:
            raise SceneError(
                f"{path}: unknown option for method {name!r}; expected one of "
                f"{', '.join(sorted(k for k in defaults if k != 'friction')) or '(none)'}"
            )
        default = defaults[key]
        if isinstance(default, int) and not isinstance(default, bool):
            if isinstance(raw, bool) or not isinstance(raw, int):
                raise SceneError(f"{path}: expected an integer; got {_type_name(raw)} {raw!r}")
            if abs(raw) > MAX_INTEGER_KNOB:
                raise SceneError(f"{path}: at most {MAX_INTEGER_KNOB} is supported (a bound on time and memory); got {str(raw)[:40]}")
            knobs.append((key, raw))
        elif isinstance(default, str):
            knobs.append((key, _string(raw, path)))
        else:  # float knobs (and knobs whose default is None)
            q = _number(raw, path)
            knobs.append((key, float(q)))
    return name, tuple(knobs)
