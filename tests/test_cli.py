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


def _entry(args: list[str], prelude: str = "") -> subprocess.CompletedProcess:
    code = ("import atexit, sys\n" + prelude
            + f"sys.argv = ['symbolic-friction'] + {args!r}\n"
            "from symbolic_friction.cli import entry_point\nentry_point()\nprint('not reached')\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)


def test_the_entry_point_exits_with_the_commands_code_after_atexit_handlers_and_flushed_output():
    # the entry point skips the interpreter's teardown (exit_without_teardown): what a user sees must not change
    run = _entry(["verify", "/nonexistent/none.json"],
                 "atexit.register(lambda: sys.stdout.write('atexit handler ran\\n'))\nprint('buffered line', end='\\n')\n")
    assert run.returncode == 2
    assert run.stdout == "buffered line\natexit handler ran\n"  # the buffered line flushed, the handler run, once
    assert run.stderr.startswith("symbolic-friction verify: error:") and "Traceback" not in run.stderr
    assert "not reached" not in run.stdout


def test_the_entry_point_waits_for_other_threads_as_the_interpreter_would():
    prelude = ("import threading, time\n"
               "threading.Thread(target=lambda: (time.sleep(0.3), print('thread finished', flush=True))).start()\n")
    run = _entry(["verify", "/nonexistent/none.json"], prelude)
    assert run.returncode == 2 and run.stdout == "thread finished\n"


def test_the_entry_point_passes_a_zero_exit_code_and_large_output_through_a_pipe():
    run = _entry(["simulate", "--help"])  # argparse's own exit (SystemExit) takes the interpreter's ordinary path
    assert run.returncode == 0 and "usage:" in run.stdout
    run = _entry(["simulate", "--list"])
    assert run.returncode == 0, run.stderr
    assert run.stdout.count("\n") > 5 and run.stdout.endswith("\n")
