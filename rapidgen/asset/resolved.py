"""The resolved asset: every fact of an asset, computed once from its descriptor and the
RAPID IDL model, the way `ir.Model` holds the IDL's. The checks, the back ends, `describe`,
`diff`, `spy` and `conform` read it; none recomputes a fact (tests/unit/test_layering.py
fails when one does).

    loaded = load_asset("specs/assets/k10.yaml", sink)
    loaded.subsystems         descriptor order, the native passthrough last
    loaded.types              every type a subsystem may name (after `extends`, standard ones)
    loaded.used_types         the types the subsystems use, in CommandConfig order
    loaded.publications       every topic it publishes: role, type, topic, QoS profile, rate
    loaded.command_topic      the topic it reads commands on (None: telemetry only)
    loaded.configs            topic -> (config type, computed value)
    loaded.telemetry_topics   per telemetry entry: role -> full topic name
    loaded.streams            setpoint streams with defaults resolved (topic, deadline, QoS profile)
    loaded.facts              what the IDL says (bounds, DataTypes, topic constants)

Each fact is computed on first use and kept (the checks run on a descriptor that may still
hold errors, so nothing is computed before it is asked for). The rules live in
dictionary.py, topics.py, publish.py and streams.py; only this module calls them.

The one deliberate second computation is the conformance runner's expectation of what a
live asset publishes (rapidgen/conform/expected.py): it judges the runtimes, so it must
not share their bugs.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from rapidgen.asset import dictionary, publish, streams, topics
from rapidgen.asset.facts import Facts
from rapidgen.asset.spec import AccessControlSpec, AssetSpec, SubsystemSpec, SubsystemTypeSpec
from rapidgen.diagnostics import SourceLoc
from rapidgen.model.ir import Model


@dataclass(frozen=True, eq=False)
class LoadedAsset:
    spec: AssetSpec
    model: Model | None  # None when the IDL could not be loaded (errors are in the sink)
    # The checked `ros2:` section as plain data (rapidgen/ros2/section.py), None without one.
    ros2: dict | None = None
    # The checked `conformance:` section (rapidgen/asset/conformance.py): {"motion": {"Sub/cmd":
    # [(DataType, value), ...]}}, what `rapidgen conform` may send that moves the asset; None without one.
    conformance: dict | None = None

    @cached_property
    def facts(self) -> Facts:
        return Facts(self.model)

    @cached_property
    def types(self) -> dict[str, SubsystemTypeSpec]:
        return dictionary.effective_types(self.spec)

    @cached_property
    def subsystems(self) -> tuple[SubsystemSpec, ...]:
        return dictionary.all_subsystems(self.spec)

    @cached_property
    def used_types(self) -> tuple[SubsystemTypeSpec, ...]:
        return tuple(dictionary.used_types(self.spec))

    @cached_property
    def publications(self) -> tuple[topics.Publication, ...]:
        return tuple(topics.publications(self.spec, self.facts, self.used_types))

    @cached_property
    def command_topic(self) -> str | None:
        """Where the asset reads commands; None when it has no subsystems."""
        if not self.used_types:
            return None
        return self.facts.string_const("rapid::COMMAND_TOPIC") or "rapid_command"

    @cached_property
    def configs(self) -> dict[str, tuple[str, dict]]:
        return publish.configs(self.spec, self.facts, self.publications, self.used_types, self.subsystems)

    @cached_property
    def telemetry_messages(self) -> tuple[tuple[tuple[str, str, str, SourceLoc], ...], ...]:
        """For each telemetry entry (spec.telemetry order): its (role, type, base topic, loc)."""
        return tuple(tuple(topics.messages_of(t, self.facts)) for t in self.spec.telemetry)

    @cached_property
    def telemetry_topics(self) -> tuple[dict[str, str], ...]:
        """For each telemetry entry (spec.telemetry order): role -> full topic name."""
        return tuple({role: (f"{topic}-{t.suffix}" if t.suffix else topic) for role, _type, topic, _loc in msgs}
                     for t, msgs in zip(self.spec.telemetry, self.telemetry_messages))

    @cached_property
    def streams(self) -> tuple[streams.Stream, ...]:
        return tuple(streams.resolve(self.spec, self.facts))

    @property
    def access(self) -> AccessControlSpec | None:
        return self.spec.access_control
