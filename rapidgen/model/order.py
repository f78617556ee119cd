"""Recursion check and dependency order of declarations.

A type may refer to itself only through a sequence or map (or an @external member):
containment by value (members, arrays, bases, typedefs) must be acyclic. The order puts
every declaration after what it needs; types that refer to each other through
sequences form a strongly connected component, ordered inside by value containment.
"""
from __future__ import annotations

from rapidgen.diagnostics import DiagnosticSink
from rapidgen.model import ir


def _refs(t: ir.Type, by_value: bool) -> list[str]:
    """Named types t depends on; with by_value, only those stored inline."""
    if isinstance(t, ir.TypeRef):
        return [t.name]
    if isinstance(t, ir.Array):
        return _refs(t.element, by_value)
    if isinstance(t, ir.Sequence):
        return [] if by_value else _refs(t.element, by_value)
    if isinstance(t, ir.Map):
        return [] if by_value else _refs(t.key, by_value) + _refs(t.value, by_value)
    return []


def _edges(d: ir.Declaration, by_value: bool) -> list[str]:
    out: list[str] = []
    if isinstance(d, ir.Struct):
        if d.base:
            out.append(d.base)
        for m in d.members:
            if not (by_value and m.external):
                out.extend(_refs(m.type, by_value))
    elif isinstance(d, ir.Union):
        out.extend(_refs(d.discriminator, by_value))
        for c in d.cases:
            if not (by_value and c.member.external):
                out.extend(_refs(c.member.type, by_value))
    elif isinstance(d, ir.Typedef):
        out.extend(_refs(d.type, by_value))
    elif isinstance(d, ir.Bitset) and d.base:
        out.append(d.base)
    elif isinstance(d, ir.Const) and not by_value:
        out.extend(_refs(d.type, False))
        if isinstance(d.value, ir.EnumValue):
            out.append(d.value.enum)
    return out


def strongly_connected(names: list[str], graph: dict[str, list[str]]) -> list[list[str]]:
    """Tarjan's algorithm, iterative; components come out dependencies first."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    result: list[list[str]] = []
    counter = 0
    for root in names:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = counter
                counter += 1
                stack.append(node)
                on_stack.add(node)
            succ = graph.get(node, [])
            if i < len(succ):
                work.append((node, i + 1))
                nxt = succ[i]
                if nxt not in index:
                    work.append((nxt, 0))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                result.append(comp)
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return result


def check_recursion(decls: list[ir.Declaration], sink: DiagnosticSink) -> None:
    names = [d.scoped_name for d in decls]
    by_name = {d.scoped_name: d for d in decls}
    graph = {d.scoped_name: [n for n in _edges(d, True) if n in by_name] for d in decls}
    for comp in strongly_connected(names, graph):
        if len(comp) == 1 and comp[0] not in graph[comp[0]]:
            continue
        members = sorted(comp, key=names.index)
        first = by_name[members[0]]
        cycle = " -> ".join(members + [members[0]])
        sink.error("RG0303", f"'{first.scoped_name}' contains itself by value ({cycle})", first.loc,
                   "recursion is allowed only through a sequence, e.g. sequence<" + first.name + ">")


def dependency_order(decls: list[ir.Declaration]) -> list[ir.Declaration]:
    names = [d.scoped_name for d in decls]
    pos = {n: i for i, n in enumerate(names)}
    by_name = {d.scoped_name: d for d in decls}
    soft = {n: sorted({e for e in _edges(by_name[n], False) if e in by_name}, key=pos.__getitem__) for n in names}
    out: list[ir.Declaration] = []
    for comp in strongly_connected(names, soft):
        if len(comp) == 1:
            out.append(by_name[comp[0]])
            continue
        # Inside a cycle through sequences: order by value containment, source order otherwise.
        hard = {n: set(_edges(by_name[n], True)) for n in comp}
        remaining = sorted(comp, key=pos.__getitem__)
        placed: set[str] = set()
        while remaining:
            ready = next((n for n in remaining if not hard[n] & (set(remaining) - {n})), remaining[0])
            remaining.remove(ready)
            placed.add(ready)
            out.append(by_name[ready])
    return out
