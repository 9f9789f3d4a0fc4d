"""The command line's reference page: every ``seacable`` command, its usage, what it does and
its options, from the commands themselves (click). docs/conf.py writes it as
docs/reference/cli.md at each build."""

import inspect

import click

from seacable.cli import main


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def cli_md() -> str:
    out = [
        "# Command line",
        "",
        "Every command of `seacable`, as `seacable COMMAND --help` prints it. A command that "
        "fails prints one line on stderr and exits with 2 (the input: the case, an option, a "
        "file), 3 (a run that diverged), 130 or 143 (interrupted; the rows computed are kept) "
        "or 1 (a bug in seacable, said so; `seacable --debug ...` shows the traceback).",
        "",
    ]
    with click.Context(main, info_name="seacable") as root:
        out += _options(main, root)
        for name in main.list_commands(root):
            command = main.get_command(root, name)
            assert command is not None
            with click.Context(command, info_name=name, parent=root) as ctx:
                out += [f"## seacable {name}", ""]
                usage = " ".join(["seacable", name, *command.collect_usage_pieces(ctx)])
                out += ["```text", usage, "```", ""]
                out += [_paragraphs(command.help or ""), ""]
                out += _options(command, ctx)
    return "\n".join(out) + "\n"


def _paragraphs(text: str) -> str:
    """A command's docstring as Markdown paragraphs (click's \\b marks dropped)."""
    text = inspect.cleandoc(click.unstyle(text).replace("\b\n", ""))
    return "\n\n".join(" ".join(p.split()) for p in text.split("\n\n"))


def _options(command: click.Command, ctx: click.Context) -> list[str]:
    rows = [p.get_help_record(ctx) for p in command.get_params(ctx) if isinstance(p, click.Option)]
    rows = [r for r in rows if r is not None]
    if not rows:
        return []
    out = ["| option | meaning |", "| --- | --- |"]
    out += [f"| `{_cell(opts)}` | {_cell(text)} |" for opts, text in rows]
    return [*out, ""]
