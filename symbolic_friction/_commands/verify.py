"""``symbolic-friction verify FILE…``: exact re-check of certificate files.

Each file is dispatched on its ``schema`` field: a stability certificate of
the paper's model (:mod:`.._certify.verify`, exact rationals) or a hunting
certificate (:mod:`.._hunting._certificate`, a Krawczyk proof in arb balls).

Exit status: 0 if every file proves its claim; 1 if some inequality fails
(each failing one is named with its exact numbers); 2 if a file is missing
or malformed (not JSON, unknown schema, missing keys, a float where an exact
rational string is required, …).
"""

from __future__ import annotations

import argparse
import sys

HELP = "exactly re-check certificate files (exit 0 only if every file proves its claim)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """``FILE…`` and ``--verbose``."""
    parser.description = (
        f"{HELP}. Exit status: 0 if every file proves its claim, 1 if an inequality fails "
        "(named with its exact numbers), 2 if a file is missing or malformed."
    )
    parser.add_argument("files", nargs="+", metavar="FILE", help="certificate JSON files")
    parser.add_argument("-v", "--verbose", action="store_true", help="print every inequality with its exact numbers")


def run(args: argparse.Namespace) -> int:
    """Verify each file; print one summary line per file (and every check with ``--verbose``)."""
    from .._certify import verify_file
    from .._errors import CertificateFormatError

    failed = False
    malformed: list[Exception] = []
    from .._hunting._certificate import is_hunting_file, verify_hunting_file

    for name in args.files:
        try:
            # dispatch on the file's schema: a hunting certificate has its own proof
            report = verify_hunting_file(name) if is_hunting_file(name) else verify_file(name)
        except (CertificateFormatError, FileNotFoundError, IsADirectoryError, PermissionError) as exc:
            malformed.append(exc)
            print(f"MALFORMED {exc}", file=sys.stdout)
            continue
        print(report.summary(), file=sys.stdout)
        if args.verbose:
            for check in report.checks:
                print(f"  {check}  [{check.obligation}]", file=sys.stdout)
        failed = failed or not report.proved
    if malformed:
        # the CLI turns this into "error: …" and exit status 2
        if len(malformed) == 1:
            raise malformed[0]
        raise CertificateFormatError(f"{len(malformed)} files are missing or malformed; first: {malformed[0]}")
    return 1 if failed else 0
