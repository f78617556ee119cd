# Handlers of asset XArm2: written once by rapidgen, yours to edit.
# Regeneration never touches this file (delete it to get fresh stubs).
"""Command handlers of XArm2, called by the rapid_runtime bridge
(`python -m rapid_xarm2.bridge`).

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

    def exoskeleton_enable_force_feedback(self, ctx: CommandContext, enabled: bool) -> str | None:
        """Exoskeleton/enableForceFeedback: no description

        Subsystems: RightArmExo.

        enabled (RAPID_BOOL) default False
        """
        raise CommandFailed("not implemented")

    def exoskeleton_set_joint_torques(self, ctx: CommandContext, shoulder_abduction: float, shoulder_flexion: float, shoulder_rotation: float, elbow_flexion: float, forearm_rotation: float, wrist_flexion: float, wrist_deviation: float) -> str | None:
        """Exoskeleton/setJointTorques: torques fed back to the operator, one per joint

        Subsystems: RightArmExo.

        shoulder_abduction (shoulderAbduction, RAPID_FLOAT) [N*m] range [-10, 10] default 0
        shoulder_flexion (shoulderFlexion, RAPID_FLOAT) [N*m] range [-10, 10] default 0
        shoulder_rotation (shoulderRotation, RAPID_FLOAT) [N*m] range [-6, 6] default 0
        elbow_flexion (elbowFlexion, RAPID_FLOAT) [N*m] range [-8, 8] default 0
        forearm_rotation (forearmRotation, RAPID_FLOAT) [N*m] range [-2, 2] default 0
        wrist_flexion (wristFlexion, RAPID_FLOAT) [N*m] range [-2, 2] default 0
        wrist_deviation (wristDeviation, RAPID_FLOAT) [N*m] range [-2, 2] default 0
        """
        raise CommandFailed("not implemented")

    def exoskeleton_set_scaling(self, ctx: CommandContext, factor: float) -> str | None:
        """Exoskeleton/setScaling: scale from operator motion to the commanded robot motion

        Subsystems: RightArmExo.

        factor (RAPID_DOUBLE) range [0.1, 2.0] default 1.0
        """
        raise CommandFailed("not implemented")
