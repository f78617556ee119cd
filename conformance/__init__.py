"""The RAPID conformance suite: one check per protocol rule (docs/conformance.md lists
them). Shipped in the wheel as rapidgen.conform.suite; `rapidgen conform` runs it.
Modules register in run order; checks marked late judge the whole run at its end."""
from . import dds, configs, telemetry, commands, queue, access, spec  # noqa: F401  (registration order = run order)
