#!/usr/bin/env python3
"""Lists the use edges between the files of one Rust crate and the cycles among them.

A file A uses a file B when A names an item B defines: through a `use` (a `pub use` counts only
where the file also names the item itself, so a module that merely re-exports its children does
not depend on them), a path in the code (`crate::x::Y`, `super::Y`, `child::Y`) or an intra-doc
link (`[`Y`]`, `[text](super::Y)`). `#[cfg(test)]` modules are left out: tests may reach anywhere.
The crate root's own doc links are left out too: the root declares every module, and its
overview is the crate's table of contents.

Two readings of "the file B defines", both reported:
- written: the file of the module the path names the item in (`crate::integrator::X` is an edge
  to integrator/mod.rs even when that file only re-exports X);
- defining: following re-exports to the file that declares the item.

A cycle is a strongly connected set of files (two or more). Used to keep a crate's files
layered: a file should be readable knowing only the files below it.

    scripts/import_cycles.py core/src            # cycles only; exit status 1 if any
    scripts/import_cycles.py core/src --edges    # every edge too
"""
import os
import re
import sys
from collections import defaultdict

ITEM = re.compile(
    r"^(?:pub(?:\([\w:\s]+\))?\s+)?(?:(?:const|unsafe|async|extern\s+\"C\")\s+)*"
    r"(fn|struct|enum|trait|type|const|static|mod|union|macro_rules!)\s+(\w+)"
)
KEYWORDS = {"crate", "super", "self", "Self"}


def strip(src):
    """Returns (code, docs): code without comments and string contents, and the doc-comment text
    (with its line numbers kept) for intra-doc links."""
    code, docs = [], []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
            text = src[i:j]
            if text.startswith("///") or text.startswith("//!"):
                docs.append(text)
            code.append(" " * (j - i))
            i = j
        elif src.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            code.append(re.sub(r"[^\n]", " ", src[i:j]))
            i = j
        elif c == '"' or (c == "r" and re.match(r'r#*"', src[i:]) and not re.match(r"\w", src[i - 1])):
            m = re.match(r'r(#*)"', src[i:])
            if m:
                end = '"' + m.group(1)
                j = src.find(end, i + len(m.group(0)))
                j = n if j < 0 else j + len(end)
            else:
                j = i + 1
                while j < n and src[j] != '"':
                    j += 2 if src[j] == "\\" else 1
                j += 1
            code.append('""' + re.sub(r"[^\n]", " ", src[i + 2 : j]))
            i = j
        elif c == "'" and re.match(r"'(\\.[^']*|[^\\'])'", src[i:]):
            m = re.match(r"'(\\.[^']*|[^\\'])'", src[i:])
            code.append(" " * len(m.group(0)))
            i += len(m.group(0))
        else:
            code.append(c)
            i += 1
    return "".join(code), "\n".join(docs)


def drop_test_modules(code):
    """Blanks `#[cfg(test)]` items (test modules and test-only functions)."""
    out = code
    for m in reversed(list(re.finditer(r"#\[cfg\(test\)\]", code))):
        j = m.end()
        while j < len(code) and code[j] not in "{;":
            j += 1
        if j < len(code) and code[j] == "{":
            depth = 0
            while j < len(code):
                depth += code[j] == "{"
                depth -= code[j] == "}"
                j += 1
                if depth == 0:
                    break
        else:
            j += 1
        out = out[: m.start()] + re.sub(r"[^\n]", " ", out[m.start() : j]) + out[j:]
    return out


def split_use_tree(tree, prefix=()):
    """Expands `a::{b, c::{d as e}}` into (path, name) pairs; `*` gives name `*`."""
    tree = tree.strip()
    if not tree:
        return []
    depth, brace = 0, -1
    for k, ch in enumerate(tree):
        if ch == "{" and depth == 0:
            brace = k
            break
        depth += ch == "("
    if brace >= 0:
        head = [s for s in tree[:brace].split("::") if s.strip()]
        inner = tree[brace + 1 : tree.rindex("}")]
        parts, depth, start = [], 0, 0
        for k, ch in enumerate(inner):
            depth += ch == "{"
            depth -= ch == "}"
            if ch == "," and depth == 0:
                parts.append(inner[start:k])
                start = k + 1
        parts.append(inner[start:])
        out = []
        for p in parts:
            out += split_use_tree(p, prefix + tuple(s.strip() for s in head))
        return out
    alias = None
    m = re.match(r"(.*)\s+as\s+(\w+)$", tree)
    if m:
        tree, alias = m.group(1).strip(), m.group(2)
    segs = prefix + tuple(s.strip() for s in tree.split("::"))
    if segs[-1] == "self":
        segs = segs[:-1]
    name = alias or segs[-1]
    return [(segs, name)]


class Module:
    def __init__(self, path, file, parent):
        self.path, self.file, self.parent = path, file, parent
        self.children = {}
        self.items = set()
        self.imports = {}  # name -> (segments, is_pub)
        self.globs = []  # (segments, is_pub)
        self.code = ""
        self.docs = ""


def load(src_dir):
    mods = {}

    def visit(path, file, parent):
        m = Module(path, file, parent)
        mods[path] = m
        with open(file, encoding="utf-8") as f:
            code, docs = strip(f.read())
        code = drop_test_modules(code)
        m.code, m.docs = code, docs
        depth = 0
        for line in code.split("\n"):
            if depth == 0:
                im = ITEM.match(line.strip())
                if im:
                    kind, name = im.groups()
                    if kind == "mod" and line.rstrip().endswith(";"):
                        base = os.path.dirname(file)
                        if not (file.endswith("mod.rs") or file.endswith("lib.rs")):
                            base = os.path.join(base, os.path.basename(file)[:-3])
                        for cand in (os.path.join(base, name + ".rs"), os.path.join(base, name, "mod.rs")):
                            if os.path.exists(cand):
                                m.children[name] = path + (name,)
                                visit(path + (name,), cand, m)
                                break
                    else:
                        m.items.add(name)
            depth += line.count("{") - line.count("}")
        for um in re.finditer(r"(?m)^\s*(pub(?:\([\w:\s]+\))?\s+)?use\s+([^;]+);", code):
            for segs, name in split_use_tree(um.group(2).replace("\n", " ")):
                if name == "*":
                    m.globs.append((segs[:-1], bool(um.group(1))))
                else:
                    m.imports[name] = (segs, bool(um.group(1)))
        return m

    root = os.path.join(src_dir, "lib.rs")
    if not os.path.exists(root):
        root = os.path.join(src_dir, "main.rs")
    visit((), root, None)
    return mods


class Resolver:
    def __init__(self, mods):
        self.mods = mods

    def start(self, mod, first):
        """The module a path beginning with `first`, written in `mod`, starts from, or None."""
        if first == "crate":
            return ()
        if first == "self":
            return mod.path
        if first == "super":
            return mod.path[:-1]
        if first in mod.children:
            return mod.children[first]
        return None

    def resolve(self, mod, segs, seen=None):
        """Resolves a path written in `mod` to ((written file, defining file) or None)."""
        seen = seen or set()
        key = (mod.path, tuple(segs))
        if key in seen:
            return None
        seen.add(key)
        if not segs:
            return None
        cur = self.start(mod, segs[0])
        rest = list(segs[1:])
        if cur is None:
            if segs[0] in mod.imports:
                imp, _ = mod.imports[segs[0]]
                return self.resolve(mod, list(imp) + rest, seen)
            if segs[0] in mod.items:
                return (mod.file, mod.file)
            return None
        while rest and rest[0] == "super":
            cur, rest = cur[:-1], rest[1:]
        while True:
            here = self.mods[cur]
            if not rest:
                return (here.file, here.file)
            name = rest[0]
            if name in here.children:
                cur, rest = here.children[name], rest[1:]
                continue
            if name in here.items:
                return (here.file, here.file)
            if name in here.imports:
                target = self.resolve(here, list(here.imports[name][0]) + rest[1:], seen)
                if target is None:
                    return None
                if self.mods_by_file(target[0]) is not None and target[0] != here.file:
                    # The written file is the module the path named; the defining file is where
                    # the re-export leads.
                    return (here.file, target[1])
                return target
            for gsegs, _ in here.globs:
                target = self.resolve(here, list(gsegs) + rest, seen)
                if target is not None:
                    return (here.file, target[1])
            return None

    def mods_by_file(self, file):
        for m in self.mods.values():
            if m.file == file:
                return m
        return None


def edges(mods):
    res = Resolver(mods)
    written, defining = defaultdict(set), defaultdict(set)

    def add(mod, segs, why):
        t = res.resolve(mod, segs)
        if t is None:
            return
        w, d = t
        if w != mod.file:
            written[mod.file].add((w, why))
        if d != mod.file:
            defining[mod.file].add((d, why))

    for mod in mods.values():
        code_no_use = re.sub(r"(?m)^\s*(pub(?:\([\w:\s]+\))?\s+)?use\s+[^;]+;", "", mod.code)
        idents = set(re.findall(r"\b\w+\b", code_no_use))
        for name, (segs, is_pub) in mod.imports.items():
            if is_pub and name not in idents:
                continue
            if segs and segs[0] not in KEYWORDS and segs[0] not in mod.children:
                continue  # another crate
            add(mod, list(segs), "use " + "::".join(segs))
        for m in re.finditer(r"(?<![\w:])(\w+)((?:::\w+)+)", code_no_use):
            first = m.group(1)
            if first in ("crate", "super", "self") or first in mod.children:
                segs = [first] + m.group(2).split("::")[1:]
                add(mod, segs, "::".join(segs))
        docs = "" if mod.path == () else mod.docs
        for m in re.finditer(r"\[`([^`\]]+)`\](?!\()|\]\(([\w:]+)\)", docs):
            link = m.group(1) or m.group(2)
            link = re.sub(r"^(fn|struct|enum|trait|type|const|static|mod|macro|method)@", "", link)
            link = re.sub(r"(\(\)|!)$", "", link)
            if not re.fullmatch(r"\w+(::\w+)*", link):
                continue
            segs = link.split("::")
            if segs[0] == "Self":
                continue
            add(mod, segs, "doc [" + link + "]")
    return written, defining


def cycles(graph, nodes):
    """Strongly connected components of two or more files (Tarjan)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted({t for t, _ in graph.get(v, ())}):
            if w not in index:
                visit(w)
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
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit(__doc__)
    src = args[0].rstrip("/")
    mods = load(src)
    files = [m.file for m in mods.values()]
    rel = lambda f: os.path.relpath(f, src)
    found = False
    for label, graph in zip(("written", "defining"), edges(mods)):
        if "--edges" in sys.argv:
            print(f"# edges ({label})")
            for a in sorted(graph):
                for b, why in sorted(graph[a]):
                    print(f"{rel(a)} -> {rel(b)}   ({why})")
        comps = cycles(graph, files)
        print(f"# cycles ({label}): {len(comps)}")
        for comp in comps:
            found = True
            members = set(comp)
            print("  " + " <-> ".join(rel(f) for f in comp))
            for a in comp:
                for b, why in sorted(graph[a]):
                    if b in members:
                        print(f"    {rel(a)} -> {rel(b)}   ({why})")
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
