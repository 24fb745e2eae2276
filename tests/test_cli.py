"""CLI start-up: fast and free of heavy imports."""

import subprocess
import sys

import pytest

from symbolic_friction._cli.main import COMMANDS, build_parser, main

HEAVY = ("sympy", "scipy", "cvxpy", "matplotlib", "clarabel")


def test_help_imports_nothing_heavy():
    code = (
        "import sys, contextlib, io\n"
        "from symbolic_friction._cli.main import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n        main(['--help'])\n    except SystemExit:\n        pass\n"
        f"print(sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_every_command_has_help():
    parser = build_parser()
    text = parser.format_help()
    for name in COMMANDS:
        assert name in text


def test_unknown_command_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["no-such-command"])
    assert exc.value.code == 2
    assert "invalid choice" in capsys.readouterr().err


def test_a_bare_command_prints_the_help(capsys):
    assert main([]) == 0
    captured = capsys.readouterr()
    assert captured.out.startswith("usage: symbolic-friction") and "COMMAND" in captured.out and captured.err == ""


@pytest.mark.parametrize("value", ["-1,0,0", "-3/5,0,0", "-.5,-1e-3,0", "-1"])
def test_negative_tuples_are_values_not_options(value):
    args = build_parser().parse_args(["tradeoff", "--z0", value])
    assert args.z0 == [value]


def test_an_unknown_dash_option_is_still_refused(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["tradeoff", "--z0", "-x,0,0"])
    assert exc.value.code == 2 and "expected one argument" in capsys.readouterr().err
