"""Certificate templates: what a kind of proof file is, and the registry the file's ``template`` id selects from.

A *template* is one way of proving a claim with a file: the stability
certificate of Proposition 1 (constants of ``V`` and ``V̂``, Lemma 2 and
Lemma 3, template ``lyapunov-pair/v1``), the hunting certificate (a Krawczyk
box around a stick–slip cycle, ``hunting-cycle/v1``), or a new one.  It says
how to read the parsed JSON of a file, how to decide it exactly, how to write
it, and whether a committed file is stale.  A file names its template in the
optional ``template`` member; without it, its ``schema`` selects the template
registered as that schema's default, so files written before templates had
ids read unchanged.

Adding a template is one module that builds a :class:`Template` and passes it
to :func:`register`, plus its import in :func:`.templates.builtin_templates`.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._infra.errors import CertificateFormatError

__all__ = ["Template", "every_failure", "register", "unregister", "registered", "template_for", "TEMPLATE_KEY"]

TEMPLATE_KEY = "template"
"""The member of a certificate file that names its template."""


def every_failure(report: Any) -> str:
    """Every failed check's message, joined by ``"; "`` (the default :attr:`Template.failure`)."""
    return "; ".join(check.message for check in report.failures)


@dataclass(frozen=True, eq=False)
class Template:
    """One kind of certificate file.

    Attributes
    ----------
    id : str
        The template id (``"name/vN"``), written as the file's ``template``.
    schema : str
        The file's ``schema`` member.
    read : callable
        ``read(data, source) -> certificate``: parse a JSON value strictly;
        raises :class:`~symbolic_friction.CertificateFormatError`.
    verify : callable
        ``verify(certificate, source) -> report``: the exact decision; the
        report has ``proved`` (bool) and ``certificate``.
    dumps : callable
        ``dumps(certificate) -> str``: the file's bytes, deterministic.
    stale : callable
        ``stale(certificate, path) -> str``: why the committed file ``path``
        no longer states what it should (written for a different statement,
        or inconsistent with itself); empty when it does.  A failure.
    drift : callable or None
        ``drift(certificate, path) -> str``: how the file differs from what
        would be written now although it proves the same statement (a newer
        solver or package rounds differently); empty when it does not.
        Reported; a failure only under ``check --strict``.
    claim : callable
        ``claim(certificate) -> str``: what a proved file shows, for ``check``'s line.
    failure : callable
        ``failure(report) -> str``: why a report that is not proved fails;
        default :func:`every_failure`.
    default : bool
        Whether a file of ``schema`` without a ``template`` member is read
        with this template.
    regenerate : callable or None
        ``regenerate(certificate) -> certificate``: what would be written now
        (``check --write`` rewrites the file with it); None if the file is
        not regenerated.
    name : str
        The short name users choose the template by (``certify --template
        paper``); default: the id without its version (``quadratic/v1`` →
        ``quadratic``).
    """

    id: str
    schema: str
    read: Callable[[Any, str], Any]
    verify: Callable[[Any, str], Any]
    dumps: Callable[[Any], str]
    stale: Callable[[Any, Path], str]
    claim: Callable[[Any], str]
    failure: Callable[[Any], str] = field(default_factory=lambda: every_failure)
    default: bool = False
    drift: Callable[[Any, Path], str] | None = None
    regenerate: Callable[[Any], Any] | None = None
    name: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.id, str) or "/" not in self.id:
            raise ValueError(f"a template id is 'name/vN'; got {self.id!r}")
        if not self.name:
            object.__setattr__(self, "name", self.id.split("/", 1)[0])

    def write(self, certificate: Any, path: str | os.PathLike[str]) -> Path:
        """Write ``certificate`` to ``path`` atomically."""
        from .._infra.io import atomic_write_text

        return atomic_write_text(path, self.dumps(certificate))


_TEMPLATES: dict[str, Template] = {}


def register(template: Template) -> Template:
    """Add ``template`` to the registry (returned, so a module can write ``TEMPLATE = register(Template(...))``).

    Raises
    ------
    ValueError
        If another template has the same id, or is already the default of the same schema.
    """
    if not isinstance(template, Template):
        raise TypeError(f"expected a Template; got {type(template).__name__}")
    other = _TEMPLATES.get(template.id)
    if other is not None and other is not template:
        raise ValueError(f"a certificate template {template.id!r} is already registered")
    if template.default and any(t.default and t.schema == template.schema and t is not template for t in _TEMPLATES.values()):
        raise ValueError(f"schema {template.schema!r} already has a default template")
    _TEMPLATES[template.id] = template
    return template


def unregister(template: Template) -> None:
    """Remove ``template`` from the registry (for tests that register a throwaway one)."""
    if _TEMPLATES.get(template.id) is template:
        del _TEMPLATES[template.id]


def registered() -> tuple[Template, ...]:
    """The registered templates, in registration order."""
    return tuple(_TEMPLATES.values())


def template_for(data: object, *, fallback: Template) -> Template:
    """The template a parsed certificate file asks for.

    Its ``template`` member names it; without one, the default template of
    its ``schema``; a file that names neither known is read by ``fallback``,
    whose reader says what is wrong with it.

    Raises
    ------
    CertificateFormatError
        If the file names a template that is not registered.
    """
    if isinstance(data, dict) and TEMPLATE_KEY in data:
        name = data[TEMPLATE_KEY]
        template = _TEMPLATES.get(name) if isinstance(name, str) else None
        if template is None:
            known = ", ".join(sorted(_TEMPLATES))
            raise CertificateFormatError(f"unknown certificate template {name!r}; known templates: {known}")
        return template
    schema = data.get("schema") if isinstance(data, dict) else None
    for template in _TEMPLATES.values():
        if template.default and template.schema == schema:
            return template
    return fallback
