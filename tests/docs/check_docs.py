#!/usr/bin/env python3
"""make check-docs: the documentation does what it says.

1. Every deck a page of doc/ or README.md names (inputs/X.nml, examples/.../X.nml,
   tests/decks/X.nml) exists, and a sample of them runs to the exit status its
   header expects (! expect-status: N, default 0).
2. Every command block of doc/tutorial.md runs, in order, in one shell, in a
   scratch directory that stands for the student's home (HOME); a command whose
   comment says `# exit N` must exit with N, every other must succeed.
3. The output the tutorial quotes (indented blocks of `# ...` lines) is found in
   the outputs the commands wrote: every quoted line, whitespace aside, in some
   output line (`...` stands for any text).
4. Every number listed in tests/docs/tutorial_numbers.txt: the text quotes it
   (doc/tutorial.md holds the fragment) and the run prints it (the pattern finds
   it in the output file), within the stated tolerance.  Numbers are found by
   the quantity's own words in the output, never by line position.

usage: check_docs.py BUILD_DIR [SCRATCH_DIR]
"""
import glob
import os
import re
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TUTORIAL = os.path.join(REPO, 'doc', 'tutorial.md')
NUMBERS = os.path.join(REPO, 'tests', 'docs', 'tutorial_numbers.txt')
NUM = r'([-+]?[0-9][0-9.,]*(?:[eE][-+]?[0-9]+)?)'
COMMAND = re.compile(r'^(make\b|\.{1,2}/flexmech\b|sed\b|mkdir\b|cd\b|less\b|grep\b|for\b|repo=)')
SAMPLE = 8            # decks of the other pages run (the cheapest by their reference cost)
failures = []


def fail(text):
    failures.append(text)
    print('   FAILED: ' + text)


def blocks(path):
    """Indented (4-space) blocks after a blank line: (first line number, lines)."""
    lines = open(path, encoding='utf-8').read().split('\n')
    out, cur, start, prev_blank = [], None, 0, True
    for i, line in enumerate(lines, 1):
        if line.startswith('    ') and (cur is not None or prev_blank):
            if cur is None:
                cur, start = [], i
            cur.append(line[4:])
        else:
            if cur is not None:
                out.append((start, cur))
                cur = None
        prev_blank = line.strip() == ''
    if cur is not None:
        out.append((start, cur))
    return out


def norm(text):
    return ' '.join(text.replace('\u2212', '-').split())


def number(text):
    return float(text.replace(',', '').replace('\u2212', '-'))


# ------------------------------------------------------------------ 1. decks named by the pages
def check_decks(build):
    print('== decks named by doc/*.md and README.md')
    pages = sorted(glob.glob(os.path.join(REPO, 'doc', '*.md'))) + [os.path.join(REPO, 'README.md')]
    named = {}
    for page in pages:
        text = open(page, encoding='utf-8').read()
        for m in re.finditer(r'((?:inputs|examples|tests/decks)/[A-Za-z0-9_./-]*?[A-Za-z0-9_-]+\.nml)\b', text):
            named.setdefault(m.group(1), os.path.relpath(page, REPO))
    # placeholders in the text (inputs/X.nml, inputs/other.nml) name no deck
    named = {d: p for d, p in named.items()
             if os.path.basename(d)[:-4] not in ('X', 'other', 'NAME', 'deck', 'my_deck')}
    missing = [d for d in sorted(named) if not os.path.isfile(os.path.join(REPO, d))]
    for d in missing:
        fail('%s names %s, which does not exist' % (named[d], d))
    print('   %d decks named, %d missing' % (len(named), len(missing)))
    # a sample runs: the cheapest named decks by the cost line of their reference output
    cost = {}
    for d in named:
        ref = os.path.join(REPO, 'reference_outputs', os.path.basename(d)[:-4] + '.out')
        if d.startswith('inputs/') and os.path.isfile(ref) and d not in missing:
            m = re.search(r'^# cost: total_cpu_seconds = ' + NUM, open(ref, errors='replace').read(), re.M)
            if m:
                cost[d] = number(m.group(1))
    flexmech = os.path.join(REPO, build, 'bin', 'flexmech')
    # the cheapest of each analysis first, then the next cheapest, up to SAMPLE decks
    kind = {}
    for d in cost:
        m = re.search(r"analysis *= *'([a-z_]+)'", open(os.path.join(REPO, d), errors='replace').read())
        kind[d] = m.group(1) if m else ''
    by_cost = sorted(cost, key=lambda d: (cost[d], d))
    rank = {}
    for d in by_cost:
        rank[d] = sum(1 for e in by_cost[:by_cost.index(d)] if kind[e] == kind[d])
    sample = sorted(by_cost, key=lambda d: (rank[d], cost[d], d))[:SAMPLE]
    work = os.path.join(REPO, build, 'check_docs', 'decks')
    os.makedirs(work, exist_ok=True)
    for d in sample:
        text = open(os.path.join(REPO, d), errors='replace').read()
        m = re.search(r'^! *expect-status: *([0-9]+)', text, re.M)
        want = int(m.group(1)) if m else 0
        out = os.path.join(work, os.path.basename(d)[:-4] + '.out')
        run = subprocess.run([flexmech, d, '-o', out], cwd=REPO, capture_output=True, text=True, timeout=600)
        if run.returncode != want:
            fail('%s (named by %s): exit %d, expected %d: %s' % (d, named[d], run.returncode, want, run.stderr[:300]))
        else:
            print('   %s runs (exit %d)' % (d, want))


# ------------------------------------------------------------------ 2. the tutorial's commands
def run_tutorial(home):
    print('== the commands of doc/tutorial.md, in %s' % home)
    script = ['set -e', 'less() { test -s "$1"; }', 'cd "%s"' % REPO]
    logs = os.path.join(home, '.check_docs')
    os.makedirs(logs, exist_ok=True)
    commands, quoted = 0, []
    for start, lines in blocks(TUTORIAL):
        first = lines[0].strip()
        if first.startswith('#'):
            quoted.append((start, lines))
            continue
        if not COMMAND.match(first):
            continue
        commands += 1
        body = []
        for line in lines:
            m = re.match(r'^(.*?)\s+#\s*exit ([0-9]+)\b', line)
            if m:
                body.append('s=0; %s || s=$?; [ "$s" -eq %s ] || { echo "exit status $s, expected %s" >&2; exit 1; }'
                            % (m.group(1), m.group(2), m.group(2)))
            else:
                body.append(line)
        script.append('echo "block at doc/tutorial.md:%d" > "%s/current"' % (start, logs))
        script.append('{\n%s\n} > "%s/block_%d.log" 2>&1' % ('\n'.join(body), logs, start))
    script.append('echo done > "%s/current"' % logs)
    env = dict(os.environ, HOME=home)
    env.pop('MAKEFLAGS', None)
    env.pop('MFLAGS', None)
    run = subprocess.run(['bash', '-c', '\n'.join(script)], env=env, capture_output=True, text=True)
    where = open(os.path.join(logs, 'current')).read().strip()
    if run.returncode != 0 or where != 'done':
        line = where.split(':')[-1]
        log = os.path.join(logs, 'block_%s.log' % line)
        tail = open(log, errors='replace').read().splitlines()[-15:] if os.path.isfile(log) else []
        fail('%s failed (exit %d); its output ends:\n      %s' % (where, run.returncode, '\n      '.join(tail)))
        return quoted, False
    print('   %d command blocks ran' % commands)
    return quoted, True


def outputs(course):
    text = {}
    for root, _, files in os.walk(course):
        for f in files:
            if f.endswith('.out'):
                path = os.path.join(root, f)
                text[os.path.relpath(path, course)] = open(path, errors='replace').read()
    return text


# ------------------------------------------------------------------ 3. quoted output
def check_quoted(quoted, outs):
    print('== output quoted by doc/tutorial.md')
    lines = [norm(l) for t in outs.values() for l in t.splitlines() if l.startswith('#')]
    n = 0
    for start, block in quoted:
        for k, q in enumerate(block):
            if not q.strip():
                continue
            n += 1
            parts = [re.escape(norm(p)) for p in q.split('...')]
            pat = re.compile('.*?'.join(parts))
            if not any(pat.search(l) for l in lines):
                fail('doc/tutorial.md:%d quotes a line no output prints: %s' % (start + k, q.strip()))
    print('   %d quoted lines' % n)


# ------------------------------------------------------------------ 4. quoted numbers
def entries(path):
    cur = {}
    for raw in open(path, encoding='utf-8').read().split('\n') + ['']:
        if raw.startswith('#'):
            continue
        if not raw.strip():
            if cur:
                yield cur
            cur = {}
            continue
        key, _, value = raw.partition(':')
        cur[key.strip()] = value.strip()


def check_numbers(course, outs):
    print('== numbers quoted by doc/tutorial.md (tests/docs/tutorial_numbers.txt)')
    doc = norm(open(TUTORIAL, encoding='utf-8').read())
    n = 0
    for e in entries(NUMBERS):
        n += 1
        text = e['text']
        m = re.search(r'\{([^}]*)\}', text)
        quoted = number(m.group(1))
        if norm(text.replace('{', '').replace('}', '')) not in doc:
            fail('doc/tutorial.md no longer says "%s"' % text.replace('{', '').replace('}', ''))
            continue
        out = outs.get(e['file'])
        if out is None:
            fail('"%s": the tutorial wrote no %s' % (text, e['file']))
            continue
        found = None
        for pattern in e['find'].split(' || '):
            f = re.search(pattern.replace('NUM', NUM), out, re.M)
            if f:
                found = number(f.group(1))
                break
        if found is None:
            fail('"%s": no line of %s matches %s' % (text, e['file'], e['find']))
            continue
        tol = e['tol']
        limit = float(tol[:-1]) / 100 * abs(found) if tol.endswith('%') else float(tol.split()[-1])
        if abs(found - quoted) > limit:
            fail('doc/tutorial.md quotes %s in "%s"; the run prints %s (tolerance %s)'
                 % (m.group(1), text, repr(found), tol))
    print('   %d numbers' % n)


def untracked():
    """Files in the repository that git does not track, outside the build directory."""
    run = subprocess.run(['git', 'ls-files', '--others', '--', '.', ':!build'], cwd=REPO,
                         capture_output=True, text=True)
    return set(run.stdout.split())


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else 'build'
    scratch = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(REPO, build, 'check_docs'))
    home = os.path.join(scratch, 'home')
    shutil.rmtree(home, ignore_errors=True)
    os.makedirs(home)
    check_decks(build)
    before = untracked()
    quoted, ok = run_tutorial(home)
    for f in sorted(untracked() - before):
        fail('the tutorial wrote %s into the repository' % f)
    if ok:
        course = os.path.join(home, 'flexmech-course')
        outs = outputs(course)
        check_quoted(quoted, outs)
        check_numbers(course, outs)
    if failures:
        print('check-docs: %d failed' % len(failures))
        return 1
    print('check-docs: the tutorial runs and its numbers hold')
    return 0


if __name__ == '__main__':
    sys.exit(main())
