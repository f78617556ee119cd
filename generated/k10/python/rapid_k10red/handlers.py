# Handlers of asset K10Red: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of K10Red, called by the rapid_runtime bridge
(`python -m rapid_k10red.bridge`).

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

    def pan_tilt_camera_point_camera(self, ctx: CommandContext, pan: float, tilt: float) -> str | None:
        """PanTiltCamera/pointCamera: point the pan-tilt unit

        Subsystems: PanCam. Abortable: watch ctx.cancelled.

        pan (RAPID_FLOAT) [rad] range [-3.05, 3.05] default 0
        tilt (RAPID_FLOAT) [rad] range [-1.4, 1.4] default 0
        """
        raise CommandFailed("not implemented")

    def pan_tilt_camera_take_picture(self, ctx: CommandContext, mode: str, exposure: float) -> str | None:
        """PanTiltCamera/takePicture: acquire an image; it arrives on the camera's image topics

        Subsystems: PanCam.

        mode (RAPID_STRING) one of left, right, stereo default 'stereo'
        exposure (RAPID_FLOAT) [ms] range [0, 2000] default 0: 0 = auto exposure
        """
        raise CommandFailed("not implemented")

    def pan_tilt_camera_take_panorama(self, ctx: CommandContext, pan_start: float, pan_end: float, tilt: float, tiles: int) -> str | None:
        """PanTiltCamera/takePanorama: a tiled panorama between two pan angles

        Subsystems: PanCam. Abortable and suspendable: watch ctx.cancelled.

        pan_start (panStart, RAPID_FLOAT) [rad] range [-3.05, 3.05]
        pan_end (panEnd, RAPID_FLOAT) [rad] range [-3.05, 3.05]
        tilt (RAPID_FLOAT) [rad] range [-1.4, 1.4]
        tiles (RAPID_INT) range [1, 64] default 8
        """
        raise CommandFailed("not implemented")

    def k10_native_native_command(self, ctx: CommandContext, text: str) -> str | None:
        """K10Native/nativeCommand: a K10 command line, passed to the rover executive as-is

        Subsystems: K10Native.

        text (RAPID_STRING): native command text, passed to the asset unchanged
        """
        raise CommandFailed("not implemented")
