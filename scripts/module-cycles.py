#!/usr/bin/env python3
"""Module-level import cycles inside each crate of the workspace (python3 standard library only).

For every crate under crates/, each source file of its src/ folder is one module (src/lib.rs and
src/main.rs: the crate root, the library's when a crate has both; src/bin/ is left out; src/a.rs and
src/a/mod.rs: `a`; src/a/b.rs: `a::b`; inline `mod x {` blocks count as part of their file). An edge
A -> B is a path from A's code to an item of module B: a `use crate::...`, `use super::...`, `use
self::...` or `use child::...` declaration (also nested groups `use crate::{a::X, b::Y}`), or the
same kind of path written inline in the code (`crate::b::f(...)`, `crate::m!(...)`: a
`#[macro_export]` macro belongs to the module that defines it). A path is resolved to the deepest
module it names, and a name that module only imports or re-exports (a crate root's `pub use a::X`)
to the module that defines it; a path to an item an ancestor defines (`use super::Thing` from a
child) is an edge to that ancestor; a `#[path = "f.rs"] mod m;` file is the declaring module's `m`.
A module's own declarations `mod x;` are not edges. Comments and string literals are skipped;
`#[cfg(test)]` modules count like any other code except a test module's `use super::*` of its own
file.

Prints each crate's cycles (strongly connected components of more than one module, with one
cycle through them and the file and line of each edge on it) and exits 1 if there is any.

    scripts/module-cycles.py                 # every crate
    scripts/module-cycles.py crates/actuator # some crates
"""

import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def strip_comments_and_strings(text):
    """The text with comments and the contents of string and char literals blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "r" and re.match(r'r#*"', text[i:]) and (i == 0 or not re.match(r"[A-Za-z0-9_]", text[i - 1])):
            m = re.match(r'r(#*)"', text[i:])
            end = text.find('"' + m.group(1), i + len(m.group(0)))
            end = n if end < 0 else end + 1 + len(m.group(1))
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2 : end - 1]))
            i = end
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append('"' + re.sub(r"[^\n]", " ", text[i + 1 : j]) + '"')
            i = j + 1
        elif c == "'":
            # A char literal ('a', '\n', '\u{..}'), not a lifetime ('a).
            m = re.match(r"'(\\u\{[0-9a-fA-F]+\}|\\.|[^\\'])'", text[i:])
            if m:
                out.append("' '")
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def file_module(src, path):
    rel = os.path.relpath(path, src)[: -len(".rs")].split(os.sep)
    if rel[-1] == "mod" or (len(rel) == 1 and rel[0] in ("lib", "main")):
        rel = rel[:-1]
    return tuple(rel)


def expand_use_tree(tree):
    """`a::{b, c::{d as e}}` -> [('a::b', 'b'), ('a::c::d', 'e')]: each path and the name it binds."""
    tree = re.sub(r"\s+", "", re.sub(r"\s+as\s+", "@", tree))
    out = []

    def rec(prefix, t):
        parts, depth, cur = [], 0, ""
        for ch in t:
            if ch == "," and depth == 0:
                parts.append(cur)
                cur = ""
                continue
            depth += ch == "{"
            depth -= ch == "}"
            cur += ch
        parts.append(cur)
        for p in parts:
            p = p.strip()
            if not p:
                continue
            if "{" in p:
                head = p[: p.index("{")]
                rec(prefix + head, p[p.index("{") + 1 : p.rindex("}")])
            else:
                path, _, alias = p.partition("@")
                path = re.sub(r"::self$", "", prefix + path.strip())
                out.append((path, alias.strip() or path.split("::")[-1]))

    rec("", tree)
    return out


ITEM = re.compile(
    r"\b(?:fn|struct|enum|union|trait|type|const|static|mod)\s+(" + IDENT + r")|\bmacro_rules!\s*(" + IDENT + r")"
)


class Crate:
    """The modules of one crate's src/ folder: their text, the names they define and import."""

    def __init__(self, src):
        files = []
        for root, _, names in os.walk(src):
            if os.path.relpath(root, src).split(os.sep)[0] == "bin":
                continue  # src/bin/*: separate binary crates
            files += [os.path.join(root, f) for f in names if f.endswith(".rs")]
        if os.path.join(src, "lib.rs") in files and os.path.join(src, "main.rs") in files:
            files.remove(os.path.join(src, "main.rs"))  # the binary is its own crate over the library
        by_file = {f: file_module(src, f) for f in files}
        # `#[path = "x.rs"] mod name;` puts x.rs at the declaring module's `name`.
        for f in files:
            with open(f, encoding="utf-8") as fh:
                raw = fh.read()
            for p, name in re.findall(r'#\[path\s*=\s*"([^"]+)"\]\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(' + IDENT + r")\s*;", raw):
                target = os.path.normpath(os.path.join(os.path.dirname(f), p))
                if target in by_file:
                    by_file[target] = by_file[f] + (name,)
        self.files = {m: f for f, m in by_file.items()}
        self.modules = set(self.files)
        self.children = {}
        for m in self.modules:
            if m:
                self.children.setdefault(m[:-1], set()).add(m[-1])
        self.text, self.defined, self.imports, self.globs = {}, {}, {}, {}
        self.exported_macros = {}  # `#[macro_export]` macros live at the crate root's path
        for m, f in self.files.items():
            with open(f, encoding="utf-8") as fh:
                text = strip_comments_and_strings(fh.read())
            self.text[m] = text
            self.defined[m] = {a or b for a, b in ITEM.findall(text)}
            for name in re.findall(r"#\[macro_export\]\s*macro_rules!\s*(" + IDENT + r")", text):
                self.exported_macros[name] = m
            self.imports[m], self.globs[m] = {}, []
            for mu in re.finditer(r"\buse\s+([^;]+);", text):
                for path, alias in expand_use_tree(mu.group(1)):
                    if alias == "*":
                        self.globs[m].append(path[: -len("::*")])
                    else:
                        self.imports[m].setdefault(alias, path)

    def resolve(self, path, here, depth=0):
        """The module that defines what `path` (written in module `here`) names, or None outside the
        crate. Names a module imports from elsewhere (`pub use` re-exports of a crate root, or a
        child's `use super::Thing` of what its parent imported) resolve to where they are defined."""
        segs = [s for s in path.split("::") if s]
        if not segs or depth > 20:
            return None
        if segs[0] == "crate":
            mod, segs = (), segs[1:]
        elif segs[0] in ("super", "self"):
            mod = here
            while segs and segs[0] in ("super", "self"):
                if segs[0] == "super":
                    mod = mod[:-1]
                segs = segs[1:]
        elif segs[0] in self.children.get(here, ()):
            mod = here
        else:
            return None  # an external crate, std, or a local name
        while segs and mod + (segs[0],) in self.modules:
            mod, segs = mod + (segs[0],), segs[1:]
        if segs and mod == () and segs[0] in self.exported_macros:
            return self.exported_macros[segs[0]]
        if segs and mod in self.modules and segs[0] not in self.defined[mod]:
            name = segs[0]
            if name in self.imports[mod]:
                target = self.resolve(self.imports[mod][name], mod, depth + 1)
                return mod if target is None else target
            for g in self.globs[mod]:
                target = self.resolve(g, mod, depth + 1)
                if target is not None and target in self.modules and name in self.defined[target]:
                    return target
        return mod


def crate_edges(src):
    crate = Crate(src)
    modules = crate.modules
    edges = {}  # (a, b) -> (file, line)
    for m, f in sorted(crate.files.items()):
        text = crate.text[m]
        line_of = lambda pos: text.count("\n", 0, pos) + 1  # noqa: E731
        # Inline `mod x {` blocks: spans (start, end, name) to know where `super` points.
        inline = []
        for mm in re.finditer(r"\bmod\s+(" + IDENT + r")\s*\{", text):
            depth, j = 1, mm.end()
            while j < len(text) and depth:
                depth += text[j] == "{"
                depth -= text[j] == "}"
                j += 1
            inline.append((mm.start(), j, mm.group(1)))

        def add(path, pos):
            inner = tuple(name for s, e, name in sorted(inline) if s <= pos < e)
            if inner and path.startswith("super"):
                # Relative to an inline module (e.g. `mod tests`): drop one `super` per level.
                segs = path.split("::")
                k = 0
                while k < len(segs) and k < len(inner) and segs[k] == "super":
                    k += 1
                path = "::".join(["self"] + segs[k:]) if k == len(inner) else path
            target = crate.resolve(path, m)
            if target is not None and target != m and target in modules:
                edges.setdefault((m, target), (f, line_of(pos)))

        for mu in re.finditer(r"\buse\s+([^;]+);", text):
            for p, _ in expand_use_tree(mu.group(1)):
                add(p[: -len("::*")] if p.endswith("::*") else p, mu.start())
        used = set()
        for mu in re.finditer(r"\buse\s+[^;]+;", text):
            used.update(range(mu.start(), mu.end()))
        for mp in re.finditer(r"(?<![A-Za-z0-9_:])((?:crate|super|self)(?:::" + IDENT + r")+)", text):
            if mp.start() not in used:
                add(mp.group(1), mp.start())
    return modules, edges


def sccs(nodes, adj):
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def strong(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(adj.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            strong(v)
    return out


def a_cycle(comp, adj):
    """One cycle through the first module of a strongly connected component (breadth-first)."""
    start, inside = comp[0], set(comp)
    prev, queue = {start: None}, [start]
    while queue:
        v = queue.pop(0)
        for w in sorted(adj.get(v, ())):
            if w not in inside:
                continue
            if w == start:
                path = [v]
                while prev[path[-1]] is not None:
                    path.append(prev[path[-1]])
                return list(reversed(path)) + [start]
            if w not in prev:
                prev[w] = v
                queue.append(w)
    return comp


def name(m):
    return "::".join(m) or "crate"


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    crates = argv[1:] or sorted(
        os.path.join(root, "crates", c) for c in os.listdir(os.path.join(root, "crates"))
    )
    found = 0
    for crate in crates:
        src = os.path.join(crate, "src")
        if not os.path.isdir(src):
            continue
        modules, edges = crate_edges(src)
        adj = {}
        for a, b in edges:
            adj.setdefault(a, set()).add(b)
        cyc = [c for c in sccs(modules, adj) if len(c) > 1]
        label = os.path.basename(os.path.normpath(crate))
        if not cyc:
            print(f"{label}: no cycles ({len(modules)} modules, {len(edges)} edges)")
            continue
        found += len(cyc)
        print(f"{label}: {len(cyc)} cycle(s) ({len(modules)} modules, {len(edges)} edges)")
        for comp in cyc:
            print(f"  modules {', '.join(name(m) for m in comp)}")
            path = a_cycle(comp, adj)
            for a, b in zip(path, path[1:]):
                f, line = edges[(a, b)]
                print(f"    {name(a)} -> {name(b)}  ({os.path.relpath(f, root)}:{line})")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
