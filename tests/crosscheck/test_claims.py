"""The float view of a certificate refuses malformed ones."""

from __future__ import annotations

import dataclasses
import pytest

from symbolic_friction.errors import CertificateFormatError
from symbolic_friction._crosscheck import Claims
from tests.crosscheck.helpers import _cert


def test_claims_errors():
    cert = _cert("a")

    class Missing:
        pass

    with pytest.raises(CertificateFormatError, match="needs the attribute 'k_p'"):
        Claims.from_certificate(Missing())

    class NoBound:
        def __init__(self):
            for k, v in dataclasses.asdict(cert).items():
                setattr(self, k, v)
            self.overshoot_bound = None

    with pytest.raises(CertificateFormatError, match="needs 'overshoot_bound'"):
        Claims.from_certificate(NoBound())
    bad = NoBound()
    bad.overshoot_bound = "3.5"
    bad.c1 = "abc"
    with pytest.raises(CertificateFormatError, match="c1 must be a number; got 'abc'"):
        Claims.from_certificate(bad)
    bad.c1 = -1
    with pytest.raises(CertificateFormatError, match="c1 must be finite and > 0; got -1"):
        Claims.from_certificate(bad)
