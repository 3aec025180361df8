#!/usr/bin/env python3
"""The folders of include/tissuefem and source/ depend on each other without
a cycle (issue 32: base/ pointed up at every system, boundary/ and solid/
included each other; later solid/ and forces/): a folder may include
another's headers only where that one does not, directly or through others,
include its own. base/ includes nothing but base/. Prints each folder
dependency found in a cycle, with a file that makes it, and fails.

Usage: folder_dependencies.py <repository top>"""
import os
import re
import sys

top = sys.argv[1] if len(sys.argv) > 1 else "."
edges = {}  # folder -> {folder it includes: a file that does}
for root in ("include/tissuefem", "source"):
    for directory, _, files in os.walk(os.path.join(top, root)):
        for name in files:
            path = os.path.join(directory, name)
            relative = os.path.relpath(path, os.path.join(top, root))
            if "/" not in relative or not name.endswith((".h", ".cc")):
                continue
            folder = relative.split("/")[0]
            edges.setdefault(folder, {})
            for line in open(path, encoding="utf-8"):
                m = re.match(r"\s*#\s*include\s*<tissuefem/(\w+)/", line)
                if m and m.group(1) != folder:
                    edges[folder].setdefault(m.group(1), os.path.relpath(path, top))

failures = []
for target, where in edges.get("base", {}).items():
    failures.append("base -> %s (%s): base/ must include only base/" % (target, where))


def reaches(start, goal):
    seen, stack = set(), [start]
    while stack:
        folder = stack.pop()
        if folder == goal:
            return True
        if folder not in seen:
            seen.add(folder)
            stack.extend(edges.get(folder, {}))
    return False


for folder, targets in sorted(edges.items()):
    for target, where in sorted(targets.items()):
        if reaches(target, folder):
            failures.append("%s -> %s (%s) is in a cycle" % (folder, target, where))

print("%d folders, %d folder dependencies" % (len(edges), sum(len(t) for t in edges.values())))
for failure in failures:
    print(failure)
sys.exit(1 if failures else 0)
