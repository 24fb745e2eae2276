"""Tampered corpora of the sup-flow certificates (versions 1 and 2): see ``test_tampered_corpora.py``.

A module of their own, because their verification is the slow part (about 0.3 s an edit for both verifiers): the
test suite's workers (``--dist loadscope``) then decide them beside the other kinds.
"""

from __future__ import annotations

import pytest

from tests.independent.test_tampered_corpora import check_kind

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("kind", ["sup-flow/v1", "sup-flow/v2"])
def test_the_tampered_corpus_of_each_kind(kind):
    check_kind(kind)
