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


def inline_local_refs(schema: dict[str, Any]) -> dict[str, Any]:
    """``schema`` with every ``{"$ref": "#/$defs/name"}`` replaced by that definition (the shipped schemas' only refs).

    The same validation, the same errors (a ref's errors carry the keyword and instance path of the definition's
    own): jsonschema resolves a ref through its registry at each use, about half the time of validating a box
    certificate's hundred intervals.  A ref with sibling keywords, or one into anything but ``$defs``, stays.
    """
    defs = schema.get("$defs", {})

    def inline(node: object, seen: tuple[str, ...]) -> object:
        if isinstance(node, list):
            return [inline(item, seen) for item in node]
        if not isinstance(node, dict):
            return node
        ref = node.get("$ref")
        name = ref[len("#/$defs/"):] if len(node) == 1 and isinstance(ref, str) and ref.startswith("#/$defs/") else None
        if name in defs and ref not in seen:  # a definition that refers to itself keeps its ref there
            return inline(defs[name], (*seen, ref))
        return {key: inline(value, seen) for key, value in node.items()}

    return inline(schema, ())  # type: ignore[return-value]


@functools.lru_cache(maxsize=1)
def _validator() -> Any:
    import jsonschema

    return jsonschema.Draft202012Validator(inline_local_refs(json_schema()))


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
