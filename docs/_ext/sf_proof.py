"""The proof's obligations and the paper's errata, rendered from the package at build time.

``sf-obligations`` renders :func:`symbolic_friction.all_obligations` as a table (id, where in the
paper, statement, method: what ``symbolic-friction check`` decides); ``sf-errata`` renders
:func:`symbolic_friction.all_errata` (where, what the paper says, what is correct, which obligation
checks it).  Neither runs an obligation: the pages list what ``check`` proves, they do not prove it.
"""

from __future__ import annotations

from docutils import nodes
from docutils.parsers.rst import Directive


def _row(*cells: nodes.Node | str) -> nodes.row:
    row = nodes.row()
    for cell in cells:
        entry = nodes.entry()
        entry += cell if isinstance(cell, nodes.Node) else nodes.paragraph(text=cell)
        row += entry
    return row


def _table(headers: tuple[str, ...], widths: tuple[int, ...], rows: list[nodes.row]) -> nodes.table:
    table = nodes.table(classes=["sf-generated"])
    group = nodes.tgroup(cols=len(headers))
    table += group
    for width in widths:
        group += nodes.colspec(colwidth=width)
    head = nodes.thead()
    head += _row(*headers)
    group += head
    body = nodes.tbody()
    for row in rows:
        body += row
    group += body
    return table


def _literal(text: str) -> nodes.paragraph:
    para = nodes.paragraph()
    para += nodes.literal(text=text)
    return para


class Obligations(Directive):
    """A table of every proof obligation ``check`` decides, in the package's (the paper's) order."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from symbolic_friction import all_obligations

        rows = [_row(_literal(o.id), o.paper, o.statement, o.method) for o in all_obligations()]
        return [_table(("id", "paper", "statement", "method"), (18, 18, 40, 24), rows)]


class Errata(Directive):
    """Every place where the paper's text is wrong, with the corrected statement and the obligation that checks it."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        from symbolic_friction import all_errata

        items = nodes.enumerated_list()
        for erratum in all_errata():
            item = nodes.list_item()
            where = nodes.paragraph()
            where += nodes.strong(text=erratum.where)
            item += where
            says = nodes.paragraph()
            says += nodes.emphasis(text="The paper says: ")
            says += nodes.Text(erratum.paper_says)
            item += says
            correct = nodes.paragraph()
            correct += nodes.emphasis(text="Correct: ")
            correct += nodes.Text(erratum.correct)
            item += correct
            checked = nodes.paragraph()
            checked += nodes.emphasis(text="Checked by: ")
            for i, name in enumerate(part.strip() for part in erratum.checked_by.split(",")):
                if i:
                    checked += nodes.Text(", ")
                checked += nodes.literal(text=name)
            item += checked
            items += item
        return [items]


def setup(app):
    app.add_directive("sf-obligations", Obligations)
    app.add_directive("sf-errata", Errata)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
