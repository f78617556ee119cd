"""Every template filter is used by a template, every filter a template uses is ours
(issue 9, defect 7: no dead filters), and Options carries only what back ends read."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import jinja2
from jinja2 import nodes

from rapidgen.backends import templating
from rapidgen.backends.base import Options

TEMPLATES = Path(templating.__file__).resolve().parents[2] / "templates"


def _filters_used() -> dict[str, set[str]]:
    env = jinja2.Environment()  # parsing only: filter names are not resolved here
    used: dict[str, set[str]] = {}
    for path in sorted(TEMPLATES.rglob("*.j2")):
        tree = env.parse(path.read_text(encoding="utf-8"))
        for node in tree.find_all(nodes.Filter):
            used.setdefault(node.name, set()).add(str(path.relative_to(TEMPLATES)))
    return used


def test_every_registered_filter_is_used_by_some_template():
    used = _filters_used()
    assert TEMPLATES.is_dir() and used
    assert sorted(set(templating.FILTERS) - set(used)) == []


def test_templates_use_only_registered_or_builtin_filters():
    builtin = set(jinja2.Environment().filters)
    unknown = {name: where for name, where in _filters_used().items()
               if name not in templating.FILTERS and name not in builtin}
    assert unknown == {}


def test_options_fields_are_the_ones_back_ends_read():
    assert [f.name for f in dataclasses.fields(Options)] == ["source", "package", "qos_library"]
