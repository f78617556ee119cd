"""A received command against the asset's dictionary, in soraCore's order: subsystem,
command, argument count, each argument's union discriminator, then the descriptor's
limits (range, allowed values). Returns a reason for COMPLETED/BAD_SYNTAX, or None."""
from __future__ import annotations

from rapid_runtime import texts
from rapid_runtime.command import Cmd
from rapid_runtime.tables import CommandEntry, Tables
from rapid_runtime.values import limit_error, shape_error


def _short(text: str, n: int = 24) -> str:
    """A name from the wire, shortened so the reason stays readable within 127 bytes."""
    text = text if text.isprintable() else text.encode("unicode_escape").decode("ascii")
    return text if len(text) <= n else text[:n - 3] + "..."


def check_command(cmd: Cmd, tables: Tables) -> tuple[CommandEntry | None, str | None]:
    """(entry, None) for a valid command, (entry or None, reason) for an invalid one."""
    if tables.type_of(cmd.subsystem) is None:
        return None, texts.unknown_subsystem(_short(cmd.subsystem))
    entry = tables.command(cmd.subsystem, cmd.name)
    if entry is None:
        return None, texts.unknown_command(_short(cmd.name), _short(cmd.subsystem))
    if len(cmd.args) != len(entry.params):
        if len(entry.params) == 1:
            return entry, texts.argument_count_one(entry.name, len(cmd.args))
        return entry, texts.argument_count(entry.name, len(entry.params), len(cmd.args))
    for i, (p, (dtype, _)) in enumerate(zip(entry.params, cmd.args)):
        if dtype != p.type:
            return entry, texts.argument_type(i + 1, _short(p.name, 16), p.type, dtype)
    for i, (p, (_, value)) in enumerate(zip(entry.params, cmd.args)):
        why = shape_error(p.type, value) or limit_error(p, value)
        if why:
            return entry, texts.argument_invalid(i + 1, _short(p.name, 16), why)
    return entry, None


def kwargs_of(entry: CommandEntry, cmd: Cmd) -> dict:
    """The handler's keyword arguments: parameter names -> the values sent, by position."""
    return {p.arg: value for p, (_, value) in zip(entry.params, cmd.args)}
