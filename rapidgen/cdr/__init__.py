"""The reference XCDR1/XCDR2 codec and sample values, built from the IR alone (no syntax,
no back end): the byte contract every language's bindings are tested against."""
from rapidgen.cdr.codec import CdrError, Codec

__all__ = ["CdrError", "Codec"]
