"""AssetSpec: a loaded asset descriptor as frozen dataclasses.

Every node keeps `loc` (its YAML mapping) and `field_locs` (each field's value) so that
checks long after loading still point at the exact line and column. Names are as
written; nothing here knows the IDL model (see check.py).
"""
from __future__ import annotations

from dataclasses import dataclass

from rapidgen.diagnostics import UNKNOWN_LOC, SourceLoc

Number = int | float


@dataclass(frozen=True, slots=True, kw_only=True)
class Located:
    loc: SourceLoc = UNKNOWN_LOC
    field_locs: tuple[tuple[tuple, SourceLoc], ...] = ()

    def at(self, *rel: str | int) -> SourceLoc:
        """Location of a field (or a list element: at("allow", 2)); the node's own otherwise."""
        for path, loc in self.field_locs:
            if path == rel:
                return loc
        return self.at(*rel[:-1]) if len(rel) > 1 else self.loc

    def has(self, *rel: str | int) -> bool:
        """Whether the field was written in the descriptor (not defaulted)."""
        return any(path == rel for path, _ in self.field_locs)


@dataclass(frozen=True, slots=True, kw_only=True)
class TypedValue(Located):
    """A command parameter or a telemetry value key: a RAPID DataType with its limits."""

    name: str
    type: str  # a DataType enumerator as written; check.py verifies it
    unit: str | None = None
    description: str = ""
    min: Number | None = None
    max: Number | None = None
    allowed: tuple[str, ...] = ()
    default: object = None
    has_default: bool = False
    range_given: bool = False  # `range:` written (min/max then point into it)


@dataclass(frozen=True, slots=True, kw_only=True)
class Parameter(TypedValue):
    pass


@dataclass(frozen=True, slots=True, kw_only=True)
class Threshold(Located):
    below: Number | None = None
    above: Number | None = None


@dataclass(frozen=True, slots=True, kw_only=True)
class ValueKey(TypedValue):
    warning: Threshold | None = None
    critical: Threshold | None = None


@dataclass(frozen=True, slots=True, kw_only=True)
class CommandSpec(Located):
    name: str
    description: str = ""
    abortable: bool = False
    suspendable: bool = False
    parameters: tuple[Parameter, ...] = ()
    stop_timeout_ms: int | None = None  # the handler's stop bound; None: the bridge's default


@dataclass(frozen=True, slots=True, kw_only=True)
class SubsystemTypeSpec(Located):
    name: str
    description: str = ""
    extends: str | None = None
    commands: tuple[CommandSpec, ...] = ()
    standard: bool = False  # one of rapidgen's standard RAPID types (standard.py)


@dataclass(frozen=True, slots=True, kw_only=True)
class SubsystemSpec(Located):
    name: str
    type: str
    description: str = ""


@dataclass(frozen=True, slots=True, kw_only=True)
class Joint(Located):
    frame: str
    dof: str
    unit: str | None = None
    description: str = ""
    min: Number | None = None
    max: Number | None = None
    range_given: bool = False


@dataclass(frozen=True, slots=True, kw_only=True)
class CustomMessage(Located):
    role: str  # config | sample | state
    type: str
    topic: str


@dataclass(frozen=True, slots=True, kw_only=True)
class Telemetry(Located):
    kind: str
    suffix: str | None = None
    rate: Number | None = None
    stale_after_ms: Number | None = None  # declared only (the runtime derives it from the rate otherwise)
    qos: tuple[tuple[str, str], ...] = ()  # (role, profile); locs at ("qos", role)
    subsystem: str | None = None
    description: str = ""


@dataclass(frozen=True, slots=True, kw_only=True)
class PositionTelemetry(Telemetry):
    frame: str
    pose_encoding: str = "RAPID_ROT_QUAT"
    velocity_encoding: str = "RAPID_ROT_NONE"
    values: tuple[ValueKey, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class JointTelemetry(Telemetry):
    group: str
    joints: tuple[Joint, ...] = ()
    fields: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class AgentTelemetry(Telemetry):
    values: tuple[ValueKey, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class ImageTelemetry(Telemetry):
    sensor: str
    sensor_type: str = ""
    mime: str = "image/jpeg"
    width: int | None = None
    height: int | None = None


@dataclass(frozen=True, slots=True, kw_only=True)
class TextTelemetry(Telemetry):
    categories: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class CustomTelemetry(Telemetry):
    messages: tuple[CustomMessage, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class StreamSpec(Located):
    """A setpoint stream as written; defaults are resolved in streams.py."""

    name: str
    type: str
    rate: Number
    direction: str = "input"
    topic: str | None = None
    source: str | None = None
    deadline_ms: Number | None = None
    liveliness_ms: Number | None = None
    on_loss: str = "stop"
    subsystem: str | None = None
    state_key: str | None = None
    missed_key: str | None = None
    description: str = ""


@dataclass(frozen=True, slots=True, kw_only=True)
class NativeSpec(Located):
    subsystem: str = "Native"
    command: str = "native"
    parameter: str = "command"
    description: str = ""


@dataclass(frozen=True, slots=True, kw_only=True)
class AccessRule(Located):
    source: str
    allow: tuple[str, ...]
    description: str = ""


@dataclass(frozen=True, slots=True, kw_only=True)
class AccessControlSpec(Located):
    default: str = "deny"
    rules: tuple[AccessRule, ...] = ()


@dataclass(frozen=True, slots=True, kw_only=True)
class AssetSpec(Located):
    """One descriptor. Paths in idl_files/include_dirs/rapid_dir are resolved (usable as-is)."""

    file: str
    name: str
    kind: str
    description: str = ""
    tags: tuple[str, ...] = ()
    domain: int = 0
    partition: str = ""
    rapid_dir: str | None = None
    include_dirs: tuple[str, ...] = ()
    idl_files: tuple[str, ...] = ()
    subsystem_types: tuple[SubsystemTypeSpec, ...] = ()  # as written; standard ones are in standard.py
    subsystems: tuple[SubsystemSpec, ...] = ()
    telemetry: tuple[Telemetry, ...] = ()
    streams: tuple[StreamSpec, ...] = ()
    native: NativeSpec | None = None
    access_control: AccessControlSpec | None = None
