"""flexmech against Exudyn on the RSSR four-bar (doc/spatial.md, "Cross-check against Exudyn").

The mechanism of inputs/spatial_rssr_100.nml in both codes: crank 6 in about Z through the origin
(clamped to its shaft, turning at a constant omega = 100 rad/s from the rigid state at crank angle 0),
rocker 12 in about X through D = (0, 20, 12) in (clamped to its shaft against bending out of its
plane, free to turn about X), coupler 24 in, spherical joints at B and C, branch 1; circular links
r = 0.25 in, E = 10.87e6 psi, nu = 0.33, rho = 2.536e-4 lb s^2/in^4; geometrically nonlinear,
rotary and torsional inertia, LINEAR material (the peer has no Ramberg-Osgood law); undamped in
bending, one revolution from the rigid-body state at crank angle 0 (a step load: the response is the
forced motion plus the free vibration the start excites, the same initial-value problem in both codes).
A damped run into the periodic state is not possible: Exudyn 1.13.6's 3D geometrically exact beam
ignores its section damping matrix (a clamped beam's free vibration is the same to all digits with
beta = 0 and 5e-4 s).

flexmech: the consistent element at the deck's mesh (1, 4, 2 elements), default solver settings (the
deck below); beta = 1e-6 s on the axial modes as in inputs/spatial_rssr_100.nml (zeta = 1.4e-4 in the
first bending mode).
Exudyn: ObjectBeamGeometricallyExact, its 3D geometrically exact (Simo-Reissner) beam: two rigid-body
nodes, linear interpolation, one-point (reduced) integration; generalized-alpha with a fixed step.
The nodes are NodeRigidBodyEP (Euler parameters): with the rotation-vector nodes
(NodeRigidBodyRotVecLG) Newton stalls when a crank node's rotation vector reaches 2 pi k (3 or 4
turns; the two agree to 1e-6 over the first turn).  Its section: axial EA, torsion GJ (J = 2I),
bending EI, shear stiffness SHEAR_FACTOR x kGA (k = 0.9): stiff, so that the beam is
Euler-Bernoulli's as flexmech's is;
section inertia rho (J, I, I); no damping (generalized-alpha's numerical dissipation, spectral
radius 0.9 at infinity, takes the axial modes' part).  The crank's first node
is held by a generic joint to a hub whose rotation about Z is driven at omega (velocity-level
coordinate constraint); the rocker's first node is on a revolute joint about X; B and C are
spherical joints between the link end nodes.  Initial state: the rigid motion at crank angle 0
(positions, velocities, the coupler's frame and spin as flexmech's kinematics defines them).

Outputs over the revolution (histories at every degree of crank angle):
  B_UZ, C_UX   elastic displacement of B along Z and of C along X (out of the crank's and the
               rocker's planes of motion; in)
  B_U, C_U     magnitude of the elastic displacement of B and of C (in)
  M_A, M_D     bending moment at the crank root (A) and the rocker root (D) (lb in)
  sigma_c      largest |normal stress| in the coupler, |N|/A + |M| r/I (psi)

Usage: python spatial_rssr.py --flexmech build/bin/flexmech --work build/peers [--turns N]
It prints the table of doc/spatial.md and writes build/peers/spatial_rssr/overlay.dat for
doc/figures/spatial_rssr_peer.gp.
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))
from peer_run import run_child, run_timed, start  # noqa: E402

L_CRANK, L_COUPLER, L_ROCKER = 6.0, 24.0, 12.0
D_PIVOT = np.array([0.0, 20.0, 12.0])
RADIUS = 0.25
E1, NU, RHO = 10.87e6, 0.33, 2.536e-4
OMEGA = 100.0
AREA = math.pi * RADIUS**2
INERTIA = math.pi * RADIUS**4 / 4.0
SHEAR_FACTOR = 100.0
TURNS = 1
NEWTON_RTOL = float(os.environ.get("EXUDYN_NEWTON_RTOL", "1e-6"))   # 1e-7 meets round-off after a few turns
OUTPUTS = ('B_UZ', 'C_UX', 'B_U', 'C_U', 'M_A', 'M_D', 'sigma_c')
DECK_MESH = (1, 4, 2)            # inputs/spatial_rssr_100.nml's elements (crank, coupler, rocker)
FINER_MESH = (2, 8, 4)           # the doubled mesh
REFERENCE_MESH = (4, 16, 8)      # flexmech's own reference (rtol 1e-8)


# ------------------------------------------------------------------ rigid kinematics (flexmech's)
def rigid_pose(theta):
    """B, C and the link frames (columns x, y, z) at crank angle theta, branch 1."""
    b = np.array([L_CRANK * math.cos(theta), L_CRANK * math.sin(theta), 0.0])
    e1, e2 = np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])   # rocker plane: psi from Y to Z
    db = D_PIVOT - b
    p, q = 2.0 * L_ROCKER * db.dot(e1), 2.0 * L_ROCKER * db.dot(e2)
    s = L_COUPLER**2 - db.dot(db) - L_ROCKER**2
    psi = math.atan2(q, p) + math.acos(s / math.hypot(p, q))
    c = D_PIVOT + L_ROCKER * (math.cos(psi) * e1 + math.sin(psi) * e2)

    def frame(x, z):
        x = x / np.linalg.norm(x)
        z = z - z.dot(x) * x
        z = z / np.linalg.norm(z)
        return np.column_stack([x, np.cross(z, x), z])
    zg = np.array([0.0, 0.0, 1.0])
    return b, c, [frame(b, zg), frame(c - b, zg), frame(c - D_PIVOT, np.array([1.0, 0.0, 0.0]))]


def rigid_rates(theta, omega, pose=rigid_pose):
    """Velocities of B, C and the links' angular velocities (global), by central differences of pose."""
    h = 1.0e-6
    bp, cp, rp = pose(theta + h)
    bm, cm, rm = pose(theta - h)
    vb, vc = omega * (bp - bm) / (2 * h), omega * (cp - cm) / (2 * h)
    ws = []
    for k in range(3):
        rdot = omega * (rp[k] - rm[k]) / (2 * h)
        r = 0.5 * (rp[k] + rm[k])
        w = rdot @ r.T
        ws.append(np.array([w[2, 1] - w[1, 2], w[0, 2] - w[2, 0], w[1, 0] - w[0, 1]]) / 2.0)
    return vb, vc, ws


# ------------------------------------------------------------------ Exudyn
def add_link(mbs, sec, n, p, q, rot, vp, w):
    """n beam elements from p to q in the frame rot, rigid velocity vp at p and angular velocity w."""
    from exudyn.itemInterface import NodeRigidBodyEP, ObjectBeamGeometricallyExact
    from exudyn.rigidBodyUtilities import RotationMatrix2EulerParameters, AngularVelocity2EulerParameters_t
    ep = list(RotationMatrix2EulerParameters(rot))
    epd = list(AngularVelocity2EulerParameters_t(w, ep))
    nodes, beams = [], []
    for k in range(n + 1):
        x = p + (q - p) * k / n
        v = vp + np.cross(w, x - p)
        nodes.append(mbs.AddNode(NodeRigidBodyEP(referenceCoordinates=list(x) + ep,
                                                 initialVelocities=list(v) + epd)))
    le = np.linalg.norm(q - p) / n
    for k in range(n):
        beams.append(mbs.AddObject(ObjectBeamGeometricallyExact(nodeNumbers=[nodes[k], nodes[k + 1]],
                                                                length=le, sectionData=sec)))
    return nodes, beams


def add_driven_clamp(mbs, node, omega):
    """The crank's shaft at the origin: a hub whose rotations x, y are held and whose rate about Z is held
    at omega, clamped to node; (the clamp's object number, the hub's node number, a ground coordinate marker)."""
    from exudyn.itemInterface import (NodeRigidBodyRxyz, ObjectRigidBody, MarkerNodeCoordinate, MarkerNodeRigid,
                                      MarkerBodyRigid, ObjectJointGeneric, CoordinateConstraint, NodePointGround)
    ground_node = mbs.AddNode(NodePointGround())
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    hub = mbs.AddNode(NodeRigidBodyRxyz(referenceCoordinates=[0.0] * 6, initialVelocities=[0, 0, 0, 0, 0, omega]))
    hub_body = mbs.AddObject(ObjectRigidBody(nodeNumber=hub, mass=1.0, inertia=[1.0, 1.0, 1.0, 0, 0, 0]))
    for k in range(6):
        mbs.AddObject(CoordinateConstraint(
            markerNumbers=[mg, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub, coordinate=k))],
            offset=omega if k == 5 else 0.0, velocityLevel=(k == 5)))
    clamp = mbs.AddObject(ObjectJointGeneric(markerNumbers=[
        mbs.AddMarker(MarkerBodyRigid(bodyNumber=hub_body, localPosition=[0, 0, 0])),
        mbs.AddMarker(MarkerNodeRigid(nodeNumber=node))], constrainedAxes=[1] * 6))
    return clamp, hub


def solve(mbs, end_time, steps, write_period, newton_rtol):
    """Generalized-alpha over [0, end_time] at a fixed step (its defaults, modified Newton, sparse solver)."""
    import exudyn as exu
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = steps
    ss.timeIntegration.verboseMode = int(os.environ.get("EXUDYN_VERBOSE", "0"))
    ss.timeIntegration.newton.relativeTolerance = newton_rtol
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = write_period
    ss.show.computationTime = False
    ss.show.statistics = False
    exu.SolveDynamic(mbs, ss)


def exudyn_case(n, steps_per_turn, turns):
    import exudyn as exu
    from exudyn.itemInterface import (ObjectGround, MarkerNodeRigid, MarkerNodePosition, MarkerBodyRigid,
                                      ObjectJointRevoluteZ, ObjectJointSpherical, SensorNode, SensorObject,
                                      SensorBody)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    b, c, frames = rigid_pose(0.0)
    vb, vc, ws = rigid_rates(0.0, OMEGA)
    g_modulus = E1 / (2.0 * (1.0 + NU))
    sec = exu.BeamSection()
    sec.stiffnessMatrix = np.diag([E1 * AREA, SHEAR_FACTOR * 0.9 * g_modulus * AREA,
                                   SHEAR_FACTOR * 0.9 * g_modulus * AREA, g_modulus * 2 * INERTIA,
                                   E1 * INERTIA, E1 * INERTIA])
    sec.massPerLength = RHO * AREA
    sec.inertia = np.diag([RHO * 2 * INERTIA, RHO * INERTIA, RHO * INERTIA])

    origin = np.zeros(3)
    crank, _ = add_link(mbs, sec, n, origin, b, frames[0], origin, ws[0])
    coupler, coupler_beams = add_link(mbs, sec, n, b, c, frames[1], vb, ws[1])
    rocker, _ = add_link(mbs, sec, n, D_PIVOT, c, frames[2], origin, ws[2])

    ground = mbs.AddObject(ObjectGround())
    clamp, hub = add_driven_clamp(mbs, crank[0], OMEGA)
    # the rocker's shaft: a revolute joint about X at D (the joint's z is the rocker frame's z)
    to_x = np.column_stack([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
    pivot = mbs.AddObject(ObjectJointRevoluteZ(markerNumbers=[
        mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=to_x, translation=D_PIVOT))),
        mbs.AddMarker(MarkerNodeRigid(nodeNumber=rocker[0]))]))
    for n1, n2 in ((crank[-1], coupler[0]), (coupler[-1], rocker[-1])):
        mbs.AddObject(ObjectJointSpherical(markerNumbers=[mbs.AddMarker(MarkerNodePosition(nodeNumber=n1)),
                                                          mbs.AddMarker(MarkerNodePosition(nodeNumber=n2))]))

    period = 2.0 * math.pi / OMEGA
    per_deg = period / 360.0

    def sensor(**kw):
        return mbs.AddSensor(kw.pop('kind')(storeInternal=True, writeToFile=False, **kw))
    s_b = sensor(kind=SensorNode, nodeNumber=crank[-1], outputVariableType=exu.OutputVariableType.Position)
    s_c = sensor(kind=SensorNode, nodeNumber=rocker[-1], outputVariableType=exu.OutputVariableType.Position)
    s_hub = sensor(kind=SensorNode, nodeNumber=hub, outputVariableType=exu.OutputVariableType.Coordinates)
    s_ma = sensor(kind=SensorObject, objectNumber=clamp, outputVariableType=exu.OutputVariableType.TorqueLocal)
    s_md = sensor(kind=SensorObject, objectNumber=pivot, outputVariableType=exu.OutputVariableType.TorqueLocal)
    s_cm = [sensor(kind=SensorBody, bodyNumber=e, localPosition=[0, 0, 0],
                   outputVariableType=exu.OutputVariableType.TorqueLocal) for e in coupler_beams]
    s_cn = [sensor(kind=SensorBody, bodyNumber=e, localPosition=[0, 0, 0],
                   outputVariableType=exu.OutputVariableType.ForceLocal) for e in coupler_beams]
    mbs.Assemble()

    solve(mbs, turns * period, turns * steps_per_turn, per_deg, NEWTON_RTOL)

    def data(s):
        return np.array(mbs.GetSensorStoredData(s))
    db, dc, dhub, dma, dmd = data(s_b), data(s_c), data(s_hub), data(s_ma), data(s_md)
    t = db[:, 0]
    # samples of the last turn, at whole degrees (the sensor times may miss a period by round-off)
    deg = np.rint(t / per_deg).astype(int)
    last = deg >= (turns - 1) * 360
    out = {k: [] for k in ('deg',) + OUTPUTS}
    cm = [data(s)[:, 1:] for s in s_cm]
    cn = [data(s)[:, 1:] for s in s_cn]
    for j in np.nonzero(last)[0]:
        bj, cj, _ = rigid_pose(OMEGA * t[j])
        ub, uc = db[j, 1:4] - bj, dc[j, 1:4] - cj
        out['deg'].append(int(deg[j] - (turns - 1) * 360))
        out['B_UZ'].append(ub[2])
        out['C_UX'].append(uc[0])
        out['B_U'].append(float(np.linalg.norm(ub)))
        out['C_U'].append(float(np.linalg.norm(uc)))
        out['M_A'].append(math.hypot(dma[j, 2], dma[j, 3]))     # about the crank's y and z (the joint frame)
        # the revolute joint's local torque: its x and y are the moments of its two rotation constraints,
        # about the rocker's y (out of its plane) and x (torsion) axes (read as a vector in the joint's
        # frame and projected on the rocker's axes they give 20 % less than flexmech's My at D)
        out['M_D'].append(math.hypot(dmd[j, 1], dmd[j, 2]))
        out['sigma_c'].append(max(abs(cn[e][j, 0]) / AREA + math.hypot(cm[e][j, 1], cm[e][j, 2]) * RADIUS / INERTIA
                                  for e in range(n)))
    out['hub_angle_error'] = float(np.max(np.abs(dhub[:, 6] - OMEGA * dhub[:, 0])))
    # periodicity: the largest change of B's and C's elastic displacements from one turn to the next
    ue = np.array([np.concatenate([db[j, 1:4] - rigid_pose(OMEGA * t[j])[0], dc[j, 1:4] - rigid_pose(OMEGA * t[j])[1]])
                   for j in range(len(t))])
    at = {d: j for j, d in enumerate(deg)}
    out['turn_change'] = [float(max(np.max(np.abs(ue[at[d]] - ue[at[d - 360]])) for d in range(360 * k, 360 * (k + 1))
                                    if d in at and d - 360 in at) / np.max(np.abs(ue)))
                          for k in range(1, turns)]
    return out


# ------------------------------------------------------------------ flexmech
DECK = """&run
  analysis = 'spatial'
  title = 'RSSR four-bar at 100 rad/s, linear material, from the rigid state: the peer comparison'
/
&spatial_mechanism
  crank_pivot = 0.0, 0.0, 0.0
  crank_axis = 0.0, 0.0, 1.0
  crank_pin = 6.0, 0.0, 0.0
  rocker_pivot = 0.0, 20.0, 12.0
  rocker_axis = 1.0, 0.0, 0.0
  rocker_length = 12.0
  coupler_length = 24.0
  branch = 1
  joint_b = 'spherical'
  joint_c = 'spherical'
  omega = 100.0
  link_n_elements = {mesh}
  link_section = 3*'circular'
  link_radius = 3*0.25
/
&transient
  rtol = {rtol}
  revolutions = {turns}
  output_step_deg = 1.0
  damping_beta = 1.0e-6
/
&effects
  stretching = T, curvature = T, material = F, rotary_inertia = T, coupling = T
  formulation = '{formulation}'
/
"""


def read_flexmech(path):
    """A flexmech output's columns (name -> index) and rows."""
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                if line.split()[1:2] == ['t']:
                    header = line[1:].split()
                continue
            if line.strip():
                rows.append([float(v) for v in line.split()])
    return {name: k for k, name in enumerate(header)}, rows


def flexmech_outputs(path, mesh, turns):
    col, rows = read_flexmech(path)
    nc = mesh[1]
    coupler = [col['sigma_max_e%d' % (mesh[0] + k)] for k in range(1, nc + 1)]
    out = {k: [] for k in ('deg',) + OUTPUTS}
    for r in rows:
        d = int(round(r[col['crank_deg']]))
        if d < (turns - 1) * 360:
            continue
        ub = np.array([r[col['B_U' + a]] for a in 'XYZ'])
        uc = np.array([r[col['C_U' + a]] for a in 'XYZ'])
        out['deg'].append(d - (turns - 1) * 360)
        out['B_UZ'].append(ub[2])
        out['C_UX'].append(uc[0])
        out['B_U'].append(float(np.linalg.norm(ub)))
        out['C_U'].append(float(np.linalg.norm(uc)))
        out['M_A'].append(math.hypot(r[col['crank_My_root']], r[col['crank_Mz_root']]))
        out['M_D'].append(math.hypot(r[col['rocker_My_root']], r[col['rocker_Mz_root']]))
        out['sigma_c'].append(max(r[k] for k in coupler))
    return out


def flexmech_case(exe, work, mesh, rtol, formulation, turns):
    tag = 'flexmech_%s_%s_rtol%g_t%d' % (formulation, '-'.join(map(str, mesh)), rtol, turns)
    deck, out = os.path.join(work, tag + '.nml'), os.path.join(work, tag + '.out')
    with open(deck, 'w') as f:
        f.write(DECK.format(mesh=', '.join(map(str, mesh)), rtol=rtol, turns=turns, formulation=formulation))
    cpu = run_timed([exe, deck, '-o', out])
    return cpu, (flexmech_outputs(out, mesh, turns) if cpu is not None else None)


def exudyn_child(work, n, steps, turns):
    return run_child(__file__, os.path.join(work, 'exudyn_n%d_s%d_t%d.json' % (n, steps, turns)), n, steps,
                     ['--turns', str(turns)])


def common(a, b, outputs=OUTPUTS):
    """The two runs' histories at the crank angles both have."""
    ia = {d: k for k, d in enumerate(a['deg'])}
    pairs = [(ia[d], k) for k, d in enumerate(b['deg']) if d in ia]
    return {key: (np.array([a[key][i] for i, _ in pairs]), np.array([b[key][j] for _, j in pairs]))
            for key in outputs}, [a['deg'][i] for i, _ in pairs]


def compare(a, b, outputs=OUTPUTS):
    """Per output: peak |a|, peak |b|, peak difference (b/a - 1), RMS(b - a) / peak |a|."""
    h, _ = common(a, b, outputs)
    res = {}
    for key in outputs:
        x, y = h[key]
        pa, pb = float(np.max(np.abs(x))), float(np.max(np.abs(y)))
        res[key] = (pa, pb, pb / pa - 1.0, float(np.sqrt(np.mean((y - x)**2))) / pa)
    return res


def print_compare(title, a, b, names=('flexmech', 'Exudyn'), outputs=OUTPUTS):
    print('\n' + title)
    print('%-8s %13s %13s %9s %12s' % ('output', 'peak ' + names[0], 'peak ' + names[1], 'peak diff', 'RMS diff/peak'))
    for key, (pa, pb, dp, dr) in compare(a, b, outputs).items():
        print('%-8s %13.6g %13.6g %+8.2f%% %11.2f%%' % (key, pa, pb, 100 * dp, 100 * dr))


def main():
    a, work = start(lambda ap: ap.add_argument('--turns', type=int, default=TURNS),
                    lambda a, n, steps: exudyn_case(n, steps, a.turns), 'spatial_rssr')
    if a is None:
        return
    turns = a.turns
    print('RSSR four-bar, %g rad/s, linear material, undamped, from the rigid state; histories over turn %d '
          'of %d, every degree' % (OMEGA, turns, turns))
    print('outputs: B_UZ, C_UX = elastic displacement of B along Z, of C along X (in); B_U, C_U = their '
          'magnitudes (in);\n  M_A, M_D = crank and rocker root bending moments (lb in); sigma_c = largest '
          'coupler stress (psi)')

    # Exudyn's own convergence: mesh at a fixed step, step at the finest mesh
    ex = {}
    for n, s in ((16, 2000), (32, 2000), (64, 2000), (64, 4000)):
        cpu, o = exudyn_child(work, n, s, turns)
        if o is None:
            print('Exudyn %d elements a link, %d steps a turn: the run failed' % (n, s))
            continue
        ex[(n, s)] = (cpu, o)
        print('Exudyn %2d elements a link, %4d steps a turn: CPU %.1f s, hub angle error %.1e rad'
              % (n, s, cpu, o['hub_angle_error'])
              + ('; change from one turn to the next / peak (B, C): %s'
                 % ', '.join('%.1e' % c for c in o['turn_change']) if o['turn_change'] else ''))
    ex_ref = ex[(64, 4000)][1]
    for key in ((16, 2000), (32, 2000), (64, 2000)):
        if key in ex:
            print_compare('Exudyn %d elements, %d steps against 64 elements, 4000 steps:' % key,
                          ex_ref, ex[key][1], ('ref', 'this'))

    fm = {}
    for mesh, form, rtol in ((DECK_MESH, 'consistent', 1e-6), (FINER_MESH, 'consistent', 1e-8),
                             (REFERENCE_MESH, 'consistent', 1e-8), ((1, 1, 1), 'exact', 1e-6)):
        cpu, o = flexmech_case(a.flexmech, work, mesh, rtol, form, turns)
        if o is None:
            print('flexmech %s %s: the run failed' % (form, mesh))
            continue
        fm[(mesh, form)] = o
        print('flexmech %s, elements %s, rtol %g: CPU %.1f s (%.2f s a turn)' % (form, mesh, rtol, cpu, cpu / turns))
    fm_ref = fm[(REFERENCE_MESH, 'consistent')]
    fm_deck = fm[(DECK_MESH, 'consistent')]
    for mesh in (DECK_MESH, FINER_MESH):
        print_compare('flexmech consistent %s against %s, rtol 1e-8:' % (mesh, REFERENCE_MESH), fm_ref,
                      fm[(mesh, 'consistent')], ('reference', 'this'))
    for (mesh, form), o in fm.items():
        print_compare('flexmech %s %s against Exudyn 64 elements, 4000 steps:' % (form, mesh), o, ex_ref)

    h, degs = common(fm_deck, ex_ref)
    hk = common(fm[((1, 1, 1), 'exact')], ex_ref)[0] if ((1, 1, 1), 'exact') in fm else None
    path = os.path.join(work, 'overlay.dat')
    with open(path, 'w') as f:
        f.write('# deg ' + ' '.join('%s_flexmech %s_exudyn %s_kear' % (k, k, k) for k in OUTPUTS) + '\n')
        for i, d in enumerate(degs):
            f.write('%d' % d + ''.join(' %.8g %.8g %.8g' % (h[k][0][i], h[k][1][i],
                                                             hk[k][0][i] if hk else float('nan'))
                                       for k in OUTPUTS) + '\n')
    print('\noverlay data: %s (gnuplot doc/figures/spatial_rssr_peer.gp)' % path)


if __name__ == '__main__':
    main()
