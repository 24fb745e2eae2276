"""The certified constants a cross-check puts to the test (float view of a
certificate of Lemma 2, Lemma 3 and Proposition 1).

A :class:`~symbolic_friction._certify.certificate.Certificate` holds exact
rationals; trajectories are floats.  :class:`Claims` is the float view the
vectorised checks need, built from any certificate-like object (the
:class:`Certificate` dataclass, or an *altered* copy made with
:func:`dataclasses.replace` that the exact verifier would reject: the
cross-check deliberately does not verify a certificate before testing it,
so that wrong certificates can be shown to fail on trajectories too).

A certificate of the quadratic template (beyond the paper) claims no constant
of Lemmas 2 and 3, only κ: its :class:`Claims` has ``template``
``"quadratic/v1"`` and NaN for the paper's constants, and the cross-check puts
to it only the properties that read κ or no constant at all
(:meth:`~._property.Property.applies_to`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from .._infra.errors import CertificateFormatError
from .._model.parameters import Parameters

__all__ = ["Claims", "PAPER_TEMPLATE"]

_CONSTANTS = ("k1", "k2", "k3", "k4", "c1", "c2", "c1_hat", "c2_hat", "c")
PAPER_TEMPLATE = "lyapunov-pair/v1"
"""The template of the paper's certificate (the constants of Lemmas 2 and 3)."""


@dataclass(frozen=True)
class Claims:
    """Float view of one certificate.

    Attributes
    ----------
    label : str
        Name shown in tables and counterexample files (usually the file stem).
    params : Parameters
        Exact gains.
    k1, k2, k3, k4, c1, c2, c1_hat, c2_hat, c : float
        The certificate's constants.
    kappa : float
        ``overshoot_bound`` (the claimed κ of eq. stabState).
    exact : dict
        The exact constants (Fractions) and ``overshoot_bound`` string, kept
        for counterexample files.
    template : str
        The certificate's template id; only the paper's has the constants
        above (another template's are NaN and no property reads them).
    """

    label: str
    params: Parameters
    k1: float
    k2: float
    k3: float
    k4: float
    c1: float
    c2: float
    c1_hat: float
    c2_hat: float
    c: float
    kappa: float
    exact: dict
    template: str = PAPER_TEMPLATE

    def __post_init__(self) -> None:
        # the paper's constants may be anything here (the self-test feeds NaN on purpose); another template has none
        constants = [getattr(self, name) for name in _CONSTANTS]
        if not self.is_paper and not all(math.isnan(c) for c in constants):
            raise CertificateFormatError(f"a {self.template} certificate has no constant of Lemmas 2 and 3 (NaN)")

    @property
    def is_paper(self) -> bool:
        """Whether the certificate is of the paper's template (has the constants of Lemmas 2 and 3)."""
        return self.template == PAPER_TEMPLATE

    @property
    def template_name(self) -> str:
        """``"paper"`` or the other template's name (its id without the version)."""
        return "paper" if self.is_paper else self.template.split("/", 1)[0]

    @classmethod
    def from_certificate(cls, certificate: Any, *, label: str | None = None) -> "Claims":
        """Read a certificate (or an altered copy of one) without verifying it.

        A certificate of a template beyond the paper (quadratic, sup-flow) is read by :meth:`from_quadratic`.

        Raises
        ------
        CertificateFormatError
            If an attribute is missing or not a finite positive number.
        """
        from .._certify.quadratic import QuadraticCertificate
        from .._certify.sup_flow import SupFlowCertificate

        if isinstance(certificate, (QuadraticCertificate, SupFlowCertificate)):
            return cls.from_quadratic(certificate, label=label)
        values: dict[str, float] = {}
        exact: dict[str, Any] = {}
        for name in ("k_p", "k_i", "k_v", "f_c", *_CONSTANTS):
            if not hasattr(certificate, name):
                raise CertificateFormatError(
                    f"a certificate for the cross-check needs the attribute {name!r}; "
                    f"{type(certificate).__name__} has none"
                )
            exact[name] = getattr(certificate, name)
        bound = getattr(certificate, "overshoot_bound", None)
        if bound is None:
            raise CertificateFormatError("a certificate for the cross-check needs 'overshoot_bound'; got none")
        exact["overshoot_bound"] = bound
        for name, value in exact.items():
            try:
                f = float(Fraction(value)) if isinstance(value, str) else float(value)
            except (TypeError, ValueError):
                raise CertificateFormatError(f"{name} must be a number; got {value!r}") from None
            if not (math.isfinite(f) and f > 0):
                raise CertificateFormatError(f"{name} must be finite and > 0; got {value!r}")
            values[name] = f
        params = Parameters(k_p=exact["k_p"], k_i=exact["k_i"], k_v=exact["k_v"], f_c=exact["f_c"])
        if label is None:
            prov = getattr(certificate, "provenance", None)
            label = getattr(prov, "label", "") or "<certificate>"
            mode = getattr(prov, "mode", "")
            if mode:
                label = f"{label} [{mode}]"
        return cls(
            label=label,
            params=params,
            **{name: values[name] for name in _CONSTANTS},
            kappa=values["overshoot_bound"],
            exact={k: (str(v) if isinstance(v, Fraction) else v) for k, v in exact.items()},
        )

    @classmethod
    def from_quadratic(cls, certificate: Any, *, label: str | None = None) -> "Claims":
        """Read a certificate of a template beyond the paper (quadratic or sup-flow; or an altered copy) without
        verifying it: its gains and κ."""
        from .._certify import quadratic, sup_flow

        # a sup-flow certificate of either version names its own template id
        TEMPLATE_ID = certificate.template_id if isinstance(certificate, sup_flow.SupFlowCertificate) else quadratic.TEMPLATE_ID

        bound = certificate.overshoot_bound
        try:
            kappa = float(Fraction(bound))
        except (TypeError, ValueError):
            raise CertificateFormatError(f"overshoot_bound must be a number; got {bound!r}") from None
        if label is None:
            label = getattr(certificate.provenance, "label", "") or "<certificate>"
            label = f"{label} [{TEMPLATE_ID.split('/')[0]}]"
        exact = {**certificate.parameters, **certificate.constants, "overshoot_bound": bound}
        nan = math.nan
        return cls(label=label, params=Parameters(**certificate.parameters), **{name: nan for name in _CONSTANTS},
                   kappa=kappa, exact={k: (str(v) if isinstance(v, Fraction) else v) for k, v in exact.items()},
                   template=TEMPLATE_ID)

    @property
    def k(self) -> tuple[float, float, float, float]:
        """``(k1, k2, k3, k4)`` of eq. (Vhat)."""
        return (self.k1, self.k2, self.k3, self.k4)

    @property
    def kappa_formula(self) -> float:
        """``√(c₂ĉ₂/(c₁ĉ₁))`` from the constants (the bound ``kappa`` must not be below it)."""
        from .._certify.certificate import kappa_squared

        return math.sqrt(kappa_squared(self.c1, self.c2, self.c1_hat, self.c2_hat))

    def lambda_max_K_half(self) -> float:
        """Largest eigenvalue of ``K/2`` (``V̂ = ½wᵀKw``), used only to scale tolerances."""
        from .._model.lyapunov import vhat_matrix_entries

        K = np.array(vhat_matrix_entries(*self.k), dtype=float)
        return float(np.linalg.eigvalsh(K)[-1]) / 2.0
