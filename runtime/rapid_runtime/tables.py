"""The generated asset tables (`<package>/asset_tables.py`) read into typed entries.

The generated module holds plain literals only; this is where the runtime gives them
shape. Every name the runtime looks up goes through here.
"""
from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

FORMAT = 1  # asset_tables.FORMAT this runtime reads


class TablesError(Exception):
    """The tables module is not one this runtime can read (regenerate, or upgrade the runtime)."""


@dataclass(frozen=True)
class Param:
    name: str  # as in the descriptor (KeyTypePair.key)
    arg: str  # the handler method's keyword
    type: str  # RAPID DataType enumerator name
    unit: str | None = None
    min: float | None = None
    max: float | None = None
    allowed: tuple = ()
    default: object = None
    has_default: bool = False
    description: str = ""


@dataclass(frozen=True)
class CommandEntry:
    subsystem_type: str
    name: str
    method: str  # handler method name
    params: tuple[Param, ...]
    abortable: bool = False
    suspendable: bool = False
    standard: bool = False  # a standard RAPID subsystem type's command
    description: str = ""
    # how long [ms] the handler may run on after it was told to stop; None: the bridge's default
    stop_timeout_ms: int | None = None


@dataclass(frozen=True)
class AccessRule:
    source: str
    allow: tuple[str, ...]


@dataclass(frozen=True)
class AccessSpec:
    default: str  # allow | deny, for sources no rule names
    rules: tuple[AccessRule, ...]


class Tables:
    """Attributes: name, kind, domain, partition, subsystems (name -> type), configs
    (topic -> (type, value)), publications (list of dicts), telemetry (list of dicts),
    access (AccessSpec or None: any source may command)."""

    def __init__(self, module: ModuleType | dict) -> None:
        data = module if isinstance(module, dict) else vars(module)
        if data.get("FORMAT") != FORMAT:
            raise TablesError(f"asset tables format {data.get('FORMAT')!r}; this runtime reads {FORMAT}")
        try:
            asset = data["ASSET"]
            self.name: str = asset["name"]
            self.kind: str = asset.get("kind", "other")
            self.domain: int = asset.get("domain", 0)
            self.partition: str = asset.get("partition", self.name)
            self.subsystems: dict[str, str] = dict(data["SUBSYSTEMS"])
            self._commands = {t: {n: self._entry(t, n, c) for n, c in cmds.items()}
                              for t, cmds in data["COMMANDS"].items()}
            acc = data.get("ACCESS")
            self.access = None if acc is None else AccessSpec(
                acc.get("default", "deny"), tuple(AccessRule(r["source"], tuple(r["allow"])) for r in acc["rules"]))
            self.configs: dict[str, tuple[str, dict]] = {t: (c["type"], c["value"])
                                                          for t, c in data["CONFIGS"].items()}
            self.publications: list[dict] = list(data["PUBLICATIONS"])
            self.telemetry: list[dict] = list(data["TELEMETRY"])
        except (KeyError, TypeError, AttributeError) as exc:
            raise TablesError(f"asset tables malformed: {exc!r}") from None

    @staticmethod
    def _entry(type_name: str, name: str, c: dict) -> CommandEntry:
        params = tuple(Param(name=p["name"], arg=p["arg"], type=p["type"], unit=p.get("unit"), min=p.get("min"),
                             max=p.get("max"), allowed=tuple(p.get("allowed", ())), default=p.get("default"),
                             has_default=p.get("has_default", False), description=p.get("description", ""))
                       for p in c["parameters"])
        return CommandEntry(subsystem_type=type_name, name=name, method=c["method"], params=params,
                            abortable=c.get("abortable", False), suspendable=c.get("suspendable", False),
                            standard=c.get("standard", False), description=c.get("description", ""),
                            stop_timeout_ms=c.get("stop_timeout_ms"))

    def type_of(self, subsystem: str) -> str | None:
        return self.subsystems.get(subsystem)

    def command(self, subsystem: str, name: str) -> CommandEntry | None:
        t = self.subsystems.get(subsystem)
        return self._commands.get(t, {}).get(name) if t is not None else None

    def commands_of_type(self, type_name: str) -> dict[str, CommandEntry]:
        return dict(self._commands.get(type_name, {}))

    def entries(self):
        """(subsystem, CommandEntry) for every command the asset takes, in dictionary order."""
        for sub, t in self.subsystems.items():
            for entry in self._commands.get(t, {}).values():
                yield sub, entry

    def has_type(self, type_name: str) -> bool:
        return type_name in self.subsystems.values()

    def subsystems_of_type(self, type_name: str) -> list[str]:
        return [s for s, t in self.subsystems.items() if t == type_name]
