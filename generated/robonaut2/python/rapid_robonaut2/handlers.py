# Handlers of asset Robonaut2: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of Robonaut2, called by the rapid_runtime bridge
(`python -m rapid_robonaut2.bridge`).

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

    def arm_setpoint_for_tool(self, ctx: CommandContext, xyz: list[float], rpy: list[float], frame: str) -> str | None:
        """Arm/Setpoint for Tool: move the tool (hand) to a cartesian pose

        Subsystems: LeftArm, RightArm. Abortable: watch ctx.cancelled.

        xyz (RAPID_VEC3d) [m]: X, Y, Z coordinates
        rpy (RAPID_VEC3d) [rad] range [-3.141592653589793, 3.141592653589793]: roll, pitch, yaw
        frame (RAPID_STRING) default 'R2OriginFrame': reference frame, e.g. R2OriginFrame
        """
        raise CommandFailed("not implemented")

    def arm_setpoint_for_single_joint(self, ctx: CommandContext, abduction: float, extension: float, upper_arm_outer_rotation: float, elbow_flexion: float, forearm_outer_rotation: float, wrist_flexion: float, wrist_ulnar_flexion: float) -> str | None:
        """Arm/Setpoint for single joint: set every joint of the arm

        Subsystems: LeftArm, RightArm. Abortable: watch ctx.cancelled.

        abduction (RAPID_FLOAT) [rad]: abduction
        extension (RAPID_FLOAT) [rad]: extension
        upper_arm_outer_rotation (upperArmOuterRotation, RAPID_FLOAT) [rad]: upper arm outer rotation
        elbow_flexion (elbowFlexion, RAPID_FLOAT) [rad]: elbow flexion
        forearm_outer_rotation (forearmOuterRotation, RAPID_FLOAT) [rad]: forearm outer rotation
        wrist_flexion (wristFlexion, RAPID_FLOAT) [rad]: wrist flexion
        wrist_ulnar_flexion (wristUlnarFlexion, RAPID_FLOAT) [rad]: wrist ulnar flexion
        """
        raise CommandFailed("not implemented")

    def neck_setpoint_for_single_joint(self, ctx: CommandContext, lower_pitch: float, yaw: float, upper_pitch: float) -> str | None:
        """Neck/Setpoint for single joint: set every joint of the neck

        Subsystems: Neck. Abortable: watch ctx.cancelled.

        lower_pitch (lowerPitch, RAPID_FLOAT) [rad] range [-1.2, 0.6]: lower neck pitch
        yaw (RAPID_FLOAT) [rad] range [-1.5, 1.5]: neck yaw
        upper_pitch (upperPitch, RAPID_FLOAT) [rad] range [-0.6, 0.6]: upper neck pitch
        """
        raise CommandFailed("not implemented")

    def hand_open_the_hand(self, ctx: CommandContext) -> str | None:
        """Hand/Open the Hand: open all fingers

        Subsystems: LeftHand, RightHand. Abortable: watch ctx.cancelled.
        """
        raise CommandFailed("not implemented")

    def hand_close_the_hand(self, ctx: CommandContext) -> str | None:
        """Hand/Close the Hand: close all fingers (power grasp)

        Subsystems: LeftHand, RightHand. Abortable: watch ctx.cancelled.
        """
        raise CommandFailed("not implemented")
