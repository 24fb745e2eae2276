"""The independent checker: a small second verifier of every certificate kind, for reviewers.

It imports the standard library and python-flint only (an import-linter contract holds it to that), reads
the JSON files itself and decides every premise exactly or in arb balls rounded outward; undecided is not
proved.  Nothing else of the package imports it except the commands that run it beside the main verifier.
"""

from __future__ import annotations


from ._core import Malformed, Verdict, load, shared

__all__ = ["check_file", "check_data", "KINDS", "Malformed", "Verdict", "shared"]

KINDS = {
    "lyapunov-pair/v1": "paper",
    "lyapunov-box/v1": "box",
    "quadratic/v1": "quadratic",
    "sup-flow/v1": "sup_flow",
    "sup-flow/v2": "sup_flow",
    "hunting-cycle/v1": "hunting",
    "reset-contraction/v1": "reset_contraction",
}
"""Each template id and the module that decides it."""

_SCHEMAS = {
    "symbolic-friction/certificate/v1": "lyapunov-pair/v1",
    "symbolic-friction/box-certificate/v1": "lyapunov-box/v1",
    "symbolic-friction/hunting-certificate/v1": "hunting-cycle/v1",
}
"""Files written before templates had ids name only their schema."""


def check_data(data: dict) -> Verdict:
    """Decide a parsed certificate with the module of its template (``Malformed`` if none fits)."""
    import importlib

    template = data.get("template") or _SCHEMAS.get(data.get("schema"))
    if template not in KINDS:
        raise Malformed(f"no independent check for template {template!r}")
    return importlib.import_module(f"{__name__}.{KINDS[template]}").check(data)


def check_file(path: str) -> Verdict:
    """Read and decide one certificate file."""
    return check_data(load(str(path)))
