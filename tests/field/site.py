"""The two sites of a field test: the asset's simulated bridge in the asset namespace, ground
tools in the ground namespace, each with the generated Cyclone `wan` (or `lan`) configuration
whose static peers are the namespaces' own addresses (what a deployment edits in)."""
from __future__ import annotations

import re
import sys
from pathlib import Path

from tests.field.link import ADDRESS, Link
from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir

K10 = str(ROOT / "specs" / "assets" / "k10.yaml")
RAPIDGEN = [sys.executable, "-m", "rapidgen"]


def site_config(folder: Path, asset: str = "k10", transport: str = "wan", extra: str = "") -> Path:
    """The package's generated Cyclone file for `transport`, peers set to the two sites
    (extra: XML put at the end of the Domain element)."""
    src = python_dir(asset) / SEEDS[asset] / "qos_files" / "cyclonedds" / f"{transport}.xml"
    text = src.read_text(encoding="utf-8")
    peers = "".join(f'<Peer Address="{a}"/>' for a in ADDRESS.values())
    text, n = re.subn(r"<Peers>.*?</Peers>", f"<Peers>{peers}</Peers>", text, flags=re.S)
    if n == 0:  # lan: multicast discovery, no peers to set
        assert transport == "lan", src
    text = text.replace("</Domain>", extra + "</Domain>")
    out = folder / f"{asset}-{transport}.xml"
    out.write_text(text, encoding="utf-8")
    return out


def _site_data(rtt: float | None, lease: float | None, transport: str, participants: int | None) -> dict:
    """specs/qos/rapid.yaml as a site copies it: its peers in the transport and, for a slow
    link, its round trip, lease and participants."""
    import yaml

    data = yaml.safe_load((ROOT / "specs" / "qos" / "rapid.yaml").read_text(encoding="utf-8"))
    t = data["transports"][transport]
    t["peers"] = list(ADDRESS.values())
    for key, value in (("rtt", rtt), ("lease", lease), ("max_participants_per_host", participants)):
        if value is not None:
            t[key] = value
    return data


def site_library(folder: Path, rtt: float | None, lease: float | None, transport: str = "wan",
                 participants: int | None = None) -> Path:
    """The Cyclone file of a site's own QoS library (docs/qos.md: a site copies
    specs/qos/rapid.yaml, puts its peers in and, for a slow link, its round trip and the
    longest outage to ride through), rendered by rapidgen's qos back end."""
    import yaml

    from rapidgen.backends.base import notice
    from rapidgen.backends.qos import view
    from rapidgen.backends.templating import render
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.qos.spec import load_qos

    data = _site_data(rtt, lease, transport, participants)
    lib = folder / "site-qos.yaml"
    lib.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    sink = DiagnosticSink()
    spec = load_qos(str(lib), sink)
    assert spec is not None and not sink.has_errors, sink
    t_view = next(v for v in view.cyclone_views(spec) if v.name == transport)
    out = folder / f"site-{transport}.xml"
    out.write_text(render("qos", "cyclonedds.xml.j2", t=t_view, notice=notice(str(lib)), library=spec.library,
                          asset=None), encoding="utf-8")
    return out


def site_env(config: Path, asset: str = "k10") -> dict:
    return dict(env_for(python_dir(asset), SEEDS[asset]), CYCLONEDDS_URI=f"file://{config}")


def start_bridge(link: Link, config: Path, domain: int, *extra: str, asset: str = "k10") -> BridgeProcess:
    """The asset's simulated bridge in the asset namespace (ready once it says so)."""
    argv = link.argv("asset", [sys.executable, "-m", f"{SEEDS[asset]}.bridge", "--simulate", "--domain",
                               str(domain), *extra])
    bridge = BridgeProcess.of_command(argv, python_dir(asset), site_env(config, asset))
    link.children.append(bridge.proc)
    bridge.wait_ready(60)
    return bridge


def site_fastdds(folder: Path, rtt: float | None, lease: float | None, transport: str = "wan",
                 participants: int | None = None, asset: str = "k10") -> Path:
    """The Fast DDS profiles of the same site library as site_library(), rendered for the
    asset by rapidgen's qos back end (the C++ bridge's --qos file; its participant profile is
    rapid_<transport>)."""
    import yaml

    from rapidgen.backends import qos as qos_backend
    from rapidgen.backends.base import Options
    from rapidgen.diagnostics import DiagnosticSink
    from rapidgen.generate import load_inputs
    from rapidgen.qos.spec import parse_qos

    data = _site_data(rtt, lease, transport, participants)
    sink = DiagnosticSink()
    spec = parse_qos(yaml.safe_dump(data, sort_keys=False), str(folder / "site-qos.yaml"), sink)
    inputs = load_inputs([str(ROOT / "specs" / "assets" / f"{asset}.yaml")], [str(ROOT / "specs" / "rapid")], sink)
    assert spec is not None and inputs is not None and not sink.has_errors, sink
    files = qos_backend.render(spec, inputs.model, inputs.asset, Options(source="site-qos.yaml"))
    out = folder / f"site-{transport}-fastdds.xml"
    out.write_text(next(f.content for f in files if f.path == qos_backend.FASTDDS_FILE), encoding="utf-8")
    return out
