"""`rapidgen conform`: check a live asset against the RAPID protocol.

model    checks (id, level, title, rule), outcomes, the registry
asset    the descriptor's facts a check needs (commands, sources, telemetry)
client   the runner's DDS side: command writer, ack/config/telemetry readers
session  one run: bindings, discovery, client, shared steps (control, commands)
runner   ordering, dependencies, progress; report: table, JUnit XML, JSON
The suite itself (one check per protocol rule) is the top-level conformance/ folder,
shipped as rapidgen.conform.suite.
"""
