"""RAPID's QoS library in neutral form: the loader and its model (see spec.py).

The package ships RAPID's library (rapid.yaml, a link to specs/qos/rapid.yaml) and its
JSON Schema (qos.schema.json, for editors and for the loader).
"""
from rapidgen.qos.spec import (DDS_DEFAULT_READER, DDS_DEFAULT_WRITER, History, Policies, Ports, Profile,
                               QosSpec, Transport, default_library, load_qos, parse_qos)

__all__ = ["DDS_DEFAULT_READER", "DDS_DEFAULT_WRITER", "History", "Policies", "Ports", "Profile", "QosSpec",
           "Transport", "default_library", "load_qos", "parse_qos"]
