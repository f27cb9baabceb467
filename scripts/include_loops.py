#!/usr/bin/python3
"""Include loops in src/: between folders and between files.

Every quoted #include is resolved as the compiler does (beside the file, then
src/). A loop is a strongly connected set of more than one node: of files
(a.hpp includes b.hpp, which includes a.hpp again through any chain, a .cpp
counting as its header's), or of folders (src/core/x includes src/core/y and
y includes x). Prints each loop, then a summary line; exits 1 if any.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def sources(src):
    for root, _, names in os.walk(src):
        for name in names:
            if name.endswith(('.hpp', '.cpp', '.cc', '.h')):
                yield os.path.relpath(os.path.join(root, name), src)


def includes(src, path):
    with open(os.path.join(src, path), encoding='utf-8') as f:
        text = f.read()
    for target in INCLUDE.findall(text):
        for base in (os.path.dirname(path), ''):
            candidate = os.path.normpath(os.path.join(base, target))
            if os.path.isfile(os.path.join(src, candidate)):
                yield candidate
                break


def unit(path):
    """A .cpp and its header are one node: the header's loop is the file's."""
    stem, ext = os.path.splitext(path)
    return stem if ext in ('.hpp', '.cpp', '.h', '.cc') else path


def loops(edges):
    """Tarjan's strongly connected components with more than one node."""
    index, low, stack, on, found, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), '..', 'src')
    files, folders = {}, {}
    count = 0
    for path in sources(src):
        count += 1
        for target in includes(src, path):
            a, b = unit(path), unit(target)
            if a != b:
                files.setdefault(a, set()).add(b)
            fa, fb = os.path.dirname(path), os.path.dirname(target)
            if fa != fb:
                folders.setdefault(fa, set()).add(fb)
    file_loops = loops(files)
    folder_loops = loops(folders)
    for loop in folder_loops:
        print('folder loop: ' + ' <-> '.join(loop))
    for loop in file_loops:
        print('file loop: ' + ' <-> '.join(loop))
    print('%d files, %d folders: %d folder loops, %d file loops'
          % (count, len(set(folders) | {f for t in folders.values() for f in t}),
             len(folder_loops), len(file_loops)))
    return 1 if file_loops or folder_loops else 0


if __name__ == '__main__':
    sys.exit(main())
