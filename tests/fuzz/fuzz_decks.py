#!/usr/bin/env python3
"""Mutation fuzzer for flexmech decks (Python 3 standard library only).

Every case takes one deck of inputs/ or tests/decks/, applies one to three
mutations (numbers to 0, +-tiny, +-huge, subnormal, NaN, +-Inf, wrong types,
deleted / duplicated lines, truncation, unknown groups and variables, long
lines, tabs, binary garbage, line endings, ...), runs it with each binary under a time limit
and classifies the run.  The time limits count the case's CPU seconds, not wall time, so a
loaded host (several builds at once) does not turn slow cases into hangs.  A case is a pure function of (seed, index), so

    python3 tests/fuzz/fuzz_decks.py --seed S --only I

replays case I of a run with seed S (the failing cases are also saved, with
their deck and a README, under WORKDIR/failures/).

Classes (FAIL = the fuzzer exits 1):
  exit0, exit2, exit3    normal outcomes
  timeout                the time limit was hit, and the case then finished
                         within --hang-factor times the limit, or was still
                         writing rows then (slow, not a failure)
  hang           FAIL    no result within --hang-factor times the limit and
                         no growth of its output meanwhile (an endless loop,
                         or a long computation that writes nothing: replay)
  crash          FAIL    killed by a signal, a runtime error, a backtrace, or
                         an exit status other than 0, 2, 3
  nonfinite      FAIL    NaN/Inf (or an unreadable number) in a data row of a
                         run that exited 0 or 3
  bad_number     FAIL    a number without its exponent letter (0.1+301)
                         anywhere in the output, header included
  leftover       FAIL    an exit-2 run left its output or a .tmp* file; any
                         run left a .tmp* file
  warning        FAIL    a Fortran runtime warning (e.g. a string truncated
                         on read)
  no_context     FAIL    an exit-2 message that does not name the deck and
                         the group
  exit2_without_line     an exit-2 message naming no line (counted only:
                         a missing group has none)
"""
import argparse
import functools
import multiprocessing
import threading
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

NUMBER = re.compile(rb'(?<![A-Za-z_0-9.])[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eEdD][-+]?\d+)?(?![A-Za-z_0-9.])')
STRING = re.compile(rb"'[^'\n]*'|\"[^\"\n]*\"")
LOGICAL = re.compile(rb'(?<![A-Za-z_0-9])(?:\.?[TtFf]\.?|\.true\.|\.false\.)(?=\s*[,/\n]|\s*$)')
ASSIGN = re.compile(rb'^(\s*)([A-Za-z_][A-Za-z_0-9]*)(\s*(?:\([^)]*\))?\s*=)', re.M)

SPECIAL_NUMBERS = [b'0', b'0.0', b'-0.0', b'1e-300', b'-1e-300', b'1e-310', b'4.9e-324',
                   b'1e300', b'-1e300', b'1.7976931348623157e308', b'1e309', b'-1e309',
                   b'NaN', b'Inf', b'-Inf', b'Infinity', b'2147483647', b'2147483648',
                   b'-2147483648', b'-1', b'1', b'999999999', b'1e15', b'1e-15', b'3.0e-5']
WRONG_TYPES = [b"'abc'", b'T', b'F', b'.true.', b'1.5', b'(1.0,2.0)', b"''", b'"x"', b'*', b'1.2.3',
               b'1e', b'--1', b'0x10', b'1,,2', b'3*', b'100000*1.0']


def mutate_number(rng, text):
    spans = [m.span() for m in NUMBER.finditer(text)]
    if not spans:
        return None
    a, b = rng.choice(spans)
    new = rng.choice(SPECIAL_NUMBERS)
    if rng.random() < 0.2:  # a relative perturbation that keeps the value sensible
        try:
            v = float(text[a:b].replace(b'd', b'e').replace(b'D', b'e'))
            new = repr(v * rng.choice([1 + 1e-14, 1 - 1e-14, 10.0, 0.1, -1.0, 1e6, 1e-6])).encode()
        except ValueError:
            pass
    return text[:a] + new + text[b:], 'number %r -> %r' % (text[a:b].decode(), new.decode())


def mutate_type(rng, text):
    targets = [m.span() for m in NUMBER.finditer(text)] + [m.span() for m in STRING.finditer(text)]
    if not targets:
        return None
    a, b = rng.choice(targets)
    new = rng.choice(WRONG_TYPES + [b'1.0', b'7'])
    return text[:a] + new + text[b:], 'value %r -> %r' % (text[a:b].decode('latin-1'), new.decode())


def mutate_string(rng, text):
    spans = [m.span() for m in STRING.finditer(text)]
    if not spans:
        return None
    a, b = rng.choice(spans)
    choice = rng.randrange(5)
    if choice == 0:
        new = b"'" + b'x' * rng.choice([33, 65, 257, 1000, 5000]) + b"'"
    elif choice == 1:
        new = b"'" + rng.choice([b'nosuch', b'BDF', b'bdf ', b' adams', b'', b'a/b', b'a!b', b'a&b']) + b"'"
    elif choice == 2:
        new = text[a:b - 1]          # unterminated string
    elif choice == 3:
        new = b'unquoted'
    else:
        new = text[a:b] + b', ' + text[a:b]   # one value too many
    return text[:a] + new + text[b:], 'string %r -> %r' % (text[a:b].decode('latin-1')[:40],
                                                              new.decode('latin-1')[:40])


def lines_of(text):
    return text.split(b'\n')


def mutate_lines(rng, text):
    ls = lines_of(text)
    if len(ls) < 2:
        return None
    i = rng.randrange(len(ls))
    choice = rng.randrange(4)
    if choice == 0:
        what = 'delete line %d %r' % (i + 1, ls[i][:60].decode('latin-1'))
        del ls[i]
    elif choice == 1:
        what = 'duplicate line %d' % (i + 1)
        ls.insert(i, ls[i])
    elif choice == 2:
        j = rng.randrange(len(ls))
        ls[i], ls[j] = ls[j], ls[i]
        what = 'swap lines %d and %d' % (i + 1, j + 1)
    else:
        k = rng.randrange(len(ls))
        ls.insert(k, ls.pop(i))
        what = 'move line %d to %d' % (i + 1, k + 1)
    return b'\n'.join(ls), what


def mutate_truncate(rng, text):
    if not text:
        return None
    n = rng.randrange(len(text))
    return text[:n], 'truncate at byte %d of %d' % (n, len(text))


def group_spans(text):
    """(start, end) byte offsets of '&name' ... up to the next line start after '/'."""
    return [m.span() for m in re.finditer(rb'&[A-Za-z_]+', text)]


def mutate_unknown(rng, text):
    choice = rng.randrange(4)
    ls = lines_of(text)
    if choice == 0:
        k = rng.randrange(len(ls) + 1)
        ls.insert(k, rng.choice([b'&bogus x = 1 /', b'&BOGUS /', b'&transient_x rtol = 1 /', b'&', b'&&run /']))
        return b'\n'.join(ls), 'unknown group at line %d' % (k + 1)
    groups = [i for i, l in enumerate(ls) if l.lstrip().startswith(b'&')]
    if not groups:
        return None
    g = rng.choice(groups)
    if choice == 1:
        ls.insert(g + 1, rng.choice([b'  nosuchvar = 1', b'  rtoll = 1e-4', b'  x(3) = 1', b'  = 5',
                                      b'  joint_x(0) = 1.0', b'  joint_x(1000) = 1.0', b'  x0(-1) = 1',
                                      b'  atol(99999) = 1', b'  n_joints = 4, n_joints = 5']))
        return b'\n'.join(ls), 'unknown/odd variable after line %d' % (g + 1)
    if choice == 2:   # rename an assignment's variable
        ms = list(ASSIGN.finditer(text))
        if not ms:
            return None
        m = rng.choice(ms)
        name = m.group(2) + rng.choice([b'x', b'_', b'1'])
        return text[:m.start(2)] + name + text[m.end(2):], 'rename variable %r' % m.group(2).decode()
    # remove the group terminator or the ampersand
    l = ls[g]
    if rng.random() < 0.5:
        ls[g] = l.replace(b'&', b'', 1)
        return b'\n'.join(ls), 'drop & on line %d' % (g + 1)
    for k in range(g, len(ls)):
        if b'/' in ls[k] and not ls[k].lstrip().startswith(b'!'):
            ls[k] = ls[k].replace(b'/', b'', 1)
            return b'\n'.join(ls), 'drop / on line %d' % (k + 1)
    return None


def mutate_long(rng, text):
    ls = lines_of(text)
    i = rng.randrange(len(ls))
    choice = rng.randrange(3)
    n = rng.choice([1023, 1024, 1025, 2000, 5000, 70000])
    if choice == 0:
        ls[i] = b' ' * n + ls[i]
        what = 'indent line %d by %d blanks' % (i + 1, n)
    elif choice == 1:
        ls[i] = ls[i] + b' ' * n + b'! trailing comment'
        what = 'append %d blanks and a comment to line %d' % (n, i + 1)
    else:
        ls.insert(i, b'! ' + b'c' * n)
        what = 'insert a %d-character comment at line %d' % (n, i + 1)
    return b'\n'.join(ls), what


def mutate_tabs(rng, text):
    positions = [m.start() for m in re.finditer(rb'[ ,]', text)]
    if rng.random() < 0.4:
        out = re.sub(rb'^(\s*&[A-Za-z_]+) ?', lambda m: m.group(1) + b'\t', text, flags=re.M)
        return out, 'tab after every &group'
    if not positions:
        return None
    p = rng.choice(positions)
    return text[:p] + b'\t' + text[p + 1:], 'tab at byte %d' % p


def mutate_garbage(rng, text):
    p = rng.randrange(len(text) + 1)
    n = rng.choice([1, 2, 8, 64])
    junk = bytes(rng.randrange(256) for _ in range(n))
    if rng.random() < 0.3:
        junk = rng.choice([b'\x00', b'\xff\xfe', b'\r', b'\r\n', b'\x1a', b'\xc3\xa9', b'\\', b'"', b"'"])
    return text[:p] + junk + text[p:], 'insert %r at byte %d' % (junk, p)


def mutate_repeat(rng, text):
    ms = list(re.finditer(rb'(\d+)\*', text))
    if not ms:
        return None
    m = rng.choice(ms)
    new = rng.choice([b'0', b'1', b'100', b'1000000'])
    return text[:m.start(1)] + new + text[m.end(1):], 'repeat count %s -> %s' % (m.group(1).decode(), new.decode())


def mutate_endings(rng, text):
    choice = rng.randrange(3)
    if choice == 0:
        return text.replace(b'\n', b'\r\n'), 'CRLF line endings'
    if choice == 1:
        return text.rstrip(b'\n'), 'no newline after the last line'
    return text.replace(b'\n', b'\r'), 'CR line endings'


MUTATORS = [(mutate_number, 6), (mutate_type, 3), (mutate_string, 2), (mutate_lines, 2),
            (mutate_truncate, 1), (mutate_unknown, 2), (mutate_long, 1), (mutate_tabs, 1),
            (mutate_garbage, 1), (mutate_repeat, 1), (mutate_endings, 1)]


def make_case(rng, decks):
    deck = rng.choice(decks)
    with open(deck, 'rb') as f:
        text = f.read()
    # Keep a case short: at most 0.2 revolutions of a transient run.
    text = re.sub(rb'(?i)(revolutions\s*=\s*)[0-9.eEdD+-]+', rb'\g<1>0.2', text)
    steps = []
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        funcs, weights = zip(*MUTATORS)
        for _attempt in range(5):
            f = rng.choices(funcs, weights)[0]
            r = f(rng, text)
            if r is not None:
                text, what = r
                steps.append(what)
                break
    return deck, text, steps


CRASH_MARKS = ['Program received signal', 'Backtrace', 'Fortran runtime error', 'runtime error',
               'Segmentation fault', 'Floating-point exception', 'ERROR STOP', 'Error termination',
               'malloc', 'double free', 'core dumped', 'Operating system error']
BAD_NUMBER = re.compile(r'(?<![\w.+-])[-+]?\d*\.\d+[-+]\d{2,}(?![\w.])')


def data_problem(path):
    """First non-finite or unreadable number in a data row, or None."""
    with open(path, 'rb') as f:
        for n, raw in enumerate(f, 1):
            line = raw.decode('latin-1')
            if line.startswith('#') or not line.strip():
                continue
            for tok in line.split():
                try:
                    v = float(tok)
                except ValueError:
                    return 'line %d: unreadable %r' % (n, tok)
                if v != v or v in (float('inf'), float('-inf')):
                    return 'line %d: %s' % (n, tok)
    return None


def bad_number(path):
    with open(path, 'rb') as f:
        for n, raw in enumerate(f, 1):
            m = BAD_NUMBER.search(raw.decode('latin-1'))
            if m:
                return 'line %d: %r' % (n, m.group(0))
    return None


def output_size(out_path):
    return sum(os.path.getsize(p) for p in tmp_files(out_path) if os.path.exists(p))


def cpu_seconds(pid):
    """CPU time (user + system) of a running process, from /proc; None when gone."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            fields = f.read().rsplit(')', 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')
    except (OSError, IndexError, ValueError):
        return None


def run_case(binary, deck_path, out_path, timeout, hang_factor):
    """(status or None, stdout, stderr, seconds, progressing).  The limits are
    CPU seconds of the case, not wall time, so that a loaded host does not turn
    slow cases into hangs: a run past `timeout` CPU seconds gets hang_factor
    times as long in all; if it is still going then, it is killed, and
    `progressing` says whether its temporary output grew meanwhile (rows being
    written: slow, not hung).  A run that uses no CPU for 20 times the whole
    budget of wall time (blocked) is killed as well.  `seconds` is CPU time."""
    for p in [out_path] + tmp_files(out_path):
        if os.path.lexists(p):
            os.remove(p)
    start = time.time()
    try:
        proc = subprocess.Popen([binary, deck_path, '-o', out_path], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, start_new_session=True,
                                cwd=os.path.dirname(out_path))
    except OSError as e:     # the binary vanished (rebuilt meanwhile?): not a finding
        sys.exit('fuzz: cannot run %s: %s' % (binary, e))
    # the pipes are drained by a thread so that a talkative case cannot block
    result = {}
    reader = threading.Thread(target=lambda: result.update(zip(('out', 'err'), proc.communicate())))
    reader.start()
    size0 = None
    cpu = 0.0
    while True:
        reader.join(0.05)
        if not reader.is_alive():
            return proc.returncode, result['out'], result['err'], max(cpu, 0.0), True
        c = cpu_seconds(proc.pid)
        cpu = c if c is not None else cpu
        if size0 is None and cpu > timeout:
            size0 = output_size(out_path)
        if cpu > timeout * hang_factor or time.time() - start > 20 * timeout * hang_factor:
            progressing = size0 is not None and output_size(out_path) > size0
            os.killpg(proc.pid, signal.SIGKILL)
            reader.join()
            return None, result.get('out', b''), result.get('err', b''), cpu, progressing


def tmp_files(out_path):
    d, base = os.path.split(out_path)
    return [os.path.join(d, f) for f in os.listdir(d or '.') if f.startswith(base + '.tmp')]


def classify(status, stderr, out_path, deck_path):
    """List of (class, detail); the first is the outcome, the rest are failures."""
    err = stderr.decode('latin-1')
    found = []
    if status is None:
        return [('timeout', '')]
    crash = None
    if status < 0:
        crash = 'signal %d' % -status
    elif status not in (0, 2, 3):
        crash = 'exit status %d' % status
    for mark in CRASH_MARKS:
        if mark in err:
            crash = (crash + '; ' if crash else '') + 'stderr has %r' % mark
            break
    found.append(('crash', crash) if crash else ('exit%d' % status, ''))
    if 'runtime warning' in err:
        w = err[err.index('runtime warning'):].splitlines()[0]
        found.append(('warning', w))
    tmps = tmp_files(out_path)
    if tmps:
        found.append(('leftover', 'temporary file ' + os.path.basename(tmps[0])))
    if status == 2:
        if os.path.exists(out_path):
            found.append(('leftover', 'output file after exit 2'))
        # lines end at '\n' only: str.splitlines would also break at the bytes 0x1c-0x1e and 0x85
        # that a mutated deck's non-ASCII text can hold (stderr is read as latin-1)
        msgs = [l for l in err.split('\n') if l.startswith('flexmech:')] or ['']
        first = msgs[0]
        if "deck '" not in first or 'group &' not in first:
            found.append(('no_context', first[:200]))
        elif 'line' not in first:
            found.append(('exit2_without_line', first[:200]))   # counted, not a failure
    if status in (0, 3) and os.path.exists(out_path):
        p = data_problem(out_path)
        if p:
            found.append(('nonfinite', 'exit %d, %s' % (status, p)))
        b = bad_number(out_path)
        if b:
            found.append(('bad_number', b))
    elif status in (0, 3):
        found.append(('leftover', 'exit %d without an output file' % status))
    return found


FAILING = {'crash', 'warning', 'hang', 'nonfinite', 'bad_number', 'leftover', 'no_context'}


def fuzz_case(i, a, decks, binaries):
    """Run case i with every binary: (per-binary results, failures, slow lines).
    Each worker process works in its own folder (case.nml, case.out)."""
    rng = random.Random('%d/%d' % (a.seed, i))
    deck, text, steps = make_case(rng, decks)
    work = os.path.join(a.work, 'w%d' % os.getpid())
    os.makedirs(work, exist_ok=True)
    case = os.path.join(work, 'case.nml')
    with open(case, 'wb') as f:
        f.write(text)
    results, failures, slow = [], [], []
    ended_elsewhere = None    # a binary that finished the case, or was writing rows at its limit
    for name, binary in binaries:
        out = os.path.join(work, 'case.out')
        status, _, stderr, dt, progressing = run_case(binary, case, out, a.timeout, a.hang_factor)
        result = classify(status, stderr, out, case)
        if status is not None and dt > a.timeout:
            result = [('timeout', 'finished in %.1f CPU s' % dt)] + result[1:]
        elif status is None and progressing:
            result = [('timeout', 'still writing rows after %.1f CPU s' % dt)]
        elif status is None and ended_elsewhere:
            # the same deck ends (or shows progress) in the other build: this
            # build is slower (the debug build is -O0 with checks, 5-20 times
            # slower), not in an endless loop (seed 12, case 942)
            result = [('timeout', 'no output growth in %.1f CPU s, but the %s binary %s: slow, not hung'
                       % (dt, ended_elsewhere[0], ended_elsewhere[1]))]
        elif status is None:
            result = [('hang', 'no result and no output growth in %.1f CPU s' % dt)]
        if ended_elsewhere is None and (status is not None or progressing):
            ended_elsewhere = (name, 'finished it' if status is not None else 'was writing rows')
        results.append((name, result))
        bad = [(c, d) for c, d in result if c in FAILING]
        if result[0][0] == 'timeout':
            slow.append('case %d (%s, from %s): %s [%s]' % (i, name, deck, result[0][1], '; '.join(steps)))
        if a.verbose or a.only is not None:
            print('case %d %s %s: %s  [%.1fs] %s' % (i, name, deck, result, dt, '; '.join(steps)))
            if a.only is not None:
                sys.stdout.write(stderr.decode('latin-1')[:2000])
        if bad:
            with open(os.path.join(a.work, 'failures', 'case_%d.nml' % i), 'wb') as f:
                f.write(text)
            failures.append((i, name, deck, steps, bad, stderr.decode('latin-1').strip()))
            print('FAIL case %d (%s, from %s): %s  [%s]' % (i, name, deck,
                  '; '.join('%s: %s' % cd for cd in bad), '; '.join(steps)), flush=True)
    if a.keep:
        shutil.copy(case, os.path.join(a.work, 'case_%d.nml' % i))
    return results, failures, slow


def collect(outcome, counts, failures, slow):
    results, fails, slows = outcome
    for name, result in results:
        for cls, _ in result:
            counts[(name, cls)] = counts.get((name, cls), 0) + 1
    failures.extend(fails)
    slow.extend(slows)


def report_progress(done, total, failures, t0):
    """A line every 1,000 cases, so a long run shows how far it is."""
    if done % 1000 == 0 and done < total:
        print('fuzz: %d of %d cases, %d failing runs so far, %.0f s' % (done, total, len(failures),
              time.time() - t0), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--runs', type=int, default=200)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--first', type=int, default=0, help='index of the first case')
    ap.add_argument('--only', type=int, help='replay this one case')
    ap.add_argument('--timeout', type=float, default=5.0, help='seconds per run')
    ap.add_argument('--hang-factor', type=float, default=6.0,
                    help='a timed-out case is run again with this many times the limit')
    ap.add_argument('--release', default=os.path.join(ROOT, 'build/bin/flexmech'))
    ap.add_argument('--debug', default=os.path.join(ROOT, 'build/debug/bin/flexmech'))
    ap.add_argument('--work', default=os.path.join(ROOT, 'build/fuzz'))
    ap.add_argument('--keep', action='store_true', help='keep every case deck')
    ap.add_argument('--exclude', default='', help='skip decks whose path matches this regular expression')
    ap.add_argument('-j', '--jobs', type=int, default=1, help='cases run at once (worker processes)')
    ap.add_argument('-v', '--verbose', action='store_true')
    a = ap.parse_args()

    decks = sorted(os.path.join(d, f) for d in ('inputs', 'tests/decks')
                   for f in os.listdir(os.path.join(ROOT, d)) if f.endswith('.nml'))
    # a deck whose own run takes longer than the time limit and writes its
    # table only at the end (a design, a long sweep) says '! fuzz: long':
    # every mutation of it would be classed a hang
    decks = [d for d in decks if '! fuzz: long' not in open(os.path.join(ROOT, d), errors='replace').read()]
    if a.exclude:
        decks = [d for d in decks if not re.search(a.exclude, d)]
    os.chdir(ROOT)
    binaries = [(n, os.path.abspath(b)) for n, b in (('release', a.release), ('debug', a.debug)) if b]
    a.work = os.path.abspath(a.work)
    for n, b in binaries:
        if not os.access(b, os.X_OK):
            sys.exit('fuzz: no %s binary %s (build it first)' % (n, b))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(os.path.join(a.work, 'failures'))
    indices = [a.only] if a.only is not None else range(a.first, a.first + a.runs)
    counts = {}
    failures = []
    slow = []
    t0 = time.time()
    job = functools.partial(fuzz_case, a=a, decks=decks, binaries=binaries)
    if a.jobs > 1 and a.only is None:
        with multiprocessing.Pool(a.jobs) as pool:
            for done, outcome in enumerate(pool.imap(job, indices, chunksize=4), 1):
                collect(outcome, counts, failures, slow)
                report_progress(done, len(indices), failures, t0)
    else:
        for done, i in enumerate(indices, 1):
            collect(job(i), counts, failures, slow)
            report_progress(done, len(indices), failures, t0)
    with open(os.path.join(a.work, 'failures', 'README'), 'w') as f:
        for i, name, deck, steps, bad, err in failures:
            f.write('case %d (%s binary, from %s): %s\n  mutations: %s\n  replay: python3 '
                    'tests/fuzz/fuzz_decks.py --seed %d --only %d\n  stderr: %s\n\n'
                    % (i, name, deck, bad, '; '.join(steps), a.seed, i, err[:600]))
        if slow:
            f.write('slow cases (over the time limit, not failures):\n  ' + '\n  '.join(slow) + '\n')
    n = len(indices)
    print('fuzz: %d cases x %d binaries, seed %d, %.0f s' % (n, len(binaries), a.seed, time.time() - t0))
    for name, _ in binaries:
        row = ', '.join('%s %d' % (c, k) for (b, c), k in sorted(counts.items()) if b == name)
        print('  %-7s %s' % (name, row))
    nfail = len({(i, b) for i, b, *_ in failures})
    print('fuzz: %d failing runs%s' % (nfail, ' (decks and README in %s/failures)' % a.work if nfail else ''))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
