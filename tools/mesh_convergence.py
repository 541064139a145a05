#!/usr/bin/env python3
"""The spatial reference outputs against the same decks on a finer mesh (doc/spatial.md, "Mesh convergence").

For every inputs/spatial_*.nml and inputs/cantilever_*.nml with a reference output (or the decks named,
e.g. a general_transient deck),
a copy with every link's element count multiplied by --factor (link_n_elements) is written under the
work directory and run;
the peaks (largest |value|) of the reference output's columns are compared with the finer run's: the
joint and link-end columns by name, the element stresses per link (the largest over the link's
elements, since the element columns are numbered along the mesh).  The difference is relative as in
tools/default_settings.py (a column against the larger of its peak and 1 % of the largest peak of its
kind).  Exit status 1 when a deck's worst peak differs by more than --check percent.

With --default-solver the finer run leaves out the deck's solver lines (method, rtol, atol, atol_rate,
max_order: the settings flexmech chooses, doc/transient.md), for a deck whose own tolerances make the
finer mesh too slow; the difference then holds the chosen settings' time error too.

usage: python3 tools/mesh_convergence.py [--flexmech build/bin/flexmech] [--work build/mesh_convergence]
                                          [--factor 2] [--check PERCENT] [--last-turn] [--default-solver]
                                          [DECK_NAME ...]
"""
import argparse
import glob
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import default_settings  # noqa: E402
from default_settings import read_table  # noqa: E402

LINKS = ('crank', 'coupler', 'rocker')      # the spatial four-bar's links (a deck without link_name)


def element_counts(text):
    """The deck's link_n_elements as three integers (the forms 'n1, n2, n3' and '3*n')."""
    m = re.search(r'^\s*link_n_elements\s*=\s*([^!\n]*)', text, re.MULTILINE | re.IGNORECASE)
    counts = []
    for item in m.group(1).replace(',', ' ').split():
        if '*' in item:
            times, value = item.split('*')
            counts += [int(value)] * int(times)
        else:
            counts.append(int(item))
    return counts


SOLVER_LINE = re.compile(r'^\s*(method|rtol|atol|atol_rate|max_order)\s*=.*\n', re.MULTILINE | re.IGNORECASE)


def without_solver_lines(text):
    """The deck without its solver lines (each on its own line in the shipped decks)."""
    return SOLVER_LINE.sub('', text)


def link_names(text, n):
    """The deck's link_name values (a planar &mechanism deck), else the spatial four-bar's links."""
    m = re.search(r'^\s*link_name\s*=\s*([^!\n]*)', text, re.MULTILINE | re.IGNORECASE)
    names = re.findall(r"'([^']*)'", m.group(1)) if m else []
    return tuple(names) if len(names) == n else LINKS[:n]


def refined(text, factor):
    counts = [factor * n for n in element_counts(text)]
    line = '  link_n_elements = ' + ', '.join(str(n) for n in counts)
    return re.sub(r'^\s*link_n_elements\s*=[^!\n]*', line, text, count=1, flags=re.MULTILINE | re.IGNORECASE)


def kind(name):
    """The group a column is judged in (see the module's text)."""
    if name.startswith('sigma'):
        return 'sigma'
    for suffix, group in (('_N_root', 'N'), ('_root', 'M'), ('x_end', 'rot'), ('y_end', 'rot'),
                          ('z_end', 'rot'), ('_end', 'disp')):
        if name.endswith(suffix):
            return group
    return re.sub(r'^[A-Z]_([A-Z]).*$', r'\1', name)


def worst_peak(ref, new):
    """(largest relative peak difference, its column): tools/default_settings.py's, with the kinds above."""
    return default_settings.worst_peak(ref, new, kind)


def link_peaks(path, counts, last_turn=False, links=LINKS):
    """Peaks of an output: its columns by name, its element stresses merged per link (named by links);
    over its last revolution only with last_turn."""
    names, rows, _ = read_table(path)
    if last_turn:
        angle = names.index('crank_deg')
        end = max(r[angle] for r in rows)
        rows = [r for r in rows if r[angle] >= end - 360.0 - 1.0e-6]
    result, first = {}, 1
    for link, n in zip(links, counts):
        elems = ['sigma_max_e%d' % k for k in range(first, first + n)]
        first += n
        vals = [abs(r[names.index(e)]) for e in elems if e in names for r in rows
                if r[names.index(e)] == r[names.index(e)]]
        if vals:
            result['sigma_' + link] = max(vals)
    for j, name in enumerate(names):
        if name in ('t', 'crank_deg', 'drive') or name.startswith('sigma_max_e'):
            continue
        values = [abs(r[j]) for r in rows if r[j] == r[j]]
        if values:
            result[name] = max(values)
    return result


def revolutions(path):
    """Revolutions of the crank the output covers (0 for an output without a crank angle: a general
    mechanism's, whose columns are then judged over the whole run)."""
    names, rows, _ = read_table(path)
    if 'crank_deg' not in names:
        return 0.0
    angle = [r[names.index('crank_deg')] for r in rows]
    return (max(angle) - min(angle)) / 360.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--flexmech', default='build/bin/flexmech')
    ap.add_argument('--work', default='build/mesh_convergence')
    ap.add_argument('--factor', type=int, default=2)
    ap.add_argument('--check', type=float, default=None)
    ap.add_argument('--last-turn', action='store_true',
                    help='judge a run of several revolutions (--check) by its last revolution')
    ap.add_argument('--default-solver', action='store_true',
                    help='run the finer mesh at the solver settings flexmech chooses')
    ap.add_argument('decks', nargs='*')
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    names = args.decks or sorted(os.path.basename(p)[:-4]
                                 for p in glob.glob('inputs/spatial_*.nml') + glob.glob('inputs/cantilever_*.nml')
                                 if os.path.exists('reference_outputs/' + os.path.basename(p)[:-4] + '.out'))
    failed = False
    print('| deck | mesh | finer | peak stress psi per link, this / finer | worst peak difference | '
          'last revolution |')
    print('|---|---|---|---|---|---|')
    for name in names:
        with open('inputs/%s.nml' % name) as f:
            text = f.read()
        counts = element_counts(text)
        links = link_names(text, len(counts))
        deck = os.path.join(args.work, name + '_fine.nml')
        out = os.path.join(args.work, name + '_fine.out')
        with open(deck, 'w') as f:
            fine = refined(text, args.factor)
            f.write(without_solver_lines(fine) if args.default_solver else fine)
        proc = subprocess.run([args.flexmech, deck, '-o', out], stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0:
            print('| %s | run failed (exit %d): %s |' % (name, proc.returncode, proc.stderr.strip()[:200]))
            failed = True
            continue
        ref = link_peaks('reference_outputs/%s.out' % name, counts, links=links)
        new = link_peaks(out, [args.factor * n for n in counts], links=links)
        worst, where = worst_peak(ref, new)
        last = '(whole run: one revolution or less)'
        if revolutions('reference_outputs/%s.out' % name) > 1.01:
            worst_last, where_last = worst_peak(
                link_peaks('reference_outputs/%s.out' % name, counts, True, links),
                link_peaks(out, [args.factor * n for n in counts], True, links))
            last = '%.3f %% (%s)' % (100.0 * worst_last, where_last)
            if args.last_turn:
                worst = worst_last
        stress = ', '.join('%s %.0f / %.0f' % (k, ref.get('sigma_' + k, 0.0), new.get('sigma_' + k, 0.0))
                           for k in links)
        print('| %s | %s | %s | %s | %.3f %% (%s) | %s |' % (name, ', '.join(map(str, counts)),
              ', '.join(str(args.factor * n) for n in counts), stress, 100.0 * worst, where, last))
        sys.stdout.flush()
        if args.check is not None and 100.0 * worst > args.check:
            failed = True
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
