# Handlers of asset Oddity: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of Oddity, called by the rapid_runtime bridge
(`python -m rapid_oddity.bridge`).

One method per command, with the command's arguments by name. Return normally for
COMPLETED/OK (a returned string becomes Ack.message, at most 127 bytes); raise
CommandFailed("why") for COMPLETED/EXEC_FAILED. A method runs in its own thread: it may
run long, report progress with ctx.progress("..."), and should stop when
ctx.cancelled is set (ctx.sleep(s) returns False then). Arguments were already checked
against the descriptor (types, ranges, allowed values). The standard Admin, Queue and
AccessControl commands are answered by the runtime.
"""

from __future__ import annotations

from rapid_runtime.handlers import CommandContext, CommandFailed, Handlers as _Base


class Handlers(_Base):

    def queue_load_macro(self, ctx: CommandContext, name: str) -> str | None:
        """Queue/loadMacro: queue the commands of a named macro

        Subsystems: Queue.

        name (RAPID_STRING): name of a macro known to the asset
        """
        raise CommandFailed("not implemented")

    def winch_reel_out(self, ctx: CommandContext, length: float) -> str | None:
        """Winch/reelOut: no description

        Subsystems: Winch.

        length (RAPID_FLOAT) [m] range [0, inf]
        """
        raise CommandFailed("not implemented")

    def winch_set_tension(self, ctx: CommandContext, tension: int) -> str | None:
        """Winch/setTension: no description

        Subsystems: Winch.

        tension (RAPID_INT) [N] range [-inf, 100]
        """
        raise CommandFailed("not implemented")

    def winch_set_offset(self, ctx: CommandContext, offset: list[float]) -> str | None:
        """Winch/setOffset: no description

        Subsystems: Winch.

        offset (RAPID_VEC3d) [m] range [-1, inf]
        """
        raise CommandFailed("not implemented")

    def winch_cancel_all(self, ctx: CommandContext) -> str | None:
        """Winch/cancelAll: lets go of the winch's own pending moves (not the command queue's cancelAll)

        Subsystems: Winch.
        """
        raise CommandFailed("not implemented")
