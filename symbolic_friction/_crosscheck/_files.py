"""Which certificate files ``crosscheck`` checks when none is given, and which it leaves out and why.

The cross-check's properties instantiate the paper's template (the constants of
Lemmas 2 and 3) and, for the quadratic and sup-flow templates, their bound κ (eq. stabState);
a file of another template is named with the reason it is left out.
"""

from __future__ import annotations

__all__ = ["SKIPPED", "CHECKED", "default_certificate_files", "default_certificate_selection"]

CHECKED = ("lyapunov-pair/v1", "quadratic/v1", "sup-flow/v1", "sup-flow/v2")
"""The templates whose certificates ``crosscheck`` tests on trajectories (the paper's; the quadratic and sup-flow ones' κ)."""


SKIPPED = {
    "hunting-cycle/v1": "a hunting certificate: it proves a cycle of the stiction model, not the paper's "
                        "inequalities (verify checks it)",
    "lyapunov-box/v1": "a box certificate: it proves a box of gain sets at its corners (verify checks it); "
                       "cross-check a point inside it with its own certificate",
    "reset-contraction/v1": "a reset-contraction certificate: it proves how fast reset PID settles near the attractor, "
                            "not the paper's inequalities (verify checks it)",
}
"""Why :func:`default_certificate_files` leaves a file of another template out (by template id)."""


def default_certificate_files() -> list[str]:
    """The certificates ``crosscheck`` checks when none is given.

    The project's configured certificates (``[tool.symbolic-friction]``, as for
    ``check``), else every ``*.json`` under ``proofs/``; the paper's template and
    the templates beyond it (:data:`CHECKED`) are checked on trajectories, hunting
    and box certificates are left out.

    Raises
    ------
    FileNotFoundError
        If there is none.
    """
    return default_certificate_selection()[0]


def default_certificate_selection() -> tuple[list[str], list[tuple[str, str]]]:
    """:func:`default_certificate_files`, and the files left out with the reason for each.

    Raises
    ------
    FileNotFoundError
        If no certificate is left.
    """
    from pathlib import Path

    from .._certify.templates import read_certificate_file
    from .._infra.config import find_config
    from .._infra.errors import CertificateFormatError, InputFileError

    def other_template(name: str) -> str | None:
        """The template id of a file the cross-check does not test, else None."""
        try:
            template = read_certificate_file(name)[0].id
        except (CertificateFormatError, InputFileError):
            return None  # the certificate loader says what is wrong with it
        return None if template in CHECKED else template

    config = find_config()
    if config is not None and config.certificates:
        cwd = Path.cwd().resolve()
        files = []
        for name in config.certificates:
            path = config.proofs / name
            try:
                path = path.relative_to(cwd)
            except ValueError:
                pass
            files.append(str(path))
    else:
        files = sorted(str(p) for p in Path("proofs").rglob("*.json"))
    skipped = []
    for f in files:
        template = other_template(f)
        if template is not None:
            skipped.append((f, SKIPPED.get(template, f"a {template} certificate: the cross-check tests the "
                                                      "paper's and the quadratic template only (verify checks it)")))
    files = [f for f in files if f not in {name for name, _ in skipped}]
    if not files:
        raise FileNotFoundError("no certificate given and no proofs/*.json in the current directory"
                                + (f" (skipped {len(skipped)} of another template)" if skipped else ""))
    return files, skipped
