#!/usr/bin/env python3
"""Checks that the modules of src/ keep to the layers of doc/architecture.md.

usage: python3 tools/layer_check.py [SRC_DIR]

Each folder of src/ sits on one row of the drawing; a module may use the
modules of its own folder and of the rows below its row, never those of a row
above it nor of another folder on its own row.  Prints every use that breaks
the rule ('FOLDER/FILE uses MODULE of FOLDER') and exits 1 if there is one;
exits 0 and prints the number of uses checked otherwise.  A folder of src/ that
is on no row is an error too (a new folder takes its row here and in the
drawing).
"""
import os
import re
import sys

# The rows of doc/architecture.md's drawing, top to bottom.
ROWS = [
    ['app'],
    ['batch', 'plot'],
    ['analysis'],
    ['design'],
    ['model'],
    ['element', 'assembly', 'mechanism', 'harmonic', 'optim'],
    ['ode'],
    ['linalg'],
    ['io'],
    ['common'],
]

MODULE = re.compile(r'^\s*module\s+(\w+)\s*$', re.I)
USE = re.compile(r'^\s*use\s*(?:,\s*(?:non_)?intrinsic\s*::)?\s*(?:::)?\s*(\w+)', re.I)


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else 'src'
    row_of = {folder: k for k, row in enumerate(ROWS) for folder in row}
    defined = {}     # module -> folder
    uses = []        # (folder, path, module)
    problems = []
    for top, _, names in os.walk(src):
        for name in sorted(names):
            if not name.endswith('.f90'):
                continue
            path = os.path.join(top, name)
            folder = os.path.relpath(path, src).split(os.sep)[0]
            if folder not in row_of:
                problems.append('%s: folder %s is on no row of the drawing' % (path, folder))
                continue
            with open(path, encoding='utf-8') as f:
                for line in f:
                    code = line.split('!')[0]
                    m = MODULE.match(code)
                    if m and m.group(1).lower() != 'procedure':
                        defined[m.group(1).lower()] = folder
                    m = USE.match(code)
                    if m:
                        uses.append((folder, path, m.group(1).lower()))
    checked = 0
    for folder, path, module in uses:
        owner = defined.get(module)
        if owner is None or owner == folder:
            continue
        checked += 1
        if row_of[owner] <= row_of[folder]:
            where = 'its own row' if row_of[owner] == row_of[folder] else 'a row above'
            problems.append('%s uses %s of src/%s (%s)' % (path, module, owner, where))
    for p in sorted(set(problems)):
        print(p)
    if problems:
        return 1
    print('layers kept: %d uses of another folder\'s modules, each downward' % checked)
    return 0


if __name__ == '__main__':
    sys.exit(main())
