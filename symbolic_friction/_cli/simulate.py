"""``symbolic-friction simulate SCENE``: run a scene (a TOML file or a built-in name).

Only what the scene asks for is computed and imported: a plain event-driven
scene imports neither sympy, cvxpy, scipy.integrate nor matplotlib.  This
module imports only the standard library at top level.
"""

from __future__ import annotations

import argparse

HELP = "simulate a scene (TOML file or built-in name) and write CSV/NPZ (and PNG) outputs"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``SCENE [--out DIR] [--format csv|npz] [--png]``, or ``--list``."""
    parser.add_argument("scene", nargs="?", metavar="SCENE", help="path of a scene .toml file, or a built-in scene name")
    parser.add_argument("--out", default=".", metavar="DIR", help="output directory (default: current directory)")
    parser.add_argument("--format", choices=("csv", "npz"), default=None, help="output format (default: the scene's)")
    parser.add_argument("--png", action="store_true", help="also write a PNG of the solutions (needs matplotlib)")
    parser.add_argument("--theta", default=None, metavar="THETA",
                        help="for a moreau scene: the weight θ in [1/2, 1] of its θ-method (1: implicit Euler, "
                             "1/2: second order), replacing the scene's")
    parser.add_argument("--list", action="store_true", help="list the built-in scenes and exit")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object (scene, trajectories, events, status, files written) instead of text")


def run(args: argparse.Namespace) -> int:
    import json

    from .._infra.errors import SceneError
    from .._infra.io import ensure_directory
    from .._infra.output import emit
    from .._studies.scenes import builtin_scenes, load_scene

    if args.list:
        scenes = {name: load_scene(name).description for name in builtin_scenes()}
        if args.json:
            emit(json.dumps({"scenes": scenes}, indent=2, ensure_ascii=False), level=0)
        else:
            for name, description in scenes.items():
                emit(f"{name:20s} {description}", level=0)
        return 0
    if args.scene is None:
        raise SceneError("no scene given; pass a .toml path or one of: " + ", ".join(builtin_scenes()))
    scene = load_scene(args.scene)
    if args.theta is not None:
        scene = _with_theta(scene, args.theta)
    if args.format is not None:
        # the summary and the files name the format actually written, not the scene's default
        import dataclasses

        scene = dataclasses.replace(scene, format=args.format)
    ensure_directory(args.out)  # an unusable --out fails now, not after the simulation
    if not args.json:
        emit(scene.summary())
    result = scene.run()
    trajectories = []
    for i, sol in enumerate(result.solutions):
        z0 = [float(c) for c in scene.initial_states[i]]
        trajectories.append({"index": i, "z0": z0, "samples": int(sol.t.size), "events": len(sol.events),
                             "status": str(sol.status)})
        if not args.json:
            emit(f"  trajectory {i}: z0 = ({', '.join(f'{c:g}' for c in z0)}), {sol.t.size} samples, "
                 f"{len(sol.events)} events, {sol.status}")
    files = result.write(args.out, fmt=scene.format, png=args.png)
    if args.json:
        emit(json.dumps({"scene": scene.name, "method": scene.method, "format": scene.format, "summary": scene.summary(),
                         "trajectories": trajectories, "files": [str(p) for p in files]}, indent=2, ensure_ascii=False),
             level=0)
    else:
        for path in files:
            kind = "PNG" if path.suffix == ".png" else scene.format.upper()
            emit(f"wrote {path} ({kind})", level=0)
    return 0


def _with_theta(scene, text: str):  # type: ignore[no-untyped-def]
    """``scene`` with the Moreau weight θ of ``--theta`` (refused for a scene of another method)."""
    import dataclasses

    from .._infra.errors import UsageError
    from .tradeoff import theta_value

    theta = theta_value(text)
    if scene.method != "moreau":
        raise UsageError(f"--theta is a knob of method moreau; scene {scene.name!r} uses method {scene.method!r}")
    knobs = tuple((k, v) for k, v in scene.knobs if k != "theta") + (("theta", theta),)
    return dataclasses.replace(scene, knobs=knobs)
