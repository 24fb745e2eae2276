"""Golden files: every verdict and message of a decision procedure, pinned (``SF_REGENERATE_GOLDEN=1`` rewrites them)."""

from __future__ import annotations

import json
import os
from pathlib import Path

HERE = Path(__file__).parent


def assert_golden(name: str, actual: dict[str, list[str]]) -> None:
    """``actual`` equals the golden file ``name`` case by case (rewritten first when ``SF_REGENERATE_GOLDEN`` is set)."""
    path = HERE / name
    if os.environ.get("SF_REGENERATE_GOLDEN"):
        path.write_text(json.dumps(actual, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    golden = json.loads(path.read_text(encoding="utf-8"))
    assert sorted(actual) == sorted(golden)
    for case in golden:
        assert actual[case] == golden[case], case
