"""RAPID asset runtime: what every RAPID asset does, written once.

A generated asset package (rapidgen, Python target) holds declarative tables only: its
command dictionary, computed configs, topics and QoS files. This package holds the
behaviour (rapid-protocol.md sections 5 and 5b; docs/runtime.md says which choices it
makes where the protocol is silent):

    tables      the generated tables, read into typed entries
    values      RAPID DataType shapes, ranges and allowed values
    validate    a received command against the dictionary (BAD_SYNTAX reasons)
    access      the allow-list of command sources and the controller state
    cmdqueue    the pending queue and its actions (APPEND, INSERT, REPLACE, DELETE)
    manager     command intake, the ack lifecycle, built-in commands
    handlers    the base class of an asset's handlers, CommandContext, CommandFailed
    configs     config serials (new serial when content changes)
    telemetry   headers, timestamps, rates, values checked against declared types
    messages    plain data <-> the generated cyclonedds classes
    dds         the DDS side (Cyclone): readers, writers, QoS, partition
    bridge      the `python -m <package>.bridge` entry point
    simulate    a plausible simulated robot behind the handlers
    qos         RapidQos: each topic's QoS from the generated QoS files (every package's `qos`)
    ros2        the ROS 2 bridge's handlers and ground node (a package with a ros2: section)
    plain       a decoded sample as JSON-ready data (the tools' one form: spy, monitor)
    thresholds  an agent value's warning/critical level (the monitor and the ROS 2 ground node)
    idl_support what every generated types package calls (long sequences, DeserializeError)

The protocol logic (everything above `messages`) imports no DDS, so it is tested
without a network. Depends on cyclonedds and the standard library only.
"""
__version__ = "0.1.0"
