"""Scenes: a TOML declaration of what to simulate and which outputs to produce.

A scene is the input of ``symbolic-friction simulate``.  It names the gains
(normalised as in eq. (basic), or physical as in §II-A), the initial states
``z(0) = (e_i, s, v)`` of eq. (xPhDot), the horizon, the friction law (the
paper's Coulomb law, or a Corollary 1 perturbation from
:mod:`._simulation.friction`), the method with its accuracy knobs, and the
outputs it needs.  Only what is asked for is computed and imported.

File format (every key is checked; unknown keys are errors)::

    name = "paper-a"                      # optional; default: the file name
    description = "Table I (a) ..."       # optional
    t_end = 30                            # horizon, > 0
    samples = 3001                        # optional: uniform samples on [0, t_end]
    initial_states = [[0, 1, 0], ["0.1", "-0.5", "0"]]   # (e_i, s, v); strings stay exact
    outputs = ["trajectories", "events", "V", "V_hat", "distance", "figure"]
    format = "csv"                        # or "npz"

    [gains]                               # normalised gains (or [physical]); optional f_s, reset_dwell
    k_p = 3
    k_i = 4
    k_v = "6.4"
    f_c = 1

    [physical]                            # m, k_p_bar, k_i_bar, k_d_bar, f_c_bar, alpha_v (default 0)

    [method]
    name = "event"                        # event | moreau | regularized | ivp-events
    # knobs of that method, e.g. h = 1e-3 for moreau

    [friction]                            # optional; default Coulomb.  Needs method "moreau".
    law = "stribeck"                      # coulomb | stribeck | inflated
    f_s = "1.5"                           # stribeck: f_s, v_s, viscous (default 0)
    v_s = "0.1"
    # inflated: rho, selection = "worst-case" (default), or d and e

    [v_hat]                               # k1..k4 of eq. (Vhat); needed for output "V_hat"
    k1 = 1

Built-in scenes live in ``symbolic_friction/scenes/*.toml`` and are loaded by
name (:func:`load_scene`).
"""

from __future__ import annotations

import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from importlib import resources
from pathlib import Path
from typing import Any

from .._infra.errors import SceneError, SymbolicFrictionError
from .._infra.io import atomic_write, atomic_write_text
from .._model.parameters import Parameters
from .._infra.guards import check_path
from .._infra.rational import format_rational, shown
from ._scene_parse import (
    FRICTION_LAWS,
    MAX_INTEGER_KNOB,
    MAX_SAMPLES,
    MAX_STATES,
    MAX_TOTAL_SAMPLES,
    _check_array_count,
    _check_keys,
    _check_samples,
    _float_range,
    _number,
    _parse_friction,
    _parse_method,
    _parse_params,
    _parse_states,
    _positive,
    _string,
    _table,
    _type_name,
)

__all__ = ["Scene", "SceneResult", "load_scene", "builtin_scenes", "OUTPUTS", "FORMATS", "FRICTION_LAWS"]

OUTPUTS = ("trajectories", "events", "V", "V_hat", "distance", "figure")
FORMATS = ("csv", "npz")
_TOP_KEYS = (
    "name",
    "description",
    "t_end",
    "samples",
    "initial_states",
    "outputs",
    "format",
    "gains",
    "physical",
    "method",
    "friction",
    "v_hat",
)
_NAME_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")
MAX_SCENE_BYTES = 10_000_000
"""Largest scene file read."""


# ---------------------------------------------------------------- the Scene
@dataclass(frozen=True)
class Scene:
    """A validated simulation scene (see the module docstring for the file format).

    Attributes
    ----------
    name : str
        Used for the output file names (letters, digits, ``_ . -``).
    params : Parameters
    initial_states : tuple of (Fraction, Fraction, Fraction)
        ``(e_i, s, v)`` of each trajectory, exact.
    t_end : Fraction
        Horizon, ``> 0``.
    samples : int or None
        Number of uniform sample times on ``[0, t_end]`` (``None``: the
        method's own points).
    method : str
        A name in :data:`symbolic_friction._simulation.METHODS`.
    knobs : tuple of (str, value)
        The method's accuracy knobs (validated by the method).
    friction : FrictionLaw or None
        ``None`` is the paper's Coulomb law; any other law needs ``moreau``.
    v_hat : tuple of 4 Fractions or None
        ``k1..k4`` of eq. (Vhat), required for the ``V_hat`` output.
    outputs : tuple of str
        A subset of :data:`OUTPUTS`.
    format : {"csv", "npz"}
    description, source : str

    Raises
    ------
    SceneError
        At construction, naming the field and what was expected.
    """

    name: str
    params: Parameters
    initial_states: tuple[tuple[Fraction, Fraction, Fraction], ...]
    t_end: Fraction
    samples: int | None = None
    method: str = "event"
    knobs: tuple[tuple[str, Any], ...] = ()
    friction: Any = None
    v_hat: tuple[Fraction, Fraction, Fraction, Fraction] | None = None
    outputs: tuple[str, ...] = ("trajectories", "events")
    format: str = "csv"
    description: str = ""
    source: str = field(default="<mapping>", compare=False)

    def __post_init__(self) -> None:
        from .._simulation import METHODS, get_method
        from .._simulation.friction import FrictionLaw

        if not isinstance(self.name, str) or not _NAME_RE.match(self.name):
            raise SceneError(f"name: expected letters, digits, '_', '.' or '-' (used in file names); got {self.name!r}")
        if not isinstance(self.params, Parameters):
            raise SceneError(f"params: expected a Parameters instance; got {_type_name(self.params)}")
        states = self.initial_states
        if not isinstance(states, (tuple, list)) or not states or len(states) > MAX_STATES:
            raise SceneError(f"initial_states: expected a non-empty sequence of (e_i, s, v); got {shown(states)} "
                             f"(at most {MAX_STATES} states)")
        exact = []
        for i, row in enumerate(states):
            if not isinstance(row, (tuple, list)) or len(row) != 3:
                raise SceneError(f"initial_states[{i}]: expected (e_i, s, v) (3 numbers); got {row!r}")
            exact.append(tuple(_float_range(_number(c, f"initial_states[{i}][{j}]"), f"initial_states[{i}][{j}]")
                               for j, c in enumerate(row)))
        object.__setattr__(self, "initial_states", tuple(exact))
        object.__setattr__(self, "t_end", _float_range(_positive(self.t_end, "t_end"), "t_end"))
        _check_samples(self.samples, len(exact), shown(self.samples))
        if self.method not in METHODS:
            raise SceneError(f"method.name: expected one of {', '.join(map(repr, METHODS))}; got {self.method!r}")
        if self.friction is not None:
            if not isinstance(self.friction, FrictionLaw):
                raise SceneError(f"friction: expected a FrictionLaw or None; got {_type_name(self.friction)}")
            if self.method != "moreau":
                raise SceneError(
                    f"friction.law: the {self.friction.name!r} law is simulated by method \"moreau\"; "
                    f"got method {self.method!r}"
                )
        if self.params.reset and not get_method(self.method).resets:
            raise SceneError(f"gains.reset_dwell: reset PID is simulated by method \"event\"; got method {self.method!r}")
        knobs = dict(self.knobs)
        if len(knobs) != len(self.knobs):
            raise SceneError("method: a knob is given twice")
        solver = get_method(self.method)
        unknown = sorted(set(knobs) - set(solver.options))
        if unknown:
            raise SceneError(f"method.{unknown[0]}: unknown option for method {self.method!r}")
        merged = {**solver.options, **knobs}
        if self.friction is not None:
            merged["friction"] = self.friction
        try:
            solver._validate(merged)
        except SymbolicFrictionError as exc:
            raise SceneError(f"method: {exc}") from None
        outputs = tuple(self.outputs)
        for i, out in enumerate(outputs):
            if out not in OUTPUTS:
                raise SceneError(f"outputs[{i}]: expected one of {', '.join(map(repr, OUTPUTS))}; got {out!r}")
        if len(set(outputs)) != len(outputs):
            raise SceneError(f"outputs: an output is listed twice in {list(outputs)!r}")
        if not outputs:
            raise SceneError(f"outputs: expected at least one of {', '.join(map(repr, OUTPUTS))}")
        object.__setattr__(self, "outputs", outputs)
        if self.v_hat is not None:
            if not isinstance(self.v_hat, (tuple, list)) or len(self.v_hat) != 4:
                raise SceneError(f"v_hat: expected (k1, k2, k3, k4); got {self.v_hat!r}")
            object.__setattr__(self, "v_hat", tuple(_positive(k, f"v_hat.k{i + 1}") for i, k in enumerate(self.v_hat)))
        if "V_hat" in outputs and self.v_hat is None:
            raise SceneError("v_hat: missing table; the output \"V_hat\" needs [v_hat] with k1, k2, k3, k4")
        if self.format not in FORMATS:
            raise SceneError(f"format: expected one of {', '.join(map(repr, FORMATS))}; got {self.format!r}")

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_mapping(cls, doc: Mapping[str, Any], *, source: str = "<mapping>", default_name: str = "scene") -> "Scene":
        """Build a scene from a parsed TOML document.

        Raises
        ------
        SceneError
            Naming the dotted key path and what was expected.
        """
        doc = _table(doc, "scene")
        _check_keys(doc, "", _TOP_KEYS, ("t_end", "initial_states"))
        params = _parse_params(doc)
        states = _parse_states(doc["initial_states"])
        t_end = _positive(doc["t_end"], "t_end")
        samples = doc.get("samples")
        _check_samples(samples, len(states), f"{_type_name(samples)} {str(samples)[:40]}")
        outputs = doc.get("outputs", ["trajectories", "events"])
        if not isinstance(outputs, list):
            raise SceneError(f"outputs: expected a list of strings; got {_type_name(outputs)} {outputs!r}")
        for i, out in enumerate(outputs):
            _string(out, f"outputs[{i}]", OUTPUTS)
        fmt = _string(doc.get("format", "csv"), "format", FORMATS)
        method, knobs = _parse_method(doc.get("method", {}))
        friction = _parse_friction(doc["friction"]) if "friction" in doc else None
        v_hat = None
        if "v_hat" in doc:
            table = _table(doc["v_hat"], "v_hat")
            keys = ("k1", "k2", "k3", "k4")
            _check_keys(table, "v_hat", keys, keys)
            v_hat = tuple(_positive(table[k], f"v_hat.{k}") for k in keys)
        name = _string(doc.get("name", default_name), "name")
        description = _string(doc.get("description", ""), "description")
        return cls(
            name=name,
            params=params,
            initial_states=states,
            t_end=t_end,
            samples=samples,
            method=method,
            knobs=knobs,
            friction=friction,
            v_hat=v_hat,  # type: ignore[arg-type]
            outputs=tuple(outputs),
            format=fmt,
            description=description,
            source=source,
        )

    @classmethod
    def from_text(cls, text: str, *, source: str = "<text>", default_name: str = "scene") -> "Scene":
        """Parse TOML text (see the module docstring)."""
        _check_array_count(text)
        try:
            doc = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise SceneError(f"{source}: not valid TOML: {exc}") from None
        except RecursionError:
            raise SceneError(f"{source}: not valid TOML: nested too deeply") from None
        except ValueError as exc:  # e.g. an integer beyond Python's 4300-digit conversion limit
            reason = "an integer has more than 4300 digits" if "Exceeds the limit" in str(exc) else str(exc)[:200]
            raise SceneError(f"{source}: not valid TOML: {reason}") from None
        return cls.from_mapping(doc, source=source, default_name=default_name)

    @classmethod
    def from_file(cls, path: str | Path) -> "Scene":
        """Read a scene file; its stem is the default name."""
        from .._infra.io import read_limited

        path = Path(path)
        try:
            text = read_limited(path, limit=MAX_SCENE_BYTES, what="scene file").decode("utf-8")
        except UnicodeDecodeError as exc:
            raise SceneError(f"{path}: not a UTF-8 text file ({exc.reason})") from None
        return cls.from_text(text, source=str(path), default_name=path.stem)

    # ------------------------------------------------------------ running
    @property
    def method_options(self) -> dict[str, Any]:
        """Keyword options for :func:`~symbolic_friction._simulation.simulate`."""
        opts = dict(self.knobs)
        if self.friction is not None:
            opts["friction"] = self.friction
        return opts

    def t_eval(self) -> Any:
        """The uniform sample times, or ``None``."""
        if self.samples is None:
            return None
        import numpy as np

        return np.linspace(0.0, float(self.t_end), self.samples)

    def run(self) -> "SceneResult":
        """Simulate every initial state; compute nothing beyond the trajectories yet."""
        from .._simulation import simulate

        t_eval = self.t_eval()
        sols = tuple(
            simulate(
                self.params,
                tuple(float(c) for c in z0),
                float(self.t_end),
                method=self.method,
                t_eval=t_eval,
                **self.method_options,
            )
            for z0 in self.initial_states
        )
        return SceneResult(self, sols)

    def summary(self) -> str:
        """A few lines describing the scene."""
        law = "Coulomb f_c SGN(v)" if self.friction is None else self.friction.describe()
        knobs = ", ".join(f"{k} = {v}" for k, v in self.knobs) or "defaults"
        return "\n".join(
            [
                f"scene {self.name}" + (f": {self.description}" if self.description else ""),
                f"  gains {self.params}",
                f"  {len(self.initial_states)} initial state(s), t_end = {format_rational(self.t_end)}, "
                f"method {self.method} ({knobs}), friction {law}",
                f"  outputs {', '.join(self.outputs)} as {self.format}",
            ]
        )


@dataclass(frozen=True, eq=False)
class SceneResult:
    """The solutions of a scene, and the requested outputs computed on demand."""

    scene: Scene
    solutions: tuple[Any, ...]

    def columns(self, index: int) -> dict[str, Any]:
        """Sample columns of trajectory ``index`` for the requested outputs only."""
        sol = self.solutions[index]
        out = self.scene.outputs
        cols: dict[str, Any] = {"t": sol.t, "mode": sol.mode}
        if "trajectories" in out:
            cols.update(e_i=sol.z[:, 0], s=sol.z[:, 1], v=sol.z[:, 2], sigma=sol.x[:, 0], phi=sol.x[:, 1])
        if "V" in out:
            cols["V"] = sol.V
        if "V_hat" in out:
            cols["V_hat"] = sol.V_hat(self.scene.v_hat)
        if "distance" in out:
            cols["distance"] = sol.distance
        return cols

    @property
    def wants_samples(self) -> bool:
        return any(o in self.scene.outputs for o in ("trajectories", "V", "V_hat", "distance"))

    def write(self, out_dir: str | Path, *, fmt: str | None = None, png: bool = False) -> list[Path]:
        """Write the requested outputs into ``out_dir``; return the files written.

        CSV: ``<name>.csv`` (one row per sample, column ``trajectory``) and
        ``<name>_events.csv``.  NPZ: ``<name>.npz`` with arrays ``t_<i>``,
        ``mode_<i>``, ``z_<i>``, ``x_<i>``, ``V_<i>``, ``V_hat_<i>``,
        ``distance_<i>``, ``events_<i>`` (rows ``t, mode_before, mode_after``)
        as requested, plus ``initial_states`` and ``status``.  A PNG
        ``<name>.png`` when ``figure`` is requested or ``png`` is true.
        Every file is written atomically (temporary file, then rename).
        """
        fmt = self.scene.format if fmt is None else fmt
        if fmt not in FORMATS:
            raise SceneError(f"format: expected one of {', '.join(map(repr, FORMATS))}; got {fmt!r}")
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        written: list[Path] = []
        if fmt == "csv":
            written += self._write_csv(out)
        else:
            written += self._write_npz(out)
        if png or "figure" in self.scene.outputs:
            written.append(self._write_png(out))
        return written

    def _write_csv(self, out: Path) -> list[Path]:
        import numpy as np

        name = self.scene.name
        files = []
        if self.wants_samples:
            lines: list[str] = []
            header: list[str] | None = None
            for i in range(len(self.solutions)):
                cols = self.columns(i)
                if header is None:
                    header = ["trajectory", *cols]
                    lines.append(",".join(header))
                # columns as Python lists: repr of a float is its shortest round-trip decimal
                columns = [
                    [str(int(m)) for m in a.tolist()] if key == "mode" else list(map(repr, np.asarray(a, dtype=float).tolist()))
                    for key, a in cols.items()
                ]
                prefix = f"{i},"
                lines += [prefix + ",".join(row) for row in zip(*columns)]
            files.append(atomic_write_text(out / f"{name}.csv", "\n".join(lines) + "\n"))
        if "events" in self.scene.outputs:
            lines = ["trajectory,t,mode_before,mode_after"]
            for i, sol in enumerate(self.solutions):
                lines += [f"{i},{float(t)!r},{int(a)},{int(b)}" for t, a, b in sol.events]
            files.append(atomic_write_text(out / f"{name}_events.csv", "\n".join(lines) + "\n"))
        return files

    def _write_npz(self, out: Path) -> list[Path]:
        import numpy as np

        arrays: dict[str, Any] = {
            "initial_states": np.array([[float(c) for c in z0] for z0 in self.scene.initial_states]),
            "status": np.array([sol.status for sol in self.solutions]),
            "params": np.array([f"{k}={v}" for k, v in self.scene.params.as_strings().items()]),
        }
        for i, sol in enumerate(self.solutions):
            if self.wants_samples:
                cols = self.columns(i)
                arrays[f"t_{i}"] = cols["t"]
                arrays[f"mode_{i}"] = cols["mode"]
                if "trajectories" in self.scene.outputs:
                    arrays[f"z_{i}"] = sol.z
                    arrays[f"x_{i}"] = sol.x
                for key in ("V", "V_hat", "distance"):
                    if key in cols:
                        arrays[f"{key}_{i}"] = cols[key]
            if "events" in self.scene.outputs:
                arrays[f"events_{i}"] = np.array(sol.events, dtype=float).reshape(-1, 3)
        path = out / f"{self.scene.name}.npz"
        atomic_write(path, lambda fh: np.savez(fh, **arrays))
        return [path]

    def _write_png(self, out: Path) -> Path:
        from .figures import plot_scene

        return plot_scene(self, out / f"{self.scene.name}.png")


# ---------------------------------------------------------------- built-in scenes
def _builtin_dir() -> Any:
    return resources.files("symbolic_friction") / "scenes"


def builtin_scenes() -> list[str]:
    """Names of the built-in scenes (``symbolic_friction/scenes/*.toml``)."""
    return sorted(p.name[: -len(".toml")] for p in _builtin_dir().iterdir() if p.name.endswith(".toml"))


def load_scene(scene: str | Path) -> Scene:
    """Load a scene from a path, or a built-in scene by name.

    Raises
    ------
    SceneError
        If ``scene`` is neither an existing file nor a built-in name, or the
        scene is malformed.

    Examples
    --------
    >>> load_scene("paper-a").method
    'event'
    """
    path = Path(check_path(scene, name="scene", what="a scene file or a built-in scene's name"))
    if path.is_file():
        return Scene.from_file(path)
    name = str(scene)
    if name in builtin_scenes():
        resource = _builtin_dir() / f"{name}.toml"
        return Scene.from_text(resource.read_text(encoding="utf-8"), source=f"built-in scene {name}", default_name=name)
    if os.path.lexists(path):
        # an existing path that is not a regular file (a FIFO, a device, a symlink loop) is read, and refused,
        # by the bounded reader, which says what it is
        return Scene.from_file(path)
    raise SceneError(
        f"scene {name!r}: no such file and no built-in scene of that name; built-in scenes: {', '.join(builtin_scenes())}"
    )
