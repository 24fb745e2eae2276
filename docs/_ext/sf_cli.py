"""The CLI reference, generated from the package's own argparse parser at build time.

``.. symbolic-friction-cli::`` (MyST: a ```` ```{symbolic-friction-cli} ```` fence) renders every
command of :func:`symbolic_friction._cli.main.build_parser`: a section per command with its help,
its usage line, every option (its flags, metavar, choices and help text) by argument group, in
the order the parser declares them, and its epilog (the examples ``--help`` prints).  Nothing is
written by hand, so the page cannot drift from ``--help``.
"""

from __future__ import annotations

import argparse
import os
from contextlib import contextmanager

from docutils import nodes
from docutils.parsers.rst import Directive

PROG = "symbolic-friction"
WIDTH = "88"  # the usage lines are wrapped as on an 88-column terminal


@contextmanager
def _columns(width: str):
    """argparse wraps at the terminal's width (``COLUMNS``): fix it, so the page does not depend on the build host."""
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = width
    try:
        yield
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


def build_parser() -> argparse.ArgumentParser:
    from symbolic_friction._cli.main import build_parser as build

    with _columns(WIDTH):
        return build()


def subcommands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """``{command: its parser}``, in the order the parser declares them."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices.items())
    raise RuntimeError("the parser has no subcommands")


def _help_text(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    with _columns(WIDTH):
        formatter = parser._get_formatter()
    text = formatter._expand_help(action) if action.help else ""
    return " ".join(text.split())


def _flags(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    with _columns(WIDTH):
        formatter = parser._get_formatter()
    if not action.option_strings:
        return formatter._metavar_formatter(action, action.dest)(1)[0]
    if action.nargs == 0:
        return ", ".join(action.option_strings)
    metavar = formatter._format_args(action, action.dest.upper())
    return ", ".join(f"{flag} {metavar}" for flag in action.option_strings)


def _usage(parser: argparse.ArgumentParser) -> str:
    with _columns(WIDTH):
        return parser.format_usage().strip()


def _option_list(parser: argparse.ArgumentParser, actions: list[argparse.Action]) -> nodes.definition_list:
    items = nodes.definition_list()
    for action in actions:
        if action.help == argparse.SUPPRESS:
            continue
        flags = _flags(parser, action)
        term = nodes.term()
        term += nodes.literal(text=flags)
        body = nodes.definition()
        text = _help_text(parser, action)
        if action.choices and not isinstance(action, argparse._SubParsersAction) and "{" not in flags:
            choices = ", ".join(str(c) for c in action.choices)
            if choices not in text:
                text = f"{text} (one of: {choices})" if text else f"one of: {choices}"
        body += nodes.paragraph(text=text or "(no help text)")
        item = nodes.definition_list_item()
        item += term
        item += body
        items += item
    return items


def _groups(parser: argparse.ArgumentParser) -> list[nodes.Node]:
    """Each argument group of ``parser`` (positional arguments, options, and any group a command adds), as
    ``--help`` shows them, then its epilog (the commands' examples) verbatim."""
    out: list[nodes.Node] = []
    for group in parser._action_groups:
        actions = [a for a in group._group_actions if a.help != argparse.SUPPRESS
                   and not isinstance(a, argparse._SubParsersAction)]
        if not actions:
            continue
        out.append(nodes.rubric(text=group.title or "options"))
        if group.description:
            out.append(nodes.paragraph(text=" ".join(group.description.split())))
        out.append(_option_list(parser, actions))
    if parser.epilog:
        out.append(nodes.rubric(text="More"))
        out.append(nodes.literal_block(text=parser.epilog.strip("\n"), language="text"))
    return out


class CliReference(Directive):
    """Every command of the ``symbolic-friction`` parser, as sections of the current page."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        parser = build_parser()
        out: list[nodes.Node] = []
        intro = nodes.section(ids=["cli-overview"], names=[PROG])
        intro += nodes.title(text=f"{PROG}")
        intro += nodes.paragraph(text=" ".join((parser.description or "").split()))
        intro += nodes.literal_block(text=_usage(parser), language="text")
        intro += _groups(parser)
        commands = nodes.bullet_list()
        for name, sub in subcommands(parser).items():
            para = nodes.paragraph()
            ref = nodes.reference(refid=f"cli-{name}")
            ref += nodes.literal(text=f"{PROG} {name}")
            para += ref
            para += nodes.Text(f": {' '.join((sub.description or '').split())}")
            commands += nodes.list_item("", para)
        intro += commands
        out.append(intro)
        for name, sub in subcommands(parser).items():
            section = nodes.section(ids=[f"cli-{name}"], names=[f"{PROG} {name}"])
            section += nodes.title(text=f"{PROG} {name}")
            section += nodes.paragraph(text=" ".join((sub.description or "").split()))
            section += nodes.literal_block(text=_usage(sub), language="text")
            section += _groups(sub)
            self.state.document.note_implicit_target(section, section)
            out.append(section)
        return out


def setup(app):
    app.add_directive("symbolic-friction-cli", CliReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
