"""The JSON Schema of the stability certificate (``symbolic-friction/certificate/v1``), shipped in ``symbolic_friction/schemas/``, and validation against it with :mod:`jsonschema`."""

from __future__ import annotations

import functools
import json
from typing import Any

from .._infra.errors import CertificateFormatError


def json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of the certificate format, as shipped in the package."""
    from importlib.resources import files

    return json.loads(files("symbolic_friction").joinpath("schemas", "certificate-v1.schema.json").read_text(encoding="utf-8"))


_MAX_ERRORS = 100
"""Violations ranked to choose the one reported."""


@functools.lru_cache(maxsize=1)
def _validator() -> Any:
    import jsonschema

    return jsonschema.Draft202012Validator(json_schema())


def validate_schema(data: object) -> None:
    """Validate a parsed certificate against :func:`json_schema` with :mod:`jsonschema`.

    Raises
    ------
    CertificateFormatError
        With the first violation, located by its JSON path.
    """
    import itertools

    import jsonschema

    # the best of the first few violations: a 10⁵-item array of wrong items must not rank 10⁵ errors
    error = jsonschema.exceptions.best_match(itertools.islice(_validator().iter_errors(data), _MAX_ERRORS))
    if error is not None:
        where = "".join(f"[{p!r}]" if isinstance(p, int) else f".{p}" for p in error.absolute_path).lstrip(".") or "certificate"
        message = error.message if len(error.message) <= 200 else error.message[:200] + "…"
        raise CertificateFormatError(f"does not match the certificate schema at {where}: {message}")
