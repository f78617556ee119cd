"""The standard RAPID subsystem types, usable by reference from any descriptor.

Names, commands, parameter names, order and DataTypes follow specs/rapid/CommandConstants.idl
(GROUP, GROUP_METHOD_X, GROUP_METHOD_X_PARAM_Y, GROUP_METHOD_X_DTYPE_Y); a test keeps the
two in step. Units, flags and descriptions are rapidgen's, for `describe` and generated docs.
"""
from __future__ import annotations

from rapidgen.asset.spec import CommandSpec, Parameter, SubsystemTypeSpec
from rapidgen.diagnostics import SourceLoc

_LOC = SourceLoc("<standard RAPID subsystems>", 0, 0)


def _p(name: str, type_: str, unit: str | None = None, description: str = "") -> Parameter:
    return Parameter(name=name, type=type_, unit=unit, description=description, loc=_LOC)


def _c(name: str, description: str, *params: Parameter, abortable: bool = False,
       suspendable: bool = False) -> CommandSpec:
    return CommandSpec(name=name, description=description, abortable=abortable,
                       suspendable=suspendable, parameters=params, loc=_LOC)


def _t(name: str, description: str, *commands: CommandSpec) -> SubsystemTypeSpec:
    return SubsystemTypeSpec(name=name, description=description, commands=commands,
                             standard=True, loc=_LOC)


_FRAME = _p("frame", "RAPID_STRING", None, "reference frame of the goal (e.g. RAPID_SITE_FRAME 'site')")

STANDARD_TYPES: dict[str, SubsystemTypeSpec] = {t.name: t for t in (
    _t("Admin", "asset administration",
       _c("echo", "complete OK, copying text into Ack.message",
          _p("text", "RAPID_STRING", None, "text to echo (Ack.message holds 127 bytes)")),
       _c("shutdown", "shut the asset's RAPID interface down"),
       _c("noOp", "do nothing; tests the command path")),
    _t("Mobility", "driving the asset",
       _c("stopAllMotion", "stop every motion now"),
       # Moves can be stopped (abortable) and paused (suspendable) by the asset's queue.
       _c("simpleMove", "drive to x, y and heading in frame", _FRAME,
          _p("xyt", "RAPID_VEC3d", "m, m, rad", "goal x [m], y [m], heading [rad]"),
          abortable=True, suspendable=True),
       _c("move", "drive to x, y and heading in frame, within tolerances", _FRAME,
          _p("xyt", "RAPID_VEC3d", "m, m, rad", "goal x [m], y [m], heading [rad]"),
          _p("xytTolerance", "RAPID_VEC3d", "m, m, rad",
             "tolerance x [m], y [m], heading [rad]; negative = asset default"),
          abortable=True, suspendable=True),
       _c("move6DOF", "move to a full pose in frame", _FRAME,
          _p("xyz", "RAPID_VEC3d", "m", "goal position"),
          _p("rot", "RAPID_MAT33f", None, "goal orientation, row-major rotation matrix"),
          abortable=True, suspendable=True)),
    _t("ImageSensor", "a camera; no standard commands (extend it with the asset's own)"),
    _t("Queue", "the asset's command queue",
       _c("cancelAll", "cancel every pending and active command"),
       _c("loadMacro", "queue the commands of a named macro",
          _p("name", "RAPID_STRING", None, "name of a macro known to the asset"))),
    _t("AccessControl", "who may command the asset",
       _c("requestControl", "ask the controller for control (the requestor is cmdSrc)"),
       _c("grabControl", "take control without asking"),
       _c("releaseControl", "give control up"),
       _c("transferControl", "hand control to another source",
          _p("newController", "RAPID_STRING", None, "cmdSrc of the new controller (String32: 31 bytes)"))),
)}

# Message types published implicitly by an asset that has these subsystem types.
IMPLICIT_STATE_TOPICS = {
    "AccessControl": ("rapid::AccessControlState", "ACCESSCONTROL_STATE_TOPIC"),
    "Queue": ("rapid::QueueState", "QUEUE_STATE_TOPIC"),
}
