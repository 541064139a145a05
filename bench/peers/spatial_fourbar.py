"""flexmech's spatial analysis against Exudyn on the planar four-bar built in 3D (doc/spatial.md,
"Cross-check against Exudyn").

Tennant's four-bar as in inputs/spatial_fourbar_100.nml, in both codes as a 3D model: crank 5 in
(clamped to its shaft at A = origin, turning about Z at a constant omega = 100 rad/s from the rigid
state at crank angle 0), coupler 11 in, rocker 10.5 in on a pin at D = (10, 0, 0), revolute joints
about Z at B and C, branch 1; every link a 1.0 x 0.25 in rectangle (1.0 in the plane of motion),
E = 10.87e6 psi, nu = 0.33, rho = 2.536e-4 lb s^2/in^4; geometrically nonlinear, rotary and torsional
inertia, LINEAR material (the peer has no Ramberg-Osgood law); undamped, one revolution from the
rigid-body state (the same initial-value problem in both codes).  The peer's beams are 3D
and can leave the plane; neither does (the out-of-plane displacements are checked to stay at
round-off).

flexmech: the consistent element at the deck's mesh, two elements a link, default solver settings,
undamped (damping_beta = 0), as the peer.  A second run with beta = 1e-6 s, the shipped decks' damping
of the axial modes, shows what that damping does here: it is not small for this linkage's bending
modes (natural frequencies at the start 1214, 1461, 2712, 3083 rad/s in the plane: zeta = beta omega / 2
= 6e-4 to 1.5e-3, and the free vibration the start leaves decays by exp(-beta omega^2 t / 2), 5 % to 26 %
over the turn), which alone makes a 9-16 % difference in the peaks the free vibration sets.  Exudyn: ObjectBeamGeometricallyExact as in
spatial_rssr.py (Euler-parameter nodes, stiff shear, section inertia rho (Ip, Iy, Iz)), the crank's
hub and clamp as there; ObjectJointRevoluteZ at B, C (between the link end nodes, whose z stays Z in
planar motion) and at D.

Outputs over the revolution (every degree of crank angle):
  B_UX, B_UY, C_UX, C_UY   elastic displacements of the joints B and C (global; in)
  M_A                      bending moment at the crank root (lb in)
  sigma_c, sigma_r         largest |normal stress| in the coupler and in the rocker,
                           |N|/A + |M_y| (w/2)/I_y + |M_z| (h/2)/I_z (psi)

Usage: python spatial_fourbar.py --flexmech build/bin/flexmech --work build/peers
It prints the table of doc/spatial.md and writes build/peers/spatial_fourbar/overlay.dat.
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, 'lib'))
sys.path.insert(0, HERE)
from peer_run import run_child, run_timed, start  # noqa: E402
from spatial_rssr import add_driven_clamp, add_link, common, print_compare, read_flexmech, rigid_rates, solve  # noqa: E402,E501

L_CRANK, L_COUPLER, L_ROCKER = 5.0, 11.0, 10.5
D_PIVOT = np.array([10.0, 0.0, 0.0])
DEPTH, WIDTH = 1.0, 0.25                      # along the link's y (in the plane) and z
E1, NU, RHO = 10.87e6, 0.33, 2.536e-4
OMEGA = 100.0
AREA = DEPTH * WIDTH
I_Y, I_Z = DEPTH * WIDTH**3 / 12.0, WIDTH * DEPTH**3 / 12.0
SHEAR_FACTOR = 100.0
OUTPUTS = ('B_UX', 'B_UY', 'C_UX', 'C_UY', 'M_A', 'sigma_c', 'sigma_r')
PLANE = ('B_UZ', 'C_UZ')


def torsion_constant(b, t):
    """St. Venant J of a b x t rectangle (t <= b): Timoshenko & Goodier's series."""
    s = sum(math.tanh(n * math.pi * b / (2 * t)) / n**5 for n in range(1, 40, 2))
    return b * t**3 / 3.0 * (1.0 - 192.0 / math.pi**5 * t / b * s)


def rigid_pose(theta):
    """B, C and the link frames (columns x, y, z) at crank angle theta, branch 1 (flexmech's rule)."""
    b = np.array([L_CRANK * math.cos(theta), L_CRANK * math.sin(theta), 0.0])
    e1, e2 = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    db = D_PIVOT - b
    p, q = 2.0 * L_ROCKER * db.dot(e1), 2.0 * L_ROCKER * db.dot(e2)
    s = L_COUPLER**2 - db.dot(db) - L_ROCKER**2
    psi = math.atan2(q, p) + math.acos(s / math.hypot(p, q))
    c = D_PIVOT + L_ROCKER * (math.cos(psi) * e1 + math.sin(psi) * e2)
    z = np.array([0.0, 0.0, 1.0])

    def frame(x):
        x = x / np.linalg.norm(x)
        return np.column_stack([x, np.cross(z, x), z])
    return b, c, [frame(b), frame(c - b), frame(c - D_PIVOT)]


def exudyn_case(n, steps_per_turn):
    import exudyn as exu
    from exudyn.itemInterface import (ObjectGround, MarkerNodeRigid, MarkerBodyRigid, ObjectJointRevoluteZ,
                                      SensorNode, SensorObject, SensorBody)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    b, c, frames = rigid_pose(0.0)
    vb, vc, ws = rigid_rates(0.0, OMEGA, rigid_pose)
    g_modulus = E1 / (2.0 * (1.0 + NU))
    shear = SHEAR_FACTOR * 5.0 / 6.0 * g_modulus * AREA
    sec = exu.BeamSection()
    sec.stiffnessMatrix = np.diag([E1 * AREA, shear, shear, g_modulus * torsion_constant(DEPTH, WIDTH),
                                   E1 * I_Y, E1 * I_Z])
    sec.massPerLength = RHO * AREA
    sec.inertia = np.diag([RHO * (I_Y + I_Z), RHO * I_Y, RHO * I_Z])

    origin = np.zeros(3)
    crank, _ = add_link(mbs, sec, n, origin, b, frames[0], origin, ws[0])
    coupler, coupler_beams = add_link(mbs, sec, n, b, c, frames[1], vb, ws[1])
    rocker, rocker_beams = add_link(mbs, sec, n, D_PIVOT, c, frames[2], origin, ws[2])

    ground = mbs.AddObject(ObjectGround())
    clamp, _ = add_driven_clamp(mbs, crank[0], OMEGA)
    mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[
        mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=list(D_PIVOT))),
        mbs.AddMarker(MarkerNodeRigid(nodeNumber=rocker[0]))]))
    for n1, n2 in ((crank[-1], coupler[0]), (coupler[-1], rocker[-1])):
        mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[mbs.AddMarker(MarkerNodeRigid(nodeNumber=n1)),
                                                          mbs.AddMarker(MarkerNodeRigid(nodeNumber=n2))]))

    period = 2.0 * math.pi / OMEGA
    per_deg = period / 360.0

    def sensor(kind, **kw):
        return mbs.AddSensor(kind(storeInternal=True, writeToFile=False, **kw))
    s_b = sensor(SensorNode, nodeNumber=crank[-1], outputVariableType=exu.OutputVariableType.Position)
    s_c = sensor(SensorNode, nodeNumber=rocker[-1], outputVariableType=exu.OutputVariableType.Position)
    s_ma = sensor(SensorObject, objectNumber=clamp, outputVariableType=exu.OutputVariableType.TorqueLocal)
    s_beam = {}
    for name, beams in (('sigma_c', coupler_beams), ('sigma_r', rocker_beams)):
        s_beam[name] = [(sensor(SensorBody, bodyNumber=e, localPosition=[0, 0, 0],
                                outputVariableType=exu.OutputVariableType.ForceLocal),
                         sensor(SensorBody, bodyNumber=e, localPosition=[0, 0, 0],
                                outputVariableType=exu.OutputVariableType.TorqueLocal)) for e in beams]
    mbs.Assemble()

    solve(mbs, period, steps_per_turn, per_deg, 1e-6)

    def data(s):
        return np.array(mbs.GetSensorStoredData(s))
    db, dc, dma = data(s_b), data(s_c), data(s_ma)
    beam = {name: [(data(f)[:, 1:], data(m)[:, 1:]) for f, m in pairs] for name, pairs in s_beam.items()}
    t = db[:, 0]
    out = {k: [] for k in ('deg',) + OUTPUTS + PLANE}
    for j in range(len(t)):
        bj, cj, _ = rigid_pose(OMEGA * t[j])
        ub, uc = db[j, 1:4] - bj, dc[j, 1:4] - cj
        out['deg'].append(int(np.rint(t[j] / per_deg)))
        for key, v in (('B_UX', ub[0]), ('B_UY', ub[1]), ('B_UZ', ub[2]),
                       ('C_UX', uc[0]), ('C_UY', uc[1]), ('C_UZ', uc[2])):
            out[key].append(float(v))
        out['M_A'].append(math.hypot(dma[j, 2], dma[j, 3]))
        for name, pairs in beam.items():
            out[name].append(max(abs(f[j, 0]) / AREA + abs(m[j, 1]) * WIDTH / 2 / I_Y
                                 + abs(m[j, 2]) * DEPTH / 2 / I_Z for f, m in pairs))
    return out


DECK = """&run
  analysis = 'spatial'
  title = 'Tennant four-bar in 3D at 100 rad/s, linear material, from the rigid state: the peer comparison'
/
&spatial_mechanism
  crank_pivot = 0.0, 0.0, 0.0
  crank_axis = 0.0, 0.0, 1.0
  crank_pin = 5.0, 0.0, 0.0
  rocker_pivot = 10.0, 0.0, 0.0
  rocker_axis = 0.0, 0.0, 1.0
  rocker_length = 10.5
  coupler_length = 11.0
  branch = 1
  joint_b = 'revolute'
  joint_c = 'revolute'
  omega = 100.0
  link_n_elements = {mesh}
  link_section = 3*'rectangular'
  link_depth = 3*1.0
  link_width = 3*0.25
/
&transient
  rtol = {rtol}
  revolutions = 1
  output_step_deg = 1.0
  damping_beta = {beta}
/
&effects
  stretching = T, curvature = T, material = F, rotary_inertia = T, coupling = T
  formulation = '{formulation}'
/
"""


def flexmech_case(exe, work, mesh, rtol, formulation, beta):
    tag = 'flexmech_%s_%s_rtol%g_beta%g' % (formulation, '-'.join(map(str, mesh)), rtol, beta)
    deck, path = os.path.join(work, tag + '.nml'), os.path.join(work, tag + '.out')
    with open(deck, 'w') as f:
        f.write(DECK.format(mesh=', '.join(map(str, mesh)), rtol=rtol, formulation=formulation, beta=beta))
    cpu = run_timed([exe, deck, '-o', path])
    if cpu is None:
        return None, None
    col, rows = read_flexmech(path)
    first = {'sigma_c': mesh[0] + 1, 'sigma_r': mesh[0] + mesh[1] + 1}
    count = {'sigma_c': mesh[1], 'sigma_r': mesh[2]}
    out = {k: [] for k in ('deg',) + OUTPUTS + PLANE}
    for r in rows:
        out['deg'].append(int(round(r[col['crank_deg']])))
        for key in ('B_UX', 'B_UY', 'B_UZ', 'C_UX', 'C_UY', 'C_UZ'):
            out[key].append(r[col[key]])
        out['M_A'].append(math.hypot(r[col['crank_My_root']], r[col['crank_Mz_root']]))
        for name in ('sigma_c', 'sigma_r'):
            out[name].append(max(r[col['sigma_max_e%d' % k]] for k in range(first[name], first[name] + count[name])))
    return cpu, out


def main():
    a, work = start(lambda ap: None, lambda a, n, steps: exudyn_case(n, steps), 'spatial_fourbar')
    if a is None:
        return
    print('Tennant four-bar in 3D, %g rad/s, linear material, undamped, from the rigid state; histories over '
          'one revolution, every degree' % OMEGA)
    ex = {}
    for n, s in ((32, 2000), (32, 4000), (32, 8000), (64, 8000)):
        cpu, o = run_child(__file__, os.path.join(work, 'exudyn_n%d_s%d.json' % (n, s)), n, s, [])
        if o is None:
            print('Exudyn %d elements a link, %d steps a turn: the run failed' % (n, s))
            continue
        ex[(n, s)] = o
        print('Exudyn %2d elements a link, %4d steps a turn: CPU %.1f s; largest out-of-plane |B_UZ|, |C_UZ| '
              '%.1e, %.1e in' % (n, s, cpu, max(map(abs, o['B_UZ'])), max(map(abs, o['C_UZ']))))
    ex_ref = ex[(64, 8000)]
    for key in ((32, 2000), (32, 4000), (32, 8000)):
        if key in ex:
            print_compare('Exudyn %d elements, %d steps against 64 elements, 8000 steps:' % key,
                          ex_ref, ex[key], ('ref', 'this'), OUTPUTS)
    fm = {}
    for mesh, form, rtol, beta in (((2, 2, 2), 'consistent', 1e-6, 0.0), ((4, 4, 4), 'consistent', 1e-8, 0.0),
                                   ((2, 2, 2), 'consistent', 1e-6, 1e-6), ((1, 1, 1), 'exact', 1e-6, 0.0)):
        cpu, o = flexmech_case(a.flexmech, work, mesh, rtol, form, beta)
        if o is None:
            print('flexmech %s %s, beta %g: the run failed' % (form, mesh, beta))
            continue
        fm[(mesh, form, beta)] = o
        print('flexmech %s, elements %s, rtol %g, beta %g s: CPU %.2f s; largest out-of-plane |B_UZ|, |C_UZ| '
              '%.1e, %.1e in' % (form, mesh, rtol, beta, cpu, max(map(abs, o['B_UZ'])), max(map(abs, o['C_UZ']))))
    deck = fm[((2, 2, 2), 'consistent', 0.0)]
    print_compare('flexmech consistent (2, 2, 2) against (4, 4, 4), rtol 1e-8, undamped:',
                  fm[((4, 4, 4), 'consistent', 0.0)], deck, ('4,4,4', 'this'), OUTPUTS)
    print_compare('flexmech consistent (2, 2, 2): beta = 1e-6 s against undamped:', deck,
                  fm[((2, 2, 2), 'consistent', 1e-6)], ('undamped', 'beta 1e-6'), OUTPUTS)
    for (mesh, form, beta), o in fm.items():
        print_compare('flexmech %s %s, beta %g s, against Exudyn 64 elements, 8000 steps:' % (form, mesh, beta),
                      o, ex_ref, outputs=OUTPUTS)
    h, degs = common(deck, ex_ref, OUTPUTS)
    path = os.path.join(work, 'overlay.dat')
    with open(path, 'w') as f:
        f.write('# deg ' + ' '.join('%s_flexmech %s_exudyn' % (k, k) for k in OUTPUTS) + '\n')
        for i, d in enumerate(degs):
            f.write('%d' % d + ''.join(' %.8g %.8g' % (h[k][0][i], h[k][1][i]) for k in OUTPUTS) + '\n')
    print('\noverlay data: %s' % path)


if __name__ == '__main__':
    main()
