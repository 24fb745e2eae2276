"""Project configuration: where ``[tool.symbolic-friction]`` is found and what it may say."""

from __future__ import annotations

import pytest

from symbolic_friction._infra.config import find_config, load_config
from symbolic_friction._infra.errors import ConfigError


def _pyproject(directory, body):
    (directory / "pyproject.toml").write_text('[project]\nname = "x"\n\n[tool.symbolic-friction]\n' + body, encoding="utf-8")


def test_found_from_a_subdirectory_and_resolved_against_its_file(tmp_path):
    _pyproject(tmp_path, 'proofs = "certs"\ncertificates = ["a.json", "sub/b.json"]\n')
    (tmp_path / "src" / "deep").mkdir(parents=True)
    config = find_config(tmp_path / "src" / "deep")
    assert config.proofs == tmp_path.resolve() / "certs"
    assert config.certificates == ("a.json", "sub/b.json") and config.report is False


def test_symbolic_friction_toml_wins_over_pyproject(tmp_path):
    _pyproject(tmp_path, 'certificates = ["a.json"]\n')
    (tmp_path / "symbolic-friction.toml").write_text('certificates = ["b.json"]\nreport = true\n', encoding="utf-8")
    config = find_config(tmp_path)
    assert config.certificates == ("b.json",) and config.report is True


def test_a_pyproject_without_the_table_is_passed_over_and_the_walk_stops_at_git(tmp_path):
    _pyproject(tmp_path, 'certificates = ["outer.json"]\n')
    inner = tmp_path / "inner"
    inner.mkdir()
    (inner / "pyproject.toml").write_text('[project]\nname = "y"\n', encoding="utf-8")
    assert find_config(inner).certificates == ("outer.json",)
    (inner / ".git").mkdir()
    assert find_config(inner) is None  # the repository root bounds the search


@pytest.mark.parametrize(
    "body, message",
    [
        ("bogus = 1\n", "unknown key(s) 'bogus'"),
        ('certificates = "a.json"\n', "'certificates' must be a list"),
        ('certificates = ["../x.json"]\n', "inside the proofs directory"),
        ('certificates = ["/etc/x.json"]\n', "inside the proofs directory"),
        ('certificates = ["a.txt"]\n', "must be a .json file"),
        ('certificates = ["a.json", "a.json"]\n', "more than once"),
        ("certificates = [1]\n", "non-empty string"),
        ('report = "yes"\n', "'report' must be true or false"),
        ("proofs = 3\n", "'proofs' must be a directory name"),
    ],
)
def test_malformed_configuration_is_refused_naming_the_key(tmp_path, body, message):
    path = tmp_path / "symbolic-friction.toml"
    path.write_text(body, encoding="utf-8")
    with pytest.raises(ConfigError, match=message.replace("(", r"\(").replace(")", r"\)")):
        load_config(path)


def test_pyproject_given_explicitly_needs_the_table(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n', encoding="utf-8")
    with pytest.raises(ConfigError, match=r"has no \[tool.symbolic-friction\] table"):
        load_config(tmp_path / "pyproject.toml")


def test_not_toml_and_too_deep(tmp_path):
    path = tmp_path / "symbolic-friction.toml"
    path.write_text("certificates = [", encoding="utf-8")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_config(path)
    path.write_text("a = " + "[" * 50_000 + "]" * 50_000, encoding="utf-8")
    with pytest.raises(ConfigError, match="nested too deeply"):
        load_config(path)


def test_the_checkout_configures_table_i_and_the_report():
    from pathlib import Path

    config = load_config(Path(__file__).resolve().parents[1] / "pyproject.toml")
    assert config.report is True
    hunting = sorted(p.relative_to(config.proofs).as_posix() for p in (config.proofs / "hunting").glob("*.json"))
    assert len(hunting) == 5
    assert sorted(config.certificates) == sorted(
        [f"case_{c}_{m}.json" for c in "ab" for m in ("feasible", "tightest")] + hunting
        + ["box_case_a_10pct.json", "box_physical.json"] + [f"{d}/case_{c}.json" for d in ("quadratic", "sup_flow") for c in "ab"]
        + ["reset/case_a_contraction.json"]
    )
