#!/usr/bin/env python3
"""The default solver settings against the tuned decks (doc/benchmarks.md, "Default solver settings").

For every transient, spatial and steady deck of inputs/ with a reference output, a copy without its
solver lines (&transient: method, rtol, atol, atol_rate, max_order; &steady: integrator, rtol, atol) is
written under the work directory and run; its peaks (largest |value| of every data column) are
compared with the reference output's, and its CPU time with that of the tuned deck run now.

usage: python3 tools/default_settings.py [--flexmech build/bin/flexmech] [--work build/default_settings]
                                         [--markdown] [--check PERCENT] [--cases] [DECK_NAME_FILTER ...]
  --markdown   print the table as Markdown (doc/benchmarks.md)
  --check P    exit 1 when a deck's worst peak differs by more than P % (no CPU check: tests run it)
  --cases      instead: decks a user writes with their own solver lines, against the defaults: Tennant's
               four-bar at 150 rad/s with the consistent element (2 per link, one revolution) and the
               spin-up beam with 4 elements (a run is stopped after 60 s of CPU)
Peaks: a column's difference is taken relative to the larger of its reference peak and 1 % of the
largest reference peak among the columns of its kind (the name without its first word and digits:
B_U and C_U are kinds of 'U', sigma_max_e1 .. e3 of 'max_e'), so that a column that hardly moves
is not judged by its last digits; a column whose kind peaks below 1e-10 of the table's largest peak
holds round-off and is not compared.  t and crank_deg are not compared.
"""
import argparse
import os
import re
import subprocess
import sys

SOLVER_VARIABLES = {'transient': ('method', 'rtol', 'atol', 'atol_rate', 'max_order'),
                    'steady': ('integrator', 'rtol', 'atol')}
NOT_COMPARED = ('t', 'crank_deg', 'time', 'theta_deg')


def analysis_of(text):
    m = re.search(r"analysis\s*=\s*'([a-z_]+)'", text)
    return m.group(1) if m else ''


def strip_solver_lines(text):
    """The deck without the solver variables of its &transient / &steady groups; the names removed."""
    out, removed, group = [], [], None
    for line in text.splitlines(keepends=True):
        stripped = line.strip()
        m = re.match(r'&(\w+)', stripped)
        if m:
            group = m.group(1).lower()
        elif stripped.startswith('/'):
            group = None
        names = SOLVER_VARIABLES.get(group, ())
        code, bang, comment = line.partition('!')
        kept = []
        for item in re.split(r',(?=\s*[A-Za-z_]\w*\s*(?:\(\s*\d+\s*\))?\s*=)', code):
            m = re.match(r'\s*([A-Za-z_]\w*)\s*=', item)
            if m and m.group(1).lower() in names:
                removed.append(m.group(1).lower())
                continue
            kept.append(item)
        new = ','.join(kept)
        if new.strip() or not code.strip():
            out.append(new + (bang + comment if bang else ('' if new.endswith('\n') else '\n')))
    return ''.join(out), removed


def read_table(path):
    """Column names, rows and cost lines of a flexmech output."""
    names, rows, cost, last_comment = [], [], {}, ''
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                last_comment = line
                m = re.match(r'# cost: (\w+) = (.*)', line)
                if m:
                    cost[m.group(1)] = m.group(2).strip()
                continue
            if not line.strip():
                continue
            if not names:
                names = last_comment[1:].split()
            try:
                rows.append([float(v) for v in line.split()])
            except ValueError:
                rows.append([float('nan')] * len(names))
    return names, rows, cost


def peaks(names, rows):
    result = {}
    for j, name in enumerate(names):
        if name in NOT_COMPARED:
            continue
        values = [abs(r[j]) for r in rows if j < len(r) and r[j] == r[j]]
        if values:
            result[name] = max(values)
    return result


def kind(name):
    words = re.sub(r'\d+', '', name).split('_')
    return '_'.join(words[1:]) if len(words) > 1 else words[0]


def worst_peak(ref, new, kind_of=kind):
    """(largest relative peak difference, its column) over the columns both tables have; kind_of(name)
    names the columns a column is scaled with."""
    largest, table_peak = {}, max(ref.values(), default=0.0)
    for name, p in ref.items():
        largest[kind_of(name)] = max(largest.get(kind_of(name), 0.0), p)
    worst, where = 0.0, ''
    for name, p in ref.items():
        if name not in new:
            return float('inf'), name + ' missing'
        scale = max(p, 0.01 * largest[kind_of(name)])
        if scale <= 1.0e-10 * table_peak:     # round-off (out-of-plane columns of a planar motion)
            continue
        d = abs(new[name] - p) / scale
        if d > worst:
            worst, where = d, name
    return worst, where


def run(flexmech, deck, out):
    proc = subprocess.run([flexmech, deck, '-o', out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                          text=True)
    return proc.returncode, proc.stderr


def chosen(path):
    """The header's '(chosen)' lines, shortened."""
    picks = []
    with open(path) as f:
        for line in f:
            m = re.match(r'# (method|atol|atol_rate|max_order) = (\S+) \(chosen\)', line)
            if m:
                value = m.group(2).strip("'")
                picks.append(value if m.group(1) == 'method' else m.group(1) + ' ' + value)
    return ', '.join(picks)


CASES = [
    # (name, deck, edits of the deck: (pattern, replacement) on its text, solver lines for &transient)
    ('four-bar 150 rad/s, consistent element, 2 per link, 1 turn', 'fourbar_150_geometric',
     [(r"formulation = 'exact'", "formulation = 'default'"), (r'link_n_elements = 3\*1', 'link_n_elements = 3*2'),
      (r'revolutions = 5', 'revolutions = 1')],
     ['', 'rtol = 1.0e-8, atol = 1.0e-10', 'rtol = 1.0e-8, atol = 1.0e-10, atol_rate = 1.0e-4',
      'rtol = 1.0e-9, atol = 1.0e-11, atol_rate = 1.0e-5, max_order = 0']),
    ('spin-up beam Ws = 4 rad/s, 4 elements', 'spinup_ws4',
     [(r'link_n_elements = 8', 'link_n_elements = 4')],
     ['', 'rtol = 1.0e-8', 'rtol = 1.0e-8, method = \'bdf\'', 'rtol = 1.0e-8, method = \'bdf\', max_order = 2',
      'rtol = 1.0e-8, method = \'bdf\', max_order = 2, atol = 1.0e-7, atol_rate = 1.0e-4']),
]


def run_cases(args, markdown):
    """The decks of CASES: one run per solver line; steps, CPU, peak stresses and what was chosen."""
    rows = []
    for title, deck, edits, solver_lines in CASES:
        text, _ = strip_solver_lines(open(f'inputs/{deck}.nml').read())
        for pattern, repl in edits:
            text, n = re.subn(pattern, repl, text)
            if n == 0:
                sys.exit(f'{deck}: no {pattern} to edit')
        for k, line in enumerate(solver_lines):
            path = f'{args.work}/case_{deck}_{k}.nml'
            with open(path, 'w') as f:
                f.write(text.replace('&transient\n', '&transient\n  ' + line + '\n', 1) if line else text)
            out = path[:-4] + '.out'
            if os.path.exists(out):
                os.remove(out)
            proc = subprocess.run(['sh', '-c', f'ulimit -t 60; exec {args.flexmech} {path} -o {out}'],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if not os.path.exists(out):
                rows.append((title, line or '(none: the defaults)', 'stopped after 60 s CPU', '', '', ''))
                continue
            names, table, cost = read_table(out)
            pk = peaks(names, table)
            stress = max((v for n, v in pk.items() if n.startswith('sigma_max')), default=float('nan'))
            rows.append((title, line or '(none: the defaults)', cost.get('steps', ''),
                         cost.get('total_cpu_seconds', ''), f'{stress:.6g}', chosen(out) or ''))
    head = ('case', 'solver lines', 'steps', 'CPU (s)', 'largest peak stress (psi or Pa)', 'chosen')
    if markdown:
        print('| ' + ' | '.join(head) + ' |')
        print('|' + '---|' * len(head))
    for r in rows:
        print(('| ' + ' | '.join(r) + ' |') if markdown else '  '.join(r))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--flexmech', default='build/bin/flexmech')
    ap.add_argument('--work', default='build/default_settings')
    ap.add_argument('--markdown', action='store_true')
    ap.add_argument('--check', type=float, default=None)
    ap.add_argument('--cases', action='store_true')
    ap.add_argument('filters', nargs='*')
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.cases:
        run_cases(args, args.markdown)
        return 0
    lines, failures = [], 0
    for deck_name in sorted(os.listdir('inputs')):
        name, ext = os.path.splitext(deck_name)
        if ext != '.nml' or not os.path.exists(f'reference_outputs/{name}.out'):
            continue
        if args.filters and not any(f in name for f in args.filters):
            continue
        text = open(f'inputs/{deck_name}').read()
        analysis = analysis_of(text)
        if analysis not in ('transient', 'spatial', 'steady'):
            continue
        stripped, removed = strip_solver_lines(text)
        if not removed:
            lines.append((name, analysis, '(no solver lines)', None, '', None, None, ''))
            continue
        default_deck = f'{args.work}/{name}.nml'
        with open(default_deck, 'w') as f:
            f.write(stripped)
        tuned_out = f'{args.work}/{name}.tuned.out'
        default_out = f'{args.work}/{name}.default.out'
        for stale in (tuned_out, default_out):
            if os.path.exists(stale):
                os.remove(stale)
        run(args.flexmech, f'inputs/{deck_name}', tuned_out)
        status, err = run(args.flexmech, default_deck, default_out)
        ref_names, ref_rows, _ = read_table(f'reference_outputs/{name}.out')
        if not os.path.exists(default_out):
            lines.append((name, analysis, 'run failed: ' + err.strip()[:80], float('inf'), '', None, None, ''))
            failures += 1
            continue
        new_names, new_rows, new_cost = read_table(default_out)
        _, _, tuned_cost = read_table(tuned_out)
        worst, where = worst_peak(peaks(ref_names, ref_rows), peaks(new_names, new_rows))
        cpu_t = float(tuned_cost.get('total_cpu_seconds', 'nan'))
        cpu_d = float(new_cost.get('total_cpu_seconds', 'nan'))
        note = '' if len(new_rows) == len(ref_rows) else f'{len(new_rows)} rows, reference {len(ref_rows)}'
        lines.append((name, analysis, chosen(default_out) or '(defaults)', worst, where, cpu_t, cpu_d, note))
        if args.check is not None and worst * 100.0 > args.check:
            failures += 1
        print(f'{name}: peak {100 * worst:.3g} % ({where}), CPU {cpu_t:.3g} -> {cpu_d:.3g} s', file=sys.stderr)
    print_table(lines, args.markdown)
    return 1 if failures else 0


def print_table(lines, markdown):
    head = ('deck', 'analysis', 'chosen', 'worst peak', 'column', 'CPU tuned (s)', 'CPU default (s)',
            'ratio', 'verdict')
    if markdown:
        print('| ' + ' | '.join(head) + ' |')
        print('|' + '---|' * len(head))
    else:
        print('  '.join(head))
    for name, analysis, picks, worst, where, cpu_t, cpu_d, note in lines:
        if worst is None:
            cells = (name, analysis, picks, '', '', '', '', '', 'nothing to remove')
        elif cpu_d is None:
            cells = (name, analysis, picks, '', '', '', '', '', 'FAILS: the default run stopped')
        else:
            ratio = cpu_d / cpu_t if cpu_t and cpu_t > 0 else float('nan')
            ok = worst <= 0.01 and ratio <= 2.0
            verdict = 'meets 1 % / 2x' if ok else 'FAILS ' + ('peaks' if worst > 0.01 else '') + \
                (' and ' if worst > 0.01 and ratio > 2.0 else '') + ('CPU' if ratio > 2.0 else '')
            if note:
                verdict += ' (' + note + ')'
            cells = (name, analysis, picks, f'{100 * worst:.3g} %', where, f'{cpu_t:.3g}', f'{cpu_d:.3g}',
                     f'{ratio:.2f}', verdict)
        print(('| ' + ' | '.join(cells) + ' |') if markdown else '  '.join(cells))


if __name__ == '__main__':
    sys.exit(main())
