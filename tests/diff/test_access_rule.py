"""PROTO-ACCESS-01 (issue 24): a change that widens who may command an asset is PROTOCOL;
narrowing it, or commands added, is not."""
from __future__ import annotations

import pytest

from tests.diff.conftest import asset_pair, base, diff_paths

OLD = {"default": "deny", "sources": [{"source": "Ground", "allow": ["Admin/*", "Mobility/stopAllMotion"]},
                                      {"source": "Science", "allow": ["Admin/echo"]}]}


def _with(access):
    d = base()
    if access is not None:
        d["access_control"] = access
    return d


def _found(tmp_path, old, new):
    return [f for f in diff_paths(*asset_pair(tmp_path, _with(old), _with(new))) if f.rule.id == "PROTO-ACCESS-01"]


def _acl(default="deny", **sources):
    return {"default": default, "sources": [{"source": s, "allow": a} for s, a in sources.items()]}


@pytest.mark.parametrize("new, who, gained", [
    (None, "*", "any source may now send every command"),  # the section removed
    (_acl("allow", Ground=["Admin/*", "Mobility/stopAllMotion"], Science=["Admin/echo"]), "*", "Admin/echo"),
    (_acl(Ground=["*"], Science=["Admin/echo"]), "Ground", "Mobility/"),
    (_acl(Ground=["Admin/*", "Mobility/stopAllMotion"], Science=["Admin/*"]), "Science", "Admin/shutdown"),
    (_acl(Ground=["Admin/*", "Mobility/stopAllMotion"], Science=["Admin/echo"], Rogue=["Mobility/stopAllMotion"]),
     "Rogue", "Mobility/stopAllMotion"),
])
def test_widening_is_protocol(tmp_path, new, who, gained):
    found = _found(tmp_path, OLD, new)
    assert [f.subject for f in found] == [who], [f.message for f in found]
    f = found[0]
    assert f.rule.category == "PROTOCOL" and gained in f.message
    assert f.new is not None and "new" in f.new.file and f.new.line > 0


@pytest.mark.parametrize("new", [
    OLD,
    _acl(Ground=["Admin/*"], Science=["Admin/echo"]),  # narrowed
    _acl(Ground=["Admin/*", "Mobility/stopAllMotion"]),  # a source removed (denied by default)
    _acl(Ground=["Admin/echo", "Admin/noOp", "Admin/shutdown", "Mobility/stopAllMotion"],
         Science=["Admin/echo"]),  # the same grants spelled out
])
def test_narrowing_or_respelling_is_not(tmp_path, new):
    assert _found(tmp_path, OLD, new) == []


def test_from_no_section_nothing_can_widen(tmp_path):
    assert _found(tmp_path, None, _acl(Ground=["*"])) == []
