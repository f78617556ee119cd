"""RAPID in Foxglove (docs/foxglove.md): derived messages in Foxglove's well-known schemas
(derive.py, schemas.py), written by `rapidgen record --foxglove` (rapidgen.record.derived) and
served live with the RAPID channels by `rapidgen monitor --foxglove`
(rapidgen.monitor.foxglove_live, foxglove_server). Imports nothing of the tools (the runtime's rotations only)."""
