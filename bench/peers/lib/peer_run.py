"""What the peer comparisons of bench/peers/ share: the measured child process and the command line.

Each script runs flexmech and the peer as child processes, so that both codes are measured as whole
processes (user + system CPU of the child, os.wait4); the peer's cases are the script itself started
with --exudyn-case, writing their results to the JSON file named by --result.
"""
import argparse
import json
import os
import sys


def run_timed(cmd):
    """Run cmd with its standard output discarded; its CPU seconds, or None when it failed."""
    pid = os.fork()
    if pid == 0:                                               # child: the measured process
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, 1)
        os.execv(cmd[0], cmd)
    _, status, ru = os.wait4(pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        return None
    return ru.ru_utime + ru.ru_stime


def arguments(extra):
    """The common options (--flexmech, --work, --exudyn-case N STEPS, --result) and extra(parser)'s."""
    ap = argparse.ArgumentParser()
    ap.add_argument('--flexmech', default='build/bin/flexmech')
    ap.add_argument('--work', default='build/peers')
    ap.add_argument('--exudyn-case', nargs=2, type=int)
    ap.add_argument('--result')
    extra(ap)
    return ap.parse_args()


def child_case(a, case):
    """In a child started with --exudyn-case: run case(n, steps), write its result; True if so."""
    if not a.exudyn_case:
        return False
    with open(a.result, 'w') as f:
        json.dump(case(*a.exudyn_case), f)
    return True


def run_child(script, result, n, steps, extra):
    """Run the peer's case (n, steps) as a child of script with the options extra; (CPU s, its result)."""
    cpu = run_timed([sys.executable, os.path.abspath(script), '--exudyn-case', str(n), str(steps)] + extra
                    + ['--result', result])
    if cpu is None:
        return None, None
    with open(result) as f:
        return cpu, json.load(f)


def start(extra, case, name):
    """Parse the options; in a child run case(args, n, steps) and return (None, None), else (args, the
    work directory WORK/name, made)."""
    a = arguments(extra)
    if child_case(a, lambda n, steps: case(a, n, steps)):
        return None, None
    work = os.path.join(a.work, name)
    os.makedirs(work, exist_ok=True)
    return a, work
