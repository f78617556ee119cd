"""Import directions (docs/architecture.md, "Import rules"): the table there names every
unit of rapidgen and what each may import; this test reads it, checks every import of every
module against it, and finds circles between units. The runtime needs nothing of the
compiler; back ends import no other back end; asset facts are computed in one place."""
from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHARED_BACKEND = {"rapidgen.backends", "rapidgen.backends.base", "rapidgen.backends.escape", "rapidgen.backends.naming",
                  "rapidgen.backends.plausible", "rapidgen.backends.support",
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


# ---- the table of docs/architecture.md -------------------------------------------------------
def table() -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """(unit -> its top-level names under rapidgen, unit -> the units it may import), read
    from docs/architecture.md's "Import rules" table."""
    text = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    section = text.split("## Import rules", 1)[1].split("\n## ", 1)[0]
    members: dict[str, set[str]] = {}
    allowed: dict[str, set[str]] = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 3 or cells[0] in ("unit", "---") or set(cells[0]) <= {"-"}:
            continue
        unit, names, may = cells
        members[unit] = set(re.findall(r"`([^`]+)`", names))
        allowed[unit] = {"*"} if may == "every unit" else set(re.findall(r"`([^`]+)`", may))
    return members, allowed


def unit_of(module: str, members: dict[str, set[str]]) -> str | None:
    """The unit of a rapidgen module (rapidgen.asset.load -> asset); `runtime` for rapid_runtime."""
    parts = module.split(".")
    if parts[0] == "rapid_runtime":
        return "runtime"
    if parts[0] != "rapidgen":
        return None
    top = parts[1] if len(parts) > 1 else "rapidgen"
    if top == "__version__":
        top = "rapidgen"
    return next((u for u, names in members.items() if top in names), None)


def package_edges() -> dict[str, set[str]]:
    """unit -> the units its modules import."""
    members, _ = table()
    edges: dict[str, set[str]] = {}
    for name, path in modules("rapidgen"):
        src = unit_of(name, members)
        assert src is not None, f"{name} is in no unit of docs/architecture.md's import table: add it"
        for imp in imports_of(path):
            dst = unit_of(imp, members)
            if dst is not None and dst != src:
                edges.setdefault(src, set()).add(dst)
    return edges


def test_the_table_names_every_module_and_real_units():
    members, allowed = table()
    assert {"leaves", "model", "asset", "backends", "cli"} <= set(members)
    units = set(members) | {"runtime"}
    assert all(a <= units | {"*"} for a in allowed.values()), allowed
    tops = {p.stem if p.is_file() else p.name for p in (ROOT / "rapidgen").iterdir()
            if (p.suffix == ".py" or (p.is_dir() and (p / "__init__.py").exists()))}
    tops = {"rapidgen" if t == "__init__" else t for t in tops}
    named = set().union(*members.values())
    assert tops - named == set(), "modules missing from the table"
    assert named - tops - {"rapidgen"} == set(), "the table names modules that do not exist"


def test_every_import_is_one_the_table_allows():
    members, allowed = table()
    bad = []
    for name, path in modules("rapidgen"):
        src = unit_of(name, members)
        for imp in sorted(imports_of(path)):
            dst = unit_of(imp, members)
            if dst is None or dst in (src, "leaves") or "*" in allowed[src] or dst in allowed[src]:
                continue
            bad.append(f"{name} ({src}) imports {imp} ({dst})")
    assert bad == []


def test_no_circle_between_units():
    edges = package_edges()
    edges.pop("cli", None)  # the dispatcher: above every unit, imported by none but __main__
    seen: dict[str, int] = {}
    circles = []

    def visit(u: str, path: list[str]) -> None:
        seen[u] = 1
        for v in sorted(edges.get(u, ())):
            if seen.get(v) == 1:
                circles.append(" -> ".join(path[path.index(v):] + [v]))
            elif v not in seen:
                visit(v, path + [v])
        seen[u] = 2

    for u in sorted(edges):
        if u not in seen:
            visit(u, [u])
    assert circles == []


def test_the_leaves_import_only_leaves():
    members, _ = table()
    bad = [f"{name} imports {imp}" for name, path in modules("rapidgen") if unit_of(name, members) == "leaves"
           for imp in sorted(imports_of(path)) if unit_of(imp, members) not in (None, "leaves")]
    assert bad == []


def test_the_conformance_suite_imports_the_runner_only():
    assert offending("conformance", lambda _m, imp: under(imp, "rapidgen.conform") or under(imp, "conformance")
                     or under(imp, "rapidgen.textsafe")) == []


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
