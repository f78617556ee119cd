"""Schema-valid YAML data -> AssetSpec (locations attached, relative paths resolved).

Runs only after check_schema passed, so shapes and scalar types can be trusted here;
everything semantic is left to check.py.
"""
from __future__ import annotations

import os

from rapidgen.asset import spec as S
from rapidgen.yamlread import YamlDoc
from rapidgen.diagnostics import SourceLoc


class _Builder:
    def __init__(self, doc: YamlDoc, base_dir: str) -> None:
        self.doc = doc
        self.base_dir = base_dir

    def locs(self, path: tuple, obj: dict) -> dict:
        """loc and field_locs of the mapping at path: its fields and their list items."""
        out: list[tuple[tuple, SourceLoc]] = []
        for k, v in obj.items():
            out.append(((k,), self.doc.loc(path + (k,))))
            if isinstance(v, (list, dict)):
                for sub in (range(len(v)) if isinstance(v, list) else v):
                    out.append(((k, sub), self.doc.loc(path + (k, sub))))
        return {"loc": self.doc.loc(path), "field_locs": tuple(out)}

    def with_range(self, path: tuple, obj: dict, kw: dict) -> dict:
        """min/max from `range: [a, b]` or from min:/max:; locs point at what was written."""
        fl = list(kw["field_locs"])
        if "range" in obj:
            lo, hi = obj["range"]
            fl += [(("min",), self.doc.loc(path + ("range", 0))), (("max",), self.doc.loc(path + ("range", 1)))]
            kw.update(min=lo, max=hi, range_given=True)
        else:
            kw.update(min=obj.get("min"), max=obj.get("max"))
        kw["field_locs"] = tuple(fl)
        return kw

    def typed(self, cls, path: tuple, obj: dict, name_key: str):
        kw = self.with_range(path, obj, self.locs(path, obj))
        extra = {}
        if cls is S.ValueKey:
            extra = {lvl: self.threshold(path + (lvl,), obj[lvl]) for lvl in ("warning", "critical") if lvl in obj}
        return cls(name=obj[name_key], type=obj["type"], unit=obj.get("unit"),
                   description=obj.get("description", ""), allowed=tuple(obj.get("allowed", ())),
                   default=obj.get("default"), has_default="default" in obj, **extra, **kw)

    def threshold(self, path: tuple, obj: dict) -> S.Threshold:
        return S.Threshold(below=obj.get("below"), above=obj.get("above"), **self.locs(path, obj))

    def command(self, path: tuple, obj: dict) -> S.CommandSpec:
        params = tuple(self.typed(S.Parameter, path + ("parameters", i), p, "name")
                       for i, p in enumerate(obj.get("parameters", ())))
        return S.CommandSpec(name=obj["name"], description=obj.get("description", ""),
                             abortable=obj.get("abortable", False), suspendable=obj.get("suspendable", False),
                             parameters=params, stop_timeout_ms=obj.get("stop_timeout_ms"),
                             **self.locs(path, obj))

    def subsystem_type(self, path: tuple, obj: dict) -> S.SubsystemTypeSpec:
        cmds = tuple(self.command(path + ("commands", i), c) for i, c in enumerate(obj.get("commands", ())))
        return S.SubsystemTypeSpec(name=obj["name"], description=obj.get("description", ""),
                                   extends=obj.get("extends"), commands=cmds, **self.locs(path, obj))

    def telemetry(self, path: tuple, obj: dict) -> S.Telemetry:
        kind = obj["kind"]
        common = dict(kind=kind, suffix=obj.get("suffix"), rate=obj.get("rate"),
                      stale_after_ms=obj.get("stale_after_ms"),
                      qos=tuple(obj.get("qos", {}).items()), subsystem=obj.get("subsystem"),
                      description=obj.get("description", ""), **self.locs(path, obj))
        values = tuple(self.typed(S.ValueKey, path + ("values", i), v, "key")
                       for i, v in enumerate(obj.get("values", ())))
        if kind == "position":
            return S.PositionTelemetry(frame=obj["frame"], values=values,
                                       pose_encoding=obj.get("pose_encoding", "RAPID_ROT_QUAT"),
                                       velocity_encoding=obj.get("velocity_encoding", "RAPID_ROT_NONE"), **common)
        if kind == "joint":
            joints = []
            for i, j in enumerate(obj["joints"]):
                jp = path + ("joints", i)
                kw = self.with_range(jp, j, self.locs(jp, j))
                joints.append(S.Joint(frame=j["frame"], dof=j["dof"], unit=j.get("unit"),
                                      description=j.get("description", ""), **kw))
            return S.JointTelemetry(group=obj["group"], joints=tuple(joints),
                                    fields=tuple(obj.get("fields", ())), **common)
        if kind == "agent":
            return S.AgentTelemetry(values=values, **common)
        if kind == "image":
            return S.ImageTelemetry(sensor=obj["sensor"], sensor_type=obj.get("sensor_type", ""),
                                    mime=obj.get("mime", "image/jpeg"), width=obj.get("width"),
                                    height=obj.get("height"), **common)
        if kind == "text":
            return S.TextTelemetry(categories=tuple(obj.get("categories", ())), **common)
        msgs = tuple(S.CustomMessage(role=role, type=obj[role]["type"], topic=obj[role]["topic"],
                                     **self.locs(path + (role,), obj[role]))
                     for role in ("config", "sample", "state") if role in obj)
        return S.CustomTelemetry(messages=msgs, **common)

    def stream(self, path: tuple, obj: dict) -> S.StreamSpec:
        return S.StreamSpec(name=obj["name"], type=obj["type"], rate=obj["rate"],
                            direction=obj.get("direction", "input"), topic=obj.get("topic"),
                            source=obj.get("source"), deadline_ms=obj.get("deadline_ms"),
                            liveliness_ms=obj.get("liveliness_ms"), on_loss=obj.get("on_loss", "stop"),
                            subsystem=obj.get("subsystem"), state_key=obj.get("state_key"),
                            missed_key=obj.get("missed_key"), description=obj.get("description", ""),
                            **self.locs(path, obj))

    def path_in(self, rel: str) -> str:
        return os.path.normpath(os.path.join(self.base_dir, rel))

    def asset(self) -> S.AssetSpec:
        d = self.doc.data
        assert isinstance(d, dict)  # validated: the schema's top level is a mapping
        a, dds, idl = d["asset"], d.get("dds", {}), d.get("idl", {})
        field_locs = []  # the root keeps locs of the small sections it flattens
        for section in ("asset", "dds", "idl"):
            if section in d:
                field_locs += [((section,) + p, loc) for p, loc in self.locs((section,), d[section])["field_locs"]]
        native = None
        if "native" in d:
            n = d["native"]
            native = S.NativeSpec(subsystem=n.get("subsystem", "Native"), command=n.get("command", "native"),
                                  parameter=n.get("parameter", "command"),
                                  description=n.get("description", ""), **self.locs(("native",), n))
        access = None
        if "access_control" in d:
            ac = d["access_control"]
            rules = tuple(S.AccessRule(source=r["source"], allow=tuple(r["allow"]),
                                       description=r.get("description", ""),
                                       **self.locs(("access_control", "sources", i), r))
                          for i, r in enumerate(ac.get("sources", ())))
            access = S.AccessControlSpec(default=ac.get("default", "deny"), rules=rules,
                                         **self.locs(("access_control",), ac))
        return S.AssetSpec(
            file=self.doc.file, name=a["name"], kind=a["kind"], description=a.get("description", ""),
            tags=tuple(a.get("tags", ())), domain=dds.get("domain", 0),
            partition=dds.get("partition", a["name"]),
            rapid_dir=self.path_in(idl["rapid"]) if "rapid" in idl else None,
            include_dirs=tuple(self.path_in(p) for p in idl.get("include", ())),
            idl_files=tuple(self.path_in(p) for p in idl.get("files", ())),
            subsystem_types=tuple(self.subsystem_type(("subsystem_types", i), t)
                                  for i, t in enumerate(d.get("subsystem_types", ()))),
            subsystems=tuple(S.SubsystemSpec(name=s["name"], type=s.get("type", s["name"]),
                                             description=s.get("description", ""),
                                             **self.locs(("subsystems", i), s))
                             for i, s in enumerate(d.get("subsystems", ()))),
            telemetry=tuple(self.telemetry(("telemetry", i), t) for i, t in enumerate(d.get("telemetry", ()))),
            streams=tuple(self.stream(("streams", i), s) for i, s in enumerate(d.get("streams", ()))),
            native=native, access_control=access, loc=self.doc.loc(()),
            field_locs=tuple(field_locs) + self.locs((), d)["field_locs"])


def build_spec(doc: YamlDoc, base_dir: str) -> S.AssetSpec:
    return _Builder(doc, base_dir).asset()
