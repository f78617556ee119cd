"""The one Jinja2 environment factory: strict, whitespace-controlled, filters in one place.

Templates live in the top-level templates/<target>/; the package reaches them through the
link rapidgen/templates (a copy in the wheel, so a plain `pip install .` ships them), one per artifact, `<artifact>.<ext>.j2`, plus `_macros.j2`.
They only print what the view layer decided: loops, precomputed booleans, macros.
"""
from __future__ import annotations

import functools

import jinja2

from rapidgen.backends import escape

# Every input string a template prints goes through one of these, or (XML targets) through
# escape.xml_text, which replaces plain autoescape; rapidgen/backends/escape.py says what
# each guarantees.
FILTERS = {
    "py_str": escape.py_str,  # a Python string literal (value round-trips)
    "docstring": escape.py_docstring,  # inside """...""" (value round-trips)
    "comment": escape.line_comment,  # after `#` in Python or TOML
    "toml_str": escape.toml_str,  # a TOML basic string (value round-trips)
    "xml_comment": escape.xml_comment,  # inside <!-- ... -->
    "cpp_str": escape.cpp_str,  # a C++ string literal (value: the UTF-8 bytes)
    "cpp_comment": escape.cpp_comment,  # after `//` in C++ (or `#` in CMake)
    "rust_str": escape.rust_str,  # a Rust string literal (value round-trips)
    "rust_comment": escape.rust_comment,  # after `//` or `///` in Rust
}


# Targets whose templates are all XML: every printed value goes through escape.xml_text
# (markup escaped, whitespace a parser would normalize as character references).
XML_TARGETS = frozenset({"qos"})


@functools.lru_cache(maxsize=None)
def environment(target: str) -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("rapidgen", f"templates/{target}"),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        autoescape=lambda name: name is not None and name.endswith(".xml.j2"),
        finalize=escape.xml_text if target in XML_TARGETS else None,
    )
    env.filters.update(FILTERS)
    return env


def render(target: str, template: str, **context: object) -> str:
    return environment(target).get_template(template).render(**context)
