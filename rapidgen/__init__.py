"""rapidgen: code generation and conformance checks for NASA's RAPID robot messaging protocol."""

__version__ = "0.1.0"
