"""Watching and talking to a live RAPID network (DDS, Cyclone's Python binding).

Shared by `rapidgen conform` and `rapidgen spy`: `dds` (lazy import of cyclonedds, the
transport), `bindings` (an asset's generated types and QoS, built in a temporary folder
from its descriptor), `discovery` (participants, writers and readers from the DDS
built-in topics). cyclonedds is an optional dependency (`pip install rapidgen[dds]`):
nothing here imports it at module level.
"""
