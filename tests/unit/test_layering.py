"""Import directions (DESIGN.md): the model is a leaf; the front end owns meaning; back ends
read the model and the asset and nothing of the front end or of each other; the robot-side
runtime needs nothing of the compiler."""
from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHARED_BACKEND = {"rapidgen.backends", "rapidgen.backends.base", "rapidgen.backends.escape", "rapidgen.backends.naming",
                  "rapidgen.backends.templating", "rapidgen.backends.typewalk"}


def imports_of(path: Path) -> set[str]:
    """Every module named by an import anywhere in the file (function bodies and
    TYPE_CHECKING blocks included: a lazy import is still a dependency)."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
            names.update(f"{node.module}.{a.name}" for a in node.names)
    return names


def modules(package: str) -> list[tuple[str, Path]]:
    folder = ROOT / package.replace(".", "/")
    out = []
    for path in sorted(folder.rglob("*.py")):
        rel = path.relative_to(ROOT).with_suffix("")
        name = ".".join(p for p in rel.parts if p != "__init__")
        out.append((name, path))
    assert out, f"no modules under {package}"
    return out


def under(name: str, package: str) -> bool:
    return name == package or name.startswith(package + ".")


def offending(package: str, allowed) -> list[str]:
    bad = []
    for name, path in modules(package):
        for imp in sorted(imports_of(path)):
            if imp.split(".")[0] in ("rapidgen", "rapid_runtime") and not allowed(name, imp):
                bad.append(f"{name} imports {imp}")
    return bad


def test_model_is_a_leaf():
    assert offending("rapidgen.model", lambda _m, imp: under(imp, "rapidgen.model")
                     or under(imp, "rapidgen.diagnostics")) == []


def test_codec_reads_the_model_only():
    assert offending("rapidgen.cdr", lambda _m, imp: any(under(imp, p) for p in (
        "rapidgen.model", "rapidgen.cdr")) or under(imp, "rapidgen.diagnostics")) == []


def test_front_end_imports_no_later_stage():
    # (leaf utilities, no stage: rapidgen.precomputed, the --write/--check of a shipped
    # precomputed module; rapidgen.packagedata, a file shipped in a package)
    assert offending("rapidgen.idl", lambda _m, imp: any(under(imp, p) for p in (
        "rapidgen.idl", "rapidgen.model")) or under(imp, "rapidgen.diagnostics")
        or under(imp, "rapidgen.precomputed") or under(imp, "rapidgen.packagedata")) == []


def test_backends_import_no_front_end_and_no_other_backend():
    def allowed(mod: str, imp: str) -> bool:
        if under(imp, "rapidgen.idl") or under(imp, "rapidgen.cdr"):
            return False
        if imp == "rapidgen.backends" or any(under(imp, s) for s in SHARED_BACKEND - {"rapidgen.backends"}):
            return True
        if under(imp, "rapidgen.backends"):
            own = ".".join(mod.split(".")[:3])  # rapidgen.backends.<target>
            return under(imp, own)
        return True
    assert offending("rapidgen.backends", allowed) == []


def test_runtime_needs_nothing_of_the_compiler():
    bad = offending("runtime.rapid_runtime", lambda _m, imp: under(imp, "rapid_runtime"))
    third = [f"{name} imports {imp}" for name, path in modules("runtime.rapid_runtime")
             for imp in imports_of(path) if imp.split(".")[0] in ("lark", "jinja2", "jsonschema", "yaml")]
    assert bad + third == []


def test_the_checker_sees_lazy_imports(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("def f():\n    from rapidgen.idl import parse\n")
    assert "rapidgen.idl.parse" in imports_of(f)


# The rules that compute an asset's facts (dictionary.py, topics.py, publish.py) are called by
# the resolved asset alone (rapidgen/asset/resolved.py): everyone else reads its properties.
ASSET_RULES = {"rapidgen.asset.dictionary": None,  # every name
               "rapidgen.asset.topics": {"publications", "messages_of"},
               "rapidgen.asset.publish": {"configs", "command_config", "agent_config", "position_config",
                                          "joint_config"}}
ASSET_RULE_MODULES = {"rapidgen.asset.resolved", *ASSET_RULES}


def asset_rule_uses(path: Path) -> set[str]:
    """Names of the asset rules a module imports or reaches through its module."""
    found: set[str] = set()
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module in ASSET_RULES and node.level == 0:
            names = ASSET_RULES[node.module]
            found.update(f"{node.module}.{a.name}" for a in node.names if names is None or a.name in names)
        elif isinstance(node, ast.ImportFrom) and node.module == "rapidgen.asset" and node.level == 0:
            found.update(f"rapidgen.asset.{a.name}" for a in node.names if f"rapidgen.asset.{a.name}" in ASSET_RULES)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name in ASSET_RULES)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "Facts":
            found.add("Facts(...)")  # the IDL facts of an asset: loaded.facts
    return found


def test_asset_facts_are_computed_in_the_resolved_asset_only():
    bad = []
    for package in ("rapidgen", "conformance", "tests", "scripts", "bench"):
        for name, path in modules(package):
            if name in ASSET_RULE_MODULES or name == "tests.unit.test_layering":
                continue
            uses = asset_rule_uses(path)
            bad += [f"{name} uses {u}" for u in sorted(uses)]
    assert bad == []


def test_the_asset_rule_check_sees_imports_and_calls(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("def f(l):\n    from rapidgen.asset.publish import configs\n    return Facts(l.model)\n")
    assert asset_rule_uses(f) == {"rapidgen.asset.publish.configs", "Facts(...)"}
