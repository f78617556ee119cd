"""`rapidgen init [NAME] [-o FILE]`: a commented starter descriptor that validates as written.

The file names no IDL folder: load.py then finds the nearest specs/rapid, else the RAPID
IDL shipped with rapidgen, so it validates wherever it is written. An existing file is
never overwritten (a descriptor is the user's work); the file appears whole or not at all.
"""
from __future__ import annotations

import os
import re
import sys

from rapidgen.diagnostics import DiagnosticSink, SourceLoc

NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,63}")

TEMPLATE = """\
# Asset capability descriptor for {name} (rapidgen init). Reference: docs/asset-descriptor.md.
#   rapidgen validate {file}                       check it
#   rapidgen describe {file}                       its command dictionary and telemetry
#   rapidgen generate {file} --lang python,qos -o out/{lower}
#   python -m rapid_{lower}.bridge --simulate      (from out/{lower}/python) a simulated robot
#   rapidgen cmd {file} Mobility simpleMove frame=site xyt=1,0,0
version: 1

asset:
  name: {name}             # Header.assetName and the default DDS partition
  kind: rover              # rover, vehicle, walker, humanoid, manipulator, suit, ...
  description: A new RAPID asset.
  tags: [rover]            # AgentConfig.agentTags

dds:
  domain: 0                # DDS domain id

# Your own subsystem types: commands with typed parameters (RAPID DataTypes), units,
# ranges, allowed values and defaults. Commands are checked against these at run time.
subsystem_types:
  - name: Camera
    description: a pan-tilt camera
    commands:
      - name: point
        description: point the camera
        abortable: true    # may be canceled while it runs
        parameters:
          - {{name: pan, type: RAPID_FLOAT, unit: rad, range: [-3.1, 3.1], default: 0}}
          - {{name: tilt, type: RAPID_FLOAT, unit: rad, range: [-1.5, 1.5], default: 0}}
      - name: snap
        parameters:
          - {{name: mode, type: RAPID_STRING, allowed: [mono, stereo], default: mono}}

# Subsystems: a name, and its type (the standard RAPID types Admin, Mobility, Queue and
# AccessControl need no type line: the name is the type).
subsystems:
  - {{name: Admin}}
  - {{name: Mobility}}
  - {{name: Queue}}        # queue actions APPEND, INSERT, REPLACE, DELETE
  - {{name: Mast, type: Camera, description: mast camera}}

# What the asset publishes; rates in Hz. Each entry also publishes its config.
telemetry:
  - kind: position
    rate: 2
    frame: site
    pose_encoding: RAPID_ROT_QUAT
    velocity_encoding: RAPID_ROT_XYZ
    subsystem: Mobility
    values:
      - {{key: speed, type: RAPID_FLOAT, unit: m/s, range: [0, 1]}}
  - kind: agent
    rate: 1
    values:
      - key: batteryCharge
        type: RAPID_FLOAT
        unit: "%"
        range: [0, 100]
        warning: {{below: 30}}
        critical: {{below: 15}}
      - {{key: driveMode, type: RAPID_STRING, allowed: [idle, teleop, autonomous], default: idle}}
  - kind: text
    categories: [system]

# Who may command what (leave it out and any source may send anything):
# access_control:
#   default: deny
#   sources:
#     - {{source: Operator, allow: ["*"]}}
#     - {{source: Science, allow: [Mast/*, Admin/echo]}}

# What `rapidgen conform` may send that moves the robot (docs/conformance.md). Without
# this section (or `conform --allow-motion`) it sends nothing that moves it, and the checks
# that need a drive (QUE-04, half of QUE-02) are UNSUPPORTED. The drive is cancelled
# within seconds; choose a goal that is safe where the robot stands:
# conformance:
#   motion:
#     - command: Mobility/simpleMove
#       args: {{frame: site, xyt: [0.5, 0, 0]}}
"""


def starter(name: str, file: str) -> str:
    return TEMPLATE.format(name=name, lower=name.lower(), file=file)


def run_init(name: str, output: str | None, sink: DiagnosticSink, report) -> int:
    here = SourceLoc("<command line>", 0, 0)
    if not NAME.fullmatch(name):
        sink.error("RG1910", f"'{name}' is not an asset name for a starter descriptor", here,
                   "a letter, then letters, digits or '_' (at most 64)")
        report(sink)
        return 1
    path = output or f"{name.lower()}.yaml"
    text = starter(name, path)
    try:
        # O_EXCL: refuse an existing file (or a link) atomically; write it whole, else remove it.
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
    except FileExistsError:
        sink.error("RG1910", f"'{path}' exists; rapidgen init never overwrites a file", SourceLoc(path, 0, 0),
                   "choose another name with -o FILE, or remove it first")
        report(sink)
        return 1
    except OSError as exc:
        sink.error("RG1910", f"cannot write '{path}': {exc.strerror or exc}", SourceLoc(path, 0, 0),
                   "check that the folder exists and is writable")
        report(sink)
        return 1
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
    except OSError as exc:
        os.unlink(path)
        sink.error("RG1910", f"cannot write '{path}': {exc.strerror or exc}", SourceLoc(path, 0, 0),
                   "check the free space")
        report(sink)
        return 1
    print(f"{path}: starter descriptor for asset {name}; next: rapidgen validate {path}", file=sys.stdout)
    return 0
