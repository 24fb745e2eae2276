"""Readers of numeric options (``_infra/options.py``): ASCII digits, exact comparison with the ceiling, one message."""

import argparse
from fractions import Fraction

import pytest

from symbolic_friction._infra.options import count_option, read_count, read_real, read_reals, real_option


def test_counts():
    assert read_count(" 12 ", name="--n", high=100) == 12
    assert read_count("+3", name="--n", high=100) == 3
    for bad, says in [
        ("٣", r"--n must be an integer from 1 to 100 \(ASCII digits\); got '٣'"),
        ("1_0", r"\(ASCII digits\); got '1_0'"), ("1e3", "ASCII digits"), ("2.5", "ASCII digits"), ("", "ASCII digits"),
        ("7" * 100_000, r"got '7{40}…'"), ("0", r"from 1 to 100 \(a bound on time and memory\); got '0'"),
        ("-1", "ASCII digits"), ("101", "got '101'"),
    ]:
        with pytest.raises(argparse.ArgumentTypeError, match=says):
            read_count(bad, name="--n", high=100)


def test_reals_are_read_exactly_and_bounded_before_conversion():
    assert read_real("6.4", name="--t", high=10) == 6.4
    assert read_real("32/5", name="--t", high=10) == 6.4
    assert read_real("10", name="--t", high=10) == 10.0
    for bad, says, kwargs in [
        ("1e999", r"--t must lie in \(0, 10\]; got '1e999'", {}),  # never read as inf
        ("1e999999999", "exponents beyond", {}), ("nan", "must be finite", {}), ("-inf", "must be finite", {}),
        ("٣", "ASCII digits only", {}), ("1_0", "a decimal such as", {}), ("0", r"must lie in \(0, 10\]", {}),
        ("1e-400", "below what a float64 can hold", {}), ("1", r"must lie in \(0, 1\)", {"high": 1, "high_open": True}),
    ]:
        with pytest.raises(argparse.ArgumentTypeError, match=says):
            read_real(bad, name="--t", **({"high": 10} | kwargs))
    assert read_real("0", name="--x", low=0, low_open=False, high=Fraction(1, 2)) == 0.0


def test_tuples():
    assert read_reals("0,-1.5,2", name="--z0", size=3, bound=10) == (0.0, -1.5, 2.0)
    with pytest.raises(argparse.ArgumentTypeError, match="--z0 takes three numbers, comma-separated; got 2 in '1,2'"):
        read_reals("1,2", name="--z0", size=3, bound=10)
    with pytest.raises(argparse.ArgumentTypeError, match=r"must lie in \[-10, 10\]; got '11'"):
        read_reals("0,11,0", name="--z0", size=3, bound=10)


def test_option_types_make_usage_errors(capsys):
    parser = argparse.ArgumentParser(prog="p")
    parser.add_argument("--n", type=count_option("--n", high=5))
    parser.add_argument("--t", type=real_option("--t", high=5))
    assert vars(parser.parse_args(["--n", "5", "--t", "2.5"])) == {"n": 5, "t": 2.5}
    for argv in (["--n", "6"], ["--t", "nan"]):
        with pytest.raises(SystemExit) as exc:
            parser.parse_args(argv)
        assert exc.value.code == 2
    assert "argument --t: --t must be finite" in capsys.readouterr().err
