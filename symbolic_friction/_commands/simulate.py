"""``symbolic-friction simulate SCENE``: run a scene (a TOML file or a built-in name).

Only what the scene asks for is computed and imported: a plain event-driven
scene imports neither sympy, cvxpy, scipy.integrate nor matplotlib.  This
module imports only the standard library at top level (Standard 6).
"""

from __future__ import annotations

import argparse
import sys

HELP = "simulate a scene (TOML file or built-in name) and write CSV/NPZ (and PNG) outputs"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``SCENE [--out DIR] [--format csv|npz] [--png]``, or ``--list``."""
    parser.add_argument("scene", nargs="?", metavar="SCENE", help="path of a scene .toml file, or a built-in scene name")
    parser.add_argument("--out", default=".", metavar="DIR", help="output directory (default: current directory)")
    parser.add_argument("--format", choices=("csv", "npz"), default=None, help="output format (default: the scene's)")
    parser.add_argument("--png", action="store_true", help="also write a PNG of the solutions (needs matplotlib)")
    parser.add_argument("--list", action="store_true", help="list the built-in scenes and exit")


def run(args: argparse.Namespace) -> int:
    from .._errors import SceneError
    from .._scenes import builtin_scenes, load_scene

    if args.list:
        for name in builtin_scenes():
            scene = load_scene(name)
            print(f"{name:20s} {scene.description}")
        return 0
    if args.scene is None:
        raise SceneError("no scene given; pass a .toml path or one of: " + ", ".join(builtin_scenes()))
    scene = load_scene(args.scene)
    print(scene.summary())
    result = scene.run()
    for i, sol in enumerate(result.solutions):
        z0 = ", ".join(f"{float(c):g}" for c in scene.initial_states[i])
        print(f"  trajectory {i}: z0 = ({z0}), {sol.t.size} samples, {len(sol.events)} events, {sol.status}")
    files = result.write(args.out, fmt=args.format, png=args.png)
    for path in files:
        print(f"wrote {path}")
    sys.stdout.flush()
    return 0
