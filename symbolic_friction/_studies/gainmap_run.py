"""Run a gain map (:mod:`.gainmap`) in chunks on any executor and write its dataset.

A map lives in one directory::

    manifest.json          the spec, its SHA-256 digest, the columns (written first)
    chunks/chunk-000017.npz one file per finished chunk, each written atomically
    map.csv                one row per point:   pandas.read_csv("DIR/map.csv")
    map.nc                 netCDF3 (scipy):     xarray.open_dataset("DIR/map.nc")

Chunks are computed by :func:`~.gainmap.evaluate_chunk` on the executor
(``None``: in this process; a :class:`~concurrent.futures.ProcessPoolExecutor`;
a dask.distributed ``Client.get_executor()``) and written by this process as
they finish, so a killed run loses only the chunks in flight (one per worker),
and running the same spec again on the same directory computes only the
missing chunks.  A directory holding chunks of another spec (another digest)
is refused, never mixed.  The two dataset files are assembled from the chunks
at the end; a grid's ``map.nc`` has one dimension per ranged axis, a sample's
the dimension ``point``.
"""

from __future__ import annotations

import io
import json
import os
import time
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from .._infra.errors import UsageError
from .._infra.io import atomic_write, atomic_write_text, ensure_directory, read_limited
from .gainmap import STATUS, MapSpec

__all__ = ["MapRun", "run_map", "read_columns", "read_map", "FORMATS", "MANIFEST", "DATASET_FORMAT"]

DATASET_FORMAT = "symbolic-friction/gain-map/v1"
MANIFEST = "manifest.json"
FORMATS = ("csv", "netcdf")
_FILES = {"csv": "map.csv", "netcdf": "map.nc"}
# netCDF3 attributes are ASCII
_LONG_NAMES = {
    "status": "closed-form certificate: " + ", ".join(f"{i} {s}" for i, s in enumerate(STATUS)),
    "kappa": "overshoot bound kappa of the proved closed-form certificate (a float upper bound; NaN unless proved)",
    "kappa_sdp": "overshoot bound kappa of the SDP's tightest certificate (NaN if none)",
    "worst_overshoot": "largest sup|x(t)|_A/|x(0)|_A the adversary found (not proved)",
    "tightness": "worst_overshoot / kappa",
    "hunting_found": "symmetric hunting cycles found (-1: not evaluated)",
    "hunting_proved": "symmetric hunting cycles proved in arb balls (-1: not evaluated)",
}


@dataclass(frozen=True)
class MapRun:
    """What :func:`run_map` did.

    Attributes
    ----------
    directory : Path
    spec : MapSpec
    computed, skipped : int
        Chunks computed by this run, and chunks found finished by an earlier run.
    seconds : float
        Wall time of this run.
    counts : dict
        Points per status (:data:`~.gainmap.STATUS`).
    kappa_min, kappa_max : float
        Range of the proved κ (NaN if none is proved).
    files : tuple of Path
        The dataset files written.
    """

    directory: Path
    spec: MapSpec
    computed: int
    skipped: int
    seconds: float
    counts: dict[str, int]
    kappa_min: float
    kappa_max: float
    files: tuple[Path, ...]

    @property
    def rate(self) -> float:
        """Points per second computed by this run."""
        done = min(self.computed * self.spec.chunk, self.spec.points)
        return done / self.seconds if self.seconds > 0 else float("nan")


def _chunk_path(directory: Path, c: int) -> Path:
    return directory / "chunks" / f"chunk-{c:06d}.npz"


def _manifest(spec: MapSpec) -> dict[str, Any]:
    from .. import __version__

    return {"format": DATASET_FORMAT, "digest": spec.digest(), "spec": spec.to_dict(), "points": spec.points,
            "chunks": spec.chunks, "columns": [name for name, _ in spec.columns()], "package_version": __version__}


def _claim_directory(directory: Path, spec: MapSpec) -> None:
    """Write the manifest of a new map, or check that an existing one is of this very spec."""
    path = directory / MANIFEST
    if not path.exists():
        extra = [p.name for p in directory.iterdir()] if directory.exists() else []
        if extra:
            raise UsageError(
                f"{directory} is not empty and holds no gain map ({MANIFEST} missing; found {', '.join(sorted(extra)[:3])}); "
                "give a new or empty directory"
            )
        ensure_directory(directory)
        atomic_write_text(path, json.dumps(_manifest(spec), indent=2, sort_keys=True) + "\n")
        return
    try:
        found = json.loads(read_limited(path, limit=1 << 20, what="gain-map manifest"))
        digest = found["digest"] if found.get("format") == DATASET_FORMAT else None
    except (ValueError, KeyError, TypeError, AttributeError):
        digest = None
    if digest is None:
        raise UsageError(f"{path} is not a gain-map manifest ({DATASET_FORMAT}); give another directory")
    if digest != spec.digest():
        raise UsageError(
            f"{directory} holds chunks of a different map (spec digest {digest[:12]}…, this one {spec.digest()[:12]}…); "
            "refusing to mix them: give another directory or remove it"
        )


def _load_chunk(path: Path, spec: MapSpec, c: int) -> dict[str, np.ndarray] | None:
    """A finished chunk, or None if it is absent or not of this spec's shape (then it is recomputed)."""
    if not path.exists():
        return None
    size = min((c + 1) * spec.chunk, spec.points) - c * spec.chunk
    try:
        with np.load(path, allow_pickle=False) as data:
            cols = {name: data[name] for name, _ in spec.columns()}
    except (OSError, ValueError, KeyError):
        return None
    if any(v.shape != (size,) or v.dtype != np.dtype(dt) for (name, dt), v in zip(spec.columns(), cols.values())):
        return None
    return cols


def _write_chunk(path: Path, columns: dict[str, np.ndarray]) -> None:
    atomic_write(path, lambda handle: np.savez(handle, **columns))


def run_map(
    spec: MapSpec,
    directory: str | os.PathLike[str],
    *,
    executor: Executor | None = None,
    formats: Iterable[str] = FORMATS,
    progress: bool | None = None,
) -> MapRun:
    """Evaluate every point of ``spec`` and write the dataset under ``directory`` (see the module docstring).

    Parameters
    ----------
    spec : MapSpec
    directory : path-like
        New, empty, or holding an unfinished or finished run of the same spec.
    executor : concurrent.futures.Executor or None, keyword-only
        Where chunks are computed; ``None`` computes them in this process.
    formats : iterable of {"csv", "netcdf"}, keyword-only
        Dataset files to assemble at the end.
    progress : bool or None, keyword-only
        Progress bar (points/s, time left) on stderr; ``None``: only on a terminal.

    Raises
    ------
    UsageError
        If ``directory`` holds something else, or chunks of another spec.
    ParameterError
        For an unknown format.

    Examples
    --------
    >>> import tempfile
    >>> from symbolic_friction._studies.gainmap import map_spec
    >>> spec = map_spec({"k_p": "1:3:3", "k_i": "1:8:2", "k_v": "2"})
    >>> run = run_map(spec, tempfile.mkdtemp() + "/m", formats=["csv"], progress=False)
    >>> run.counts
    {'proved': 3, 'not_proved': 0, 'outside_assumption_1': 3}
    """
    from .._infra.errors import ParameterError
    from .._infra.progress import Progress
    from . import gainmap

    formats = tuple(formats)
    bad = [f for f in formats if f not in FORMATS]
    if bad:
        raise ParameterError(f"dataset formats are {', '.join(FORMATS)}; got {', '.join(map(repr, bad))}")
    if isinstance(directory, str) and not directory.strip():
        ensure_directory(directory, what="gain-map directory")  # refuses it: an empty path would mean the working directory
    directory = Path(directory)
    _claim_directory(directory, spec)
    start = time.perf_counter()
    done = {c for c in range(spec.chunks) if _load_chunk(_chunk_path(directory, c), spec, c) is not None}
    todo = [c for c in range(spec.chunks) if c not in done]
    finished = sum(min((c + 1) * spec.chunk, spec.points) - c * spec.chunk for c in done)
    bar = Progress(spec.points, desc="map", enabled=progress, unit="pt", initial=finished)
    with bar:
        if executor is None:
            for c in todo:
                columns = gainmap.evaluate_chunk(spec, c)
                _write_chunk(_chunk_path(directory, c), columns)
                bar.update(len(columns["status"]))
        else:
            futures = {executor.submit(gainmap.evaluate_chunk, spec, c): c for c in todo}
            try:
                for future in as_completed(futures):
                    columns = future.result()
                    _write_chunk(_chunk_path(directory, futures[future]), columns)
                    bar.update(len(columns["status"]))
            except BaseException:
                for future in futures:
                    future.cancel()
                raise
    seconds = time.perf_counter() - start
    columns = read_columns(directory, spec)
    files = tuple(_write_dataset(directory, spec, columns, f) for f in formats)
    status = columns["status"]
    proved = columns["kappa"][status == 0]
    return MapRun(
        directory=directory, spec=spec, computed=len(todo), skipped=len(done), seconds=seconds,
        counts={s: int(np.count_nonzero(status == i)) for i, s in enumerate(STATUS)},
        kappa_min=float(proved.min()) if proved.size else float("nan"),
        kappa_max=float(proved.max()) if proved.size else float("nan"), files=files,
    )


def read_columns(directory: str | os.PathLike[str], spec: MapSpec) -> dict[str, np.ndarray]:
    """Every column of a finished map, from its chunks, in point order.

    Raises
    ------
    UsageError
        If a chunk is missing (the run did not finish).
    """
    directory = Path(directory)
    parts: dict[str, list[np.ndarray]] = {name: [] for name, _ in spec.columns()}
    for c in range(spec.chunks):
        cols = _load_chunk(_chunk_path(directory, c), spec, c)
        if cols is None:
            raise UsageError(f"{directory}: chunk {c} of {spec.chunks} is missing; run the map again to finish it")
        for name, v in cols.items():
            parts[name].append(v)
    return {name: np.concatenate(v) for name, v in parts.items()}


def read_map(directory: str | os.PathLike[str]) -> tuple[MapSpec, dict[str, np.ndarray]]:
    """``(spec, columns)`` of the finished map in ``directory`` (its manifest and chunks).

    Raises
    ------
    UsageError
        If ``directory`` holds no gain map, or the run did not finish.
    """
    directory = Path(directory)
    path = directory / MANIFEST
    if not path.is_file():
        raise UsageError(f"{directory} holds no gain map ({MANIFEST} missing)")
    try:
        found = json.loads(read_limited(path, limit=1 << 20, what="gain-map manifest"))
        spec = MapSpec.from_dict(found["spec"])
        ok = found.get("format") == DATASET_FORMAT and found.get("digest") == spec.digest()
    except (ValueError, KeyError, TypeError, AttributeError):
        ok = False
    if not ok:
        raise UsageError(f"{path} is not a gain-map manifest ({DATASET_FORMAT})")
    return spec, read_columns(directory, spec)


def _write_dataset(directory: Path, spec: MapSpec, columns: dict[str, np.ndarray], fmt: str) -> Path:
    path = directory / _FILES[fmt]
    if fmt == "csv":
        atomic_write(path, lambda handle: _write_csv(handle, spec, columns))
    else:
        atomic_write(path, lambda handle: handle.write(_netcdf_bytes(spec, columns)))
    return path


def _write_csv(handle: Any, spec: MapSpec, columns: dict[str, np.ndarray]) -> None:
    """One row per point; floats in their shortest exact repr, ``status`` as its word."""
    names = list(columns)
    handle.write((",".join(names) + "\n").encode())
    step = 65536
    for lo in range(0, spec.points, step):
        cols = []
        for name in names:
            v = columns[name][lo : lo + step]
            cols.append([STATUS[i] for i in v.tolist()] if name == "status" else [repr(x) for x in v.tolist()])
        handle.write("".join(",".join(row) + "\n" for row in zip(*cols)).encode())


def _netcdf_bytes(spec: MapSpec, columns: dict[str, np.ndarray]) -> bytes:
    """The netCDF3 (64-bit offset) file: grid dimensions with coordinates, or ``point``."""
    from scipy.io import netcdf_file

    buffer = io.BytesIO()
    nc = netcdf_file(buffer, "w", version=2)
    try:
        _fill_netcdf(nc, spec, columns)
        nc.flush()
        return buffer.getvalue()
    finally:
        nc.close()


def _fill_netcdf(nc: Any, spec: MapSpec, columns: dict[str, np.ndarray]) -> None:
    nc.title = "symbolic-friction gain map: Proposition 1's overshoot bound kappa (closed-form certificate)"
    nc.format = DATASET_FORMAT
    nc.spec = json.dumps(spec.to_dict(), sort_keys=True)
    nc.digest = spec.digest()
    if spec.sample:
        dims: tuple[str, ...] = ("point",)
        nc.createDimension("point", spec.points)
        shape = (spec.points,)
    else:
        ranged = spec.ranged
        dims = tuple(a.name for a in ranged)
        shape = spec.shape
        for k, a in enumerate(ranged):
            nc.createDimension(a.name, a.n)
            grid = columns[a.name].reshape(shape)
            coordinate = grid[tuple(slice(None) if i == k else 0 for i in range(len(ranged)))]
            var = nc.createVariable(a.name, "d", (a.name,))
            var[:] = coordinate
            var.scale = a.scale
    for name, dtype in spec.columns():
        if name in dims:
            continue
        var = nc.createVariable(name, np.dtype(dtype).char, dims)
        var[:] = columns[name].reshape(shape)
        if name in _LONG_NAMES:
            var.long_name = _LONG_NAMES[name]
        if name == "status":
            var.flag_values = np.arange(len(STATUS), dtype=np.int8)
            var.flag_meanings = " ".join(STATUS)
