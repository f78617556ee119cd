# Handlers of asset Chariot: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of Chariot, called by the rapid_runtime bridge
(`python -m rapid_chariot.bridge`).

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

    def mobility_stop_all_motion(self, ctx: CommandContext) -> str | None:
        """Mobility/stopAllMotion: stop every motion now

        Subsystems: Mobility.

        The runtime has already canceled every Mobility command; stop the hardware here.
        """
        raise CommandFailed("not implemented")

    def mobility_simple_move(self, ctx: CommandContext, frame: str, xyt: list[float]) -> str | None:
        """Mobility/simpleMove: drive to x, y and heading in frame

        Subsystems: Mobility. Abortable and suspendable: watch ctx.cancelled.

        frame (RAPID_STRING): reference frame of the goal (e.g. RAPID_SITE_FRAME 'site')
        xyt (RAPID_VEC3d) [m, m, rad]: goal x [m], y [m], heading [rad]
        """
        raise CommandFailed("not implemented")

    def mobility_move(self, ctx: CommandContext, frame: str, xyt: list[float], xyt_tolerance: list[float]) -> str | None:
        """Mobility/move: drive to x, y and heading in frame, within tolerances

        Subsystems: Mobility. Abortable and suspendable: watch ctx.cancelled.

        frame (RAPID_STRING): reference frame of the goal (e.g. RAPID_SITE_FRAME 'site')
        xyt (RAPID_VEC3d) [m, m, rad]: goal x [m], y [m], heading [rad]
        xyt_tolerance (xytTolerance, RAPID_VEC3d) [m, m, rad]: tolerance x [m], y [m], heading [rad]; negative = asset default
        """
        raise CommandFailed("not implemented")

    def mobility_move6_dof(self, ctx: CommandContext, frame: str, xyz: list[float], rot: list[float]) -> str | None:
        """Mobility/move6DOF: move to a full pose in frame

        Subsystems: Mobility. Abortable and suspendable: watch ctx.cancelled.

        frame (RAPID_STRING): reference frame of the goal (e.g. RAPID_SITE_FRAME 'site')
        xyz (RAPID_VEC3d) [m]: goal position
        rot (RAPID_MAT33f): goal orientation, row-major rotation matrix
        """
        raise CommandFailed("not implemented")

    def chariot_drive_set_steering_mode(self, ctx: CommandContext, mode: str) -> str | None:
        """ChariotDrive/setSteeringMode: no description

        Subsystems: Drive.

        mode (RAPID_STRING) one of ackermann, crab, skid, turnInPlace default 'ackermann'
        """
        raise CommandFailed("not implemented")

    def chariot_drive_set_speed_limit(self, ctx: CommandContext, speed: float) -> str | None:
        """ChariotDrive/setSpeedLimit: no description

        Subsystems: Drive.

        speed (RAPID_FLOAT) [m/s] range [0, 4.2] default 1.5
        """
        raise CommandFailed("not implemented")

    def chariot_drive_set_ride_height(self, ctx: CommandContext, height: float) -> str | None:
        """ChariotDrive/setRideHeight: active suspension height above the ground

        Subsystems: Drive. Abortable: watch ctx.cancelled.

        height (RAPID_FLOAT) [m] range [0.3, 0.8] default 0.5
        """
        raise CommandFailed("not implemented")

    def turret_rotate_turret(self, ctx: CommandContext, angle: float) -> str | None:
        """Turret/rotateTurret: no description

        Subsystems: Turret. Abortable: watch ctx.cancelled.

        angle (RAPID_FLOAT) [rad] range [-3.14159, 3.14159]
        """
        raise CommandFailed("not implemented")

    def chariot_native_ccmd(self, ctx: CommandContext, command: str) -> str | None:
        """ChariotNative/ccmd: a CCMD command string, forwarded to the vehicle socket as-is

        Subsystems: ChariotNative.

        command (RAPID_STRING): native command text, passed to the asset unchanged
        """
        raise CommandFailed("not implemented")
