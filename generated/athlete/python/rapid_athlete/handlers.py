# Handlers of asset ATHLETE: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of ATHLETE, called by the rapid_runtime bridge
(`python -m rapid_athlete.bridge`).

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

    def queue_load_macro(self, ctx: CommandContext, name: str) -> str | None:
        """Queue/loadMacro: queue the commands of a named macro

        Subsystems: Queue.

        name (RAPID_STRING): name of a macro known to the asset
        """
        raise CommandFailed("not implemented")

    def limb_controller_move_foot(self, ctx: CommandContext, limb: int, xyz: list[float], frame: str) -> str | None:
        """LimbController/moveFoot: move one foot (wheel) to a position

        Subsystems: Limbs. Abortable and suspendable: watch ctx.cancelled.

        limb (RAPID_INT) range [1, 6]
        xyz (RAPID_VEC3d) [m] range [-4, 4]: foot position
        frame (RAPID_STRING) one of deck, site default 'deck'
        """
        raise CommandFailed("not implemented")

    def limb_controller_set_limb_joints(self, ctx: CommandContext, limb: int, hip_yaw: float, hip_pitch: float, knee_pitch: float, ankle_pitch: float, ankle_yaw: float, ankle_roll: float) -> str | None:
        """LimbController/setLimbJoints: set the six joints of one limb

        Subsystems: Limbs. Abortable: watch ctx.cancelled.

        limb (RAPID_INT) range [1, 6]
        hip_yaw (hipYaw, RAPID_FLOAT) [rad] range [-2.6, 2.6]
        hip_pitch (hipPitch, RAPID_FLOAT) [rad] range [-1.6, 1.6]
        knee_pitch (kneePitch, RAPID_FLOAT) [rad] range [-2.5, 2.5]
        ankle_pitch (anklePitch, RAPID_FLOAT) [rad] range [-2.0, 2.0]
        ankle_yaw (ankleYaw, RAPID_FLOAT) [rad] range [-2.6, 2.6]
        ankle_roll (ankleRoll, RAPID_FLOAT) [rad] range [-1.6, 1.6]
        """
        raise CommandFailed("not implemented")

    def limb_controller_set_stance(self, ctx: CommandContext, stance: str) -> str | None:
        """LimbController/setStance: all six limbs to a named stance

        Subsystems: Limbs. Abortable: watch ctx.cancelled.

        stance (RAPID_STRING) one of drive, walk, stow, lowDeck default 'drive'
        """
        raise CommandFailed("not implemented")

    def limb_controller_walk(self, ctx: CommandContext, gait: str, distance: float, heading: float) -> str | None:
        """LimbController/walk: walk a distance with the current gait

        Subsystems: Limbs. Abortable and suspendable: watch ctx.cancelled.

        gait (RAPID_STRING) one of tripod, wave default 'tripod'
        distance (RAPID_DOUBLE) [m] range [0, 50]
        heading (RAPID_DOUBLE) [rad] range [-3.14159, 3.14159] default 0
        """
        raise CommandFailed("not implemented")

    def limb_controller_lock_wheels(self, ctx: CommandContext, locked: bool) -> str | None:
        """LimbController/lockWheels: no description

        Subsystems: Limbs.

        locked (RAPID_BOOL) default True
        """
        raise CommandFailed("not implemented")

    def deck_level_deck(self, ctx: CommandContext) -> str | None:
        """Deck/levelDeck: no description

        Subsystems: Deck. Abortable: watch ctx.cancelled.
        """
        raise CommandFailed("not implemented")

    def deck_set_deck_height(self, ctx: CommandContext, height: float) -> str | None:
        """Deck/setDeckHeight: no description

        Subsystems: Deck. Abortable: watch ctx.cancelled.

        height (RAPID_DOUBLE) [m] range [0.8, 2.5] default 1.5
        """
        raise CommandFailed("not implemented")

    def athlete_native_athlete_command(self, ctx: CommandContext, command: str) -> str | None:
        """AthleteNative/athleteCommand: an ATHLETE Workbench command, handed to the ATHLETE Bridge untranslated

        Subsystems: AthleteNative.

        command (RAPID_STRING): native command text, passed to the asset unchanged
        """
        raise CommandFailed("not implemented")
