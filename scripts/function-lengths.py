#!/usr/bin/env python3
"""Lists the longest functions of the C++ sources (issue 21: none over ~100 lines).

A function is a definition that starts in column 0 (namespace level in this code base) or in
column 2 (a method defined in its struct's body) with a signature ending in '{', and ends at the
'}' in the same column. Lambdas count towards the function that holds them.
Usage: scripts/function-lengths.py [--limit N] [paths...]   (exit 1 when one is over the limit)
"""
import argparse, pathlib, re, sys

SIGNATURE_END = re.compile(r'\)\s*(const)?\s*(noexcept)?\s*(override)?\s*(->\s*[\w:<>, ]+)?\s*\{\s*(//.*)?$')


CONTROL = ('if ', 'if(', 'for ', 'for(', 'while', 'switch', 'else', 'do ', 'return', 'catch', 'try', '} ')
NOT_A_FUNCTION = ('namespace', 'struct', 'class', 'enum', 'using', 'template <', 'static const', 'const ', 'public', 'private')


def functions(path):
    """(name, first line, length) of each function defined in column 0 or, inside a struct or class
    body, in column 2 (inline methods)."""
    lines = path.read_text(errors='replace').splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        indent = len(line) - len(line.lstrip(' '))
        body = line[indent:]
        starts = indent in (0, 2) and body[:1] not in ('', '#', '/', '}', '{', '*', ':') \
            and not body.startswith(NOT_A_FUNCTION + CONTROL)
        if starts:
            j = i
            while j < len(lines) and j < i + 8 and not SIGNATURE_END.search(lines[j]) and not lines[j].rstrip().endswith(';'):
                j += 1
            if j < len(lines) and SIGNATURE_END.search(lines[j]):
                k = j + 1
                closing = ' ' * indent + '}'
                while k < len(lines) and not (lines[k].startswith(closing) and len(lines[k]) > indent and lines[k][indent] == '}'):
                    k += 1
                name = re.sub(r'\(.*', '', body).split()[-1] if '(' in body else body.strip()
                yield name, i + 1, k - i + 1
                i = k
        i += 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--limit', type=int, default=100)
    ap.add_argument('--top', type=int, default=15)
    ap.add_argument('paths', nargs='*', default=['common', 'filter_demarcating', 'filter_relief_edges',
                                                 'filter_multiscale', 'filter_prominent', 'filter_drawing_recon', 'batch'])
    a = ap.parse_args()
    found = []
    for root in a.paths:
        for path in sorted(p for ext in ('*.cpp', '*.h') for p in pathlib.Path(root).rglob(ext)):
            found += [(n, str(path), line, length) for n, line, length in functions(path)]
    found.sort(key=lambda f: -f[3])
    for name, path, line, length in found[:a.top]:
        print(f'{length:5d}  {path}:{line}  {name}')
    over = [f for f in found if f[3] > a.limit]
    print(f'{len(found)} functions, {len(over)} over {a.limit} lines')
    return 1 if over else 0


if __name__ == '__main__':
    sys.exit(main())
