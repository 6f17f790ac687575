"""Sphinx directive ``tolalloc-cli``: the command-line reference drawn from the real argparse parsers.

``{tolalloc-cli} allocate`` renders the usage line, the description and a table of every argument of
``tolalloc allocate`` from :func:`tolalloc.cli.build_parser`; ``{tolalloc-cli} commands`` the table of commands.
Help texts are inserted as plain text (never parsed as markup), so ``P(|dP| < r)`` stays what it is and the
reference cannot drift from ``tolalloc COMMAND --help``.
"""

from __future__ import annotations

import argparse

from docutils import nodes
from docutils.parsers.rst import Directive


def _subparsers(parser):
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help for c in action._choices_actions}
    return action.choices, helps


def _table(header, rows):
    table = nodes.table(classes=["tolalloc-cli"])
    group = nodes.tgroup(cols=len(header))
    table += group
    for width in (30, 70)[: len(header)]:
        group += nodes.colspec(colwidth=width)
    head = nodes.thead()
    group += head
    head += _row([nodes.paragraph(text=h) for h in header])
    body = nodes.tbody()
    group += body
    for cells in rows:
        body += _row(cells)
    return table


def _row(cells):
    row = nodes.row()
    for cell in cells:
        entry = nodes.entry()
        entry += cell
        row += entry
    return row


def _literal_cell(text):
    para = nodes.paragraph()
    para += nodes.literal(text=text)
    return para


class TolallocCli(Directive):
    """``.. tolalloc-cli:: COMMAND`` (or ``commands``)."""

    required_arguments = 1
    has_content = False

    def run(self):
        from tolalloc.cli import build_parser

        parser = build_parser()
        choices, helps = _subparsers(parser)
        name = self.arguments[0]
        if name == "commands":
            rows = [[_literal_cell(f"tolalloc {c}"), nodes.paragraph(text=helps.get(c) or "")] for c in choices]
            return [_table(["command", "what it does"], rows)]
        if name not in choices:
            raise self.error(f"tolalloc-cli: unknown command {name!r}; known: {', '.join(choices)}")
        sub = choices[name]
        usage = nodes.literal_block(text=sub.format_usage().strip())
        usage["language"] = "text"
        out = [usage]
        if sub.description:
            out.append(nodes.paragraph(text=sub.description))
        formatter = sub._get_formatter()
        rows = []
        for action in sub._actions:
            if isinstance(action, argparse._HelpAction):
                continue
            invocation = formatter._format_action_invocation(action)
            text = formatter._expand_help(action) if action.help else ""
            if action.choices and not isinstance(action, argparse._SubParsersAction):
                text += ("; " if text else "") + "one of " + ", ".join(map(str, action.choices))
            rows.append([_literal_cell(invocation), nodes.paragraph(text=text)])
        out.append(_table(["argument", "meaning"], rows))
        return out


def setup(app):
    app.add_directive("tolalloc-cli", TolallocCli)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
