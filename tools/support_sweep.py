#!/usr/bin/env python3
"""The four-bar on flexible mounts: a sweep of the mounts' natural frequency through the crank's
harmonics (doc/general_mechanism.md, "Support structure").

From inputs/general_support_fourbar.nml, the mounts at A and D get the mass --mass (lb s^2/in) in
every direction, the stiffness k = m (r omega)^2 and the damping c = 2 zeta sqrt(k m), for each
ratio r of the mount's own frequency sqrt(k/m) to the crank's omega (100 rad/s).  Each point runs
the deck (--revolutions from the static state, at --rtol) and reads over its last revolution the largest
element stress, the largest mount displacement (|(UX, UY)| of A and D) and the largest force a
mount carries; the rigidly grounded four-bar (the deck without &general_support) gives the
reference stress.  Writes the table and draws the figure with gnuplot.

usage: python3 tools/support_sweep.py [--flexmech build/bin/flexmech] [--work build/support_sweep]
                                       [--out doc/figures/general_support_sweep] [--mass 0.2]
                                       [--zeta 0.2] [--revolutions 2] [--rtol 1e-6] [--jobs 2]
                                       [--ratios 0.5,1,1.5,...]
"""
import argparse
import concurrent.futures
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from default_settings import read_table  # noqa: E402

DECK = 'inputs/general_support_fourbar.nml'
OMEGA = 100.0


def point_deck(text, mass, k, c):
    text = re.sub(r'revolutions = .*', 'revolutions = %d' % ARGS.revolutions, text)
    text = re.sub(r'rtol = .*', 'rtol = %g' % ARGS.rtol, text)
    text = re.sub(r'mount_mass = .*', 'mount_mass = 6*%.8g' % mass, text)
    text = re.sub(r'mount_stiffness = .*', 'mount_stiffness = 6*%.8g' % k, text)
    return re.sub(r'mount_damping = .*', 'mount_damping = 6*%.8g' % c, text)


def last_turn_peaks(path):
    """Largest element stress, mount displacement and mount force over the last revolution."""
    names, rows, _ = read_table(path)
    col = {n: j for j, n in enumerate(names)}
    last = max(r[col['drive']] for r in rows)
    rows = [r for r in rows if r[col['drive']] >= last - 360.0 - 1e-9]
    sigma = max(abs(r[j]) for r in rows for n, j in col.items() if n.startswith('sigma_max_'))
    disp = force = 0.0
    for joint in ('A', 'D'):
        if joint + '_UX' in col:
            disp = max(disp, max(math.hypot(r[col[joint + '_UX']], r[col[joint + '_UY']]) for r in rows))
            force = max(force, max(math.hypot(r[col[joint + '_FX']], r[col[joint + '_FY']]) for r in rows))
    return sigma, disp, force


def run(flexmech, deck, out):
    subprocess.run([flexmech, deck, '-o', out], check=True, stdout=subprocess.DEVNULL)


ARGS = None


def point(text, r, work, flexmech):
    """One ratio r: its deck, run, and the table line."""
    a = ARGS
    w = r*OMEGA
    k = a.mass*w*w
    c = 2.0*a.zeta*math.sqrt(k*a.mass)
    deck = os.path.join(work, 'ratio_%06.3f.nml' % r)
    with open(deck, 'w') as f:
        f.write(point_deck(text, a.mass, k, c))
    run(flexmech, deck, deck[:-4] + '.out')
    sigma, disp, force = last_turn_peaks(deck[:-4] + '.out')
    return r, w, k, sigma, disp, force


def main():
    global ARGS
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--flexmech', default='build/bin/flexmech')
    ap.add_argument('--work', default='build/support_sweep')
    ap.add_argument('--out', default='doc/figures/general_support_sweep')
    ap.add_argument('--mass', type=float, default=0.2)
    ap.add_argument('--zeta', type=float, default=0.2)
    ap.add_argument('--revolutions', type=int, default=2)
    ap.add_argument('--rtol', type=float, default=1e-6)
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--ratios', default='0.5,0.75,1,1.25,1.5,2,2.5,3,3.5,4,5,6,8')
    a = ap.parse_args()
    ARGS = a
    os.makedirs(a.work, exist_ok=True)
    with open(DECK) as f:
        text = f.read()
    rigid = os.path.join(a.work, 'rigid.nml')
    with open(rigid, 'w') as f:
        f.write(re.sub(r'&general_support.*?\n/\n', '', point_deck(text, 0, 0, 0), flags=re.DOTALL))
    run(a.flexmech, rigid, rigid[:-4] + '.out')
    sigma_rigid = last_turn_peaks(rigid[:-4] + '.out')[0]
    lines = ['# four-bar of %s on mounts at A and D: mass %g lb s^2/in, damping %g of critical; '
             'crank %g rad/s; rtol %g; peaks over the last of %d revolutions'
             % (DECK, a.mass, a.zeta, OMEGA, a.rtol, a.revolutions),
             '# rigidly grounded: peak stress %.6g psi' % sigma_rigid,
             '# ratio omega_mount_rad_s k_lb_in peak_stress_psi stress_over_rigid peak_mount_disp_in '
             'peak_mount_force_lb']
    ratios = [float(v) for v in a.ratios.split(',')]
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for r, w, k, sigma, disp, force in pool.map(lambda r: point(text, r, a.work, a.flexmech), ratios):
            lines.append('%.4f %.6g %.6g %.6g %.6g %.6g %.6g' % (r, w, k, sigma, sigma/sigma_rigid, disp, force))
            print(lines[-1], flush=True)
    with open(a.out + '.dat', 'w') as f:
        f.write('\n'.join(lines) + '\n')
    subprocess.run(['gnuplot', a.out + '.gp'], check=True)


if __name__ == '__main__':
    main()
