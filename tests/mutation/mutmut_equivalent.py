"""What mutmut's report counts (:data:`SCOPE`) and the survivors argued equivalent (:data:`EQUIVALENT`).

The scope is the trusted base: the exact verifier, the decision procedures
and the case split on ``R``, the Krawczyk proof of hunting cycles, and the
part of ``check`` that turns section results into the exit code.  Printing
helpers of ``check`` (table layout, wrapping, locating the configuration)
are mutated too but reported as out of scope.
"""

from __future__ import annotations

SCOPE: tuple[str, ...] = (
    "symbolic_friction._certify.verify.*",
    "symbolic_friction._obligations._decide.x_[!l]*",  # every function but latex(), which only renders
    "symbolic_friction._obligations._region.*",
    "symbolic_friction._certify.hunting_proof.*",
    "symbolic_friction._cli.check.x_run__mutmut_*",
    "symbolic_friction._cli._sections.x_closing_line__mutmut_*",
    "symbolic_friction._cli._sections.x__crashed__mutmut_*",
    "symbolic_friction._cli._sections.x__is_verdict__mutmut_*",
)

EQUIVALENT: dict[str, str] = {
}
