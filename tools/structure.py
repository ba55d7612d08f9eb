#!/usr/bin/env python3
"""Structure report of the MAPTR tree: the largest source files, the longest functions, and
includes that point up the layer order (deploy -> process nodes -> comm -> config, records,
idl -> control cores -> model).

    tools/structure.py [--top N] [ROOT]

Reads the C++ sources outside tests/ and build*/ as text. Functions are found by brace
matching: a definition is a `{` opened at namespace or class level after a line holding `(`;
its length runs from the signature to the closing brace (lambdas count in their function).
"""
import argparse
import os
import re
import sys

# Layer of each folder (its first level, or its first two where listed): an include may point
# to the same or a lower layer.
LAYERS = {
    "model": 0,
    "control": 1, "plant_core": 1,
    "config": 2, "records": 2, "idl": 2,
    "comm/posix": 3.0, "comm/dds": 3.1, "comm/lockstep": 3.2,
    "agent": 4, "group": 4, "central": 4, "plant": 4,
    "deploy": 5, "tools": 5,
}
SOURCE = re.compile(r"\.(cpp|hpp|h|cc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|else|do|try)\b")


def layer(path):
    """The layer of a file or include path: its first two folders if listed, else its first."""
    parts = path.replace(os.sep, "/").split("/")
    return LAYERS.get("/".join(parts[:2]), LAYERS.get(parts[0]))


def sources(root):
    for d, dirs, files in os.walk(root):
        rel = os.path.relpath(d, root)
        top = rel.split(os.sep)[0]
        if rel != "." and top.startswith(".") or top.startswith("build") or top in ("tests", "runs", "docs", "node_modules"):
            dirs[:] = []
            continue
        for f in files:
            if SOURCE.search(f):
                yield os.path.normpath(os.path.join(rel, f))


def strip(line):
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def functions(path, text):
    """(name, first line, length) of each function defined at namespace or class level."""
    out, kinds, sig, start = [], [], "", 0
    for no, raw in enumerate(text.splitlines(), 1):
        line = strip(raw)
        if line.strip().startswith("#"):
            continue
        for ch in line + "\n":
            in_fn = any(k == "fn" for k in kinds)
            if ch == "{":
                head = " ".join(sig.split())
                is_fn = ("(" in head and not CONTROL.match(head)
                         and "=" not in head.split("(")[0]
                         and not re.match(r"(namespace|struct|class|enum|union)\b", head))
                if not in_fn and is_fn:
                    name = re.findall(r"([~\w:]+)\s*\(", head.split(")")[0] + ")")
                    kinds.append("fn")
                    out.append([name[0] if name else "?", start or no, no])
                else:
                    kinds.append("block" if in_fn else "scope")
                sig, start = "", 0
            elif ch == "}":
                kind = kinds.pop() if kinds else "scope"
                if kind == "fn":
                    out[-1][2] = no
                sig, start = "", 0
            elif ch == ";" and not in_fn:
                sig, start = "", 0
            elif not in_fn:
                if not ch.isspace() and not start:
                    start = no
                sig += ch
    return [(n, a, b - a + 1) for n, a, b in out]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--top", type=int, default=5)
    a = ap.parse_args()
    root = os.path.abspath(a.root)
    files, fns, up = [], [], []
    for rel in sorted(sources(root)):
        text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
        files.append((len(text.splitlines()), rel))
        fns += [(n, rel, line, length) for n, line, length in functions(rel, text)]
        me = layer(rel)
        for no, line in enumerate(text.splitlines(), 1):
            m = INCLUDE.match(line)
            if not m or me is None:
                continue
            them = layer(m.group(1))
            if them is not None and them > me:
                up.append(f"{rel}:{no} -> {m.group(1)}")
    files.sort(reverse=True)
    fns.sort(key=lambda f: -f[3])
    print(f"source files: {len(files)}, lines: {sum(n for n, _ in files)}")
    print("largest files:")
    for n, rel in files[: a.top]:
        print(f"  {n:6d}  {rel}")
    print("longest functions:")
    for name, rel, line, length in fns[: a.top]:
        print(f"  {length:6d}  {rel}:{line} {name}")
    print(f"includes pointing up the layers: {len(up)}")
    for u in up:
        print(f"  {u}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
