#!/usr/bin/env python3
"""Lines per Fortran procedure, for the "routines a reader can hold in the head"
rule (doc/architecture.md, Routine length): every procedure longer than LIMIT
lines from its header to its end statement, with its own body in brackets
(contained procedures counted in their host and on their own).

usage: python3 tools/routine_lengths.py LIMIT FILE...
"""
import re
import sys

PREFIX = r'(?:(?:pure|elemental|recursive|impure|module|integer|logical|real|' \
         r'(?:real|integer|logical|character|type|class)\([^)]*\))\s+)*'
START = re.compile(r'^\s*' + PREFIX + r'(subroutine|function)\s+(\w+)', re.I)
END = re.compile(r'^\s*end\s+(subroutine|function)\b', re.I)


def main():
    limit = int(sys.argv[1])
    rows = []
    for path in sys.argv[2:]:
        stack = []
        with open(path, errors='replace') as f:
            for n, line in enumerate(f, 1):
                code = line.split('!')[0]
                if END.match(code):
                    if not stack:
                        continue
                    name, first, inner = stack.pop()
                    length = n - first + 1
                    if stack:
                        stack[-1][2] += length
                    if length > limit:
                        rows.append((length, length - inner, f'{path}:{first}', name, bool(stack)))
                else:
                    m = START.match(code)
                    if m and not re.match(r'^\s*end\b', code):
                        stack.append([m.group(2), n, 0])
    for length, own, where, name, contained in sorted(rows, reverse=True):
        print(f'{length:5d} ({own:4d} own) {where} {name}' + ('  (contained)' if contained else ''))


if __name__ == '__main__':
    main()
