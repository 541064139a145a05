"""flexmech against Exudyn on Tennant's four-bar (doc/benchmarks.md, "Peer comparison").

The same mechanism in both codes: crank 5 in (clamped to its shaft at A, turning at a constant
omega from the rigid state at crank angle 0), coupler 11 in, rocker 10.5 in, ground 10 in; every
link 0.25 x 1.0 in, E = 10.87e6 psi, rho = 2.536e-4 lb s^2/in^4; stiffness-proportional damping
beta = 1e-5 s; geometrically nonlinear (exact stretching and curvature, the rotating frame's
coupling), linear material, no rotary inertia (the peer's cable element has none).

flexmech: the consistent element (quintic u and w), DLSODE's BDF.
Exudyn: ANCFCable2D elements (cubic Hermite positions), generalized-alpha (its defaults, modified
Newton, Newton relative tolerance 1e-7, the sparse linear solver); damping
bendingDamping = beta EI and axialDamping = beta EA; the clamp a generic joint to a hub whose
rotation rate is held at omega; the pins revolute joints.

Outputs over the last crank revolution of five (peaks of |value|):
  sigma_b  the coupler's bending stress E kappa c (c = 0.5 in)                 (psi)
  chord    the coupler's mid-span distance from its deformed chord             (in)
  tip      the rocker tip's elastic displacement normal to the rigid rocker    (in)

Usage: python fourbar_planar.py --flexmech build/bin/flexmech --work build/peers [--omega 150]
The Exudyn runs are child processes of this script (--exudyn-case N STEPS), so that both codes
are measured as whole processes (user + system CPU of the child, os.wait4).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))
from peer_run import run_child, run_timed, start  # noqa: E402

L_CRANK, L_COUPLER, L_ROCKER, GROUND = 5.0, 11.0, 10.5, 10.0
B_WIDTH, H_DEPTH = 0.25, 1.0
E1, RHO, BETA = 10.87e6, 2.536e-4, 1.0e-5
AREA = B_WIDTH * H_DEPTH
INERTIA = B_WIDTH * H_DEPTH**3 / 12.0
FIBRE = 0.5 * H_DEPTH
TURNS = 5


# ------------------------------------------------------------------ rigid kinematics
def rigid(theta, omega):
    """Positions of B and C, link angles and rates of the rigid four-bar (open branch)."""
    bx, by = L_CRANK * math.cos(theta), L_CRANK * math.sin(theta)
    dx, dy = GROUND, 0.0
    ex, ey = dx - bx, dy - by
    d = math.hypot(ex, ey)
    a = (L_COUPLER**2 - L_ROCKER**2 + d * d) / (2.0 * d)
    h = math.sqrt(max(L_COUPLER**2 - a * a, 0.0))
    mx, my = bx + a * ex / d, by + a * ey / d
    cx, cy = mx - h * ey / d, my + h * ex / d          # open: sin(theta4 - theta3) > 0
    th3 = math.atan2(cy - by, cx - bx)
    th4 = math.atan2(cy - dy, cx - dx)
    if math.sin(th4 - th3) < 0.0:                       # the other intersection
        cx, cy = mx + h * ey / d, my - h * ex / d
        th3 = math.atan2(cy - by, cx - bx)
        th4 = math.atan2(cy - dy, cx - dx)
    # rates: vB + w3 k x (C - B) = w4 k x (C - D)
    vbx, vby = -omega * by, omega * bx
    a11, a12 = -(cy - by), (cy - dy)
    a21, a22 = (cx - bx), -(cx - dx)
    det = a11 * a22 - a12 * a21
    w3 = (-vbx * a22 + a12 * vby) / det
    w4 = (a11 * (-vby) + vbx * a21) / det
    return (bx, by), (cx, cy), th3, th4, omega, w3, w4


# ------------------------------------------------------------------ Exudyn
def exudyn_case(n, steps_per_turn, omega):
    import numpy as np
    import exudyn as exu
    from exudyn.itemInterface import (NodePoint2DSlope1, ObjectANCFCable2D, ObjectGround, NodeRigidBody2D,
                                      ObjectRigidBody2D, MarkerNodeCoordinate, MarkerNodePosition,
                                      MarkerBodyPosition, MarkerBodyRigid, ObjectJointRevolute2D,
                                      ObjectJointGeneric, CoordinateConstraint, NodePointGround,
                                      SensorNode)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    (bx, by), (cx, cy), th3, th4, w2, w3, w4 = rigid(0.0, omega)
    ground = mbs.AddObject(ObjectGround(referencePosition=[0, 0, 0]))
    ground_node = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))

    def link(p, q, w_link, vp):
        """n cable elements from p to q, initial velocity of rigid rotation w_link about p (p moving at vp)."""
        lx, ly = q[0] - p[0], q[1] - p[1]
        length = math.hypot(lx, ly)
        tx, ty = lx / length, ly / length
        nodes, cables = [], []
        for k in range(n + 1):
            x, y = p[0] + lx * k / n, p[1] + ly * k / n
            vx = vp[0] - w_link * (y - p[1])
            vy = vp[1] + w_link * (x - p[0])
            nodes.append(mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[x, y, tx, ty],
                                                       initialVelocities=[vx, vy, -w_link * ty, w_link * tx])))
        for k in range(n):
            cables.append(mbs.AddObject(ObjectANCFCable2D(
                length=length / n, massPerLength=RHO * AREA,
                bendingStiffness=E1 * INERTIA, axialStiffness=E1 * AREA,
                bendingDamping=BETA * E1 * INERTIA, axialDamping=BETA * E1 * AREA,
                nodeNumbers=[nodes[k], nodes[k + 1]])))
        return nodes, cables

    crank_nodes, crank_cables = link((0.0, 0.0), (bx, by), w2, (0.0, 0.0))
    vb = (-w2 * by, w2 * bx)
    coupler_nodes, _ = link((bx, by), (cx, cy), w3, vb)
    rocker_nodes, _ = link((GROUND, 0.0), (cx, cy), w4, (0.0, 0.0))

    # the crank's shaft: a hub at A whose position is held and whose rotation rate is omega
    hub = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0, 0, omega]))
    hub_body = mbs.AddObject(ObjectRigidBody2D(mass=1.0, inertia=1.0, nodeNumber=hub))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))
    for k in range(2):
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub,
                                                                                                 coordinate=k))]))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=hub,
                                                                                             coordinate=2))],
                                       offset=omega, velocityLevel=True))
    m_hub = mbs.AddMarker(MarkerBodyRigid(bodyNumber=hub_body, localPosition=[0, 0, 0]))
    m_crank = mbs.AddMarker(MarkerBodyRigid(bodyNumber=crank_cables[0], localPosition=[0, 0, 0]))
    mbs.AddObject(ObjectJointGeneric(markerNumbers=[m_hub, m_crank], constrainedAxes=[1, 1, 0, 0, 0, 1]))

    def pin(n1, n2):
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[mbs.AddMarker(MarkerNodePosition(nodeNumber=n1)),
                                                           mbs.AddMarker(MarkerNodePosition(nodeNumber=n2))]))
    pin(crank_nodes[-1], coupler_nodes[0])
    pin(coupler_nodes[-1], rocker_nodes[-1])
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[
        mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[GROUND, 0, 0])),
        mbs.AddMarker(MarkerNodePosition(nodeNumber=rocker_nodes[0]))]))

    sensors = [mbs.AddSensor(SensorNode(nodeNumber=nd, outputVariableType=exu.OutputVariableType.Coordinates,
                                        storeInternal=True, writeToFile=False))
               for nd in coupler_nodes + [rocker_nodes[-1], hub]]
    mbs.Assemble()
    period = 2.0 * math.pi / omega
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = TURNS * period
    ss.timeIntegration.numberOfSteps = TURNS * steps_per_turn
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = period / steps_per_turn
    ss.timeIntegration.newton.useModifiedNewton = True
    ss.timeIntegration.newton.relativeTolerance = 1e-7     # the default 1e-8 is below round-off at 32 elements
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse  # 3-6x faster than the default dense LU here
    ss.show.computationTime = False
    ss.show.statistics = False
    exu.SolveDynamic(mbs, ss)

    data = [np.array(mbs.GetSensorStoredData(s)) for s in sensors]
    t = data[0][:, 0]
    last = t >= (TURNS - 1) * period - 1e-12
    ref = [np.array(mbs.GetNodeParameter(nd, 'referenceCoordinates')) for nd in coupler_nodes + [rocker_nodes[-1]]]
    coords = [data[k][:, 1:5] + ref[k] for k in range(n + 2)]
    le = L_COUPLER / n
    sig, chord, tip = 0.0, 0.0, 0.0
    for k in range(n):
        r0, s0 = coords[k][:, 0:2], coords[k][:, 2:4]
        r1, s1 = coords[k + 1][:, 0:2], coords[k + 1][:, 2:4]
        for xi in (0.0, 0.25, 0.5, 0.75, 1.0):
            d1 = [6 * xi * xi - 6 * xi, le * (3 * xi * xi - 4 * xi + 1), 6 * xi - 6 * xi * xi, le * (3 * xi * xi - 2 * xi)]
            d2 = [12 * xi - 6, le * (6 * xi - 4), 6 - 12 * xi, le * (6 * xi - 2)]
            rx = (d1[0] * r0 + d1[1] * s0 + d1[2] * r1 + d1[3] * s1) / le
            rxx = (d2[0] * r0 + d2[1] * s0 + d2[2] * r1 + d2[3] * s1) / le**2
            cross = rx[:, 0] * rxx[:, 1] - rx[:, 1] * rxx[:, 0]
            kappa = cross / np.hypot(rx[:, 0], rx[:, 1])**3
            sig = max(sig, float(np.max(np.abs(E1 * FIBRE * kappa[last]))))
    ra, rb = coords[0][:, 0:2], coords[n][:, 0:2]
    if n % 2 == 0:
        rm = coords[n // 2][:, 0:2]
    else:                                    # mid-span inside the middle element (xi = 1/2)
        k = n // 2
        rm = (0.5 * coords[k][:, 0:2] + le / 8 * coords[k][:, 2:4] + 0.5 * coords[k + 1][:, 0:2]
              - le / 8 * coords[k + 1][:, 2:4])
    dv = rb - ra
    ch = (dv[:, 0] * (rm[:, 1] - ra[:, 1]) - dv[:, 1] * (rm[:, 0] - ra[:, 0])) / np.hypot(dv[:, 0], dv[:, 1])
    chord = float(np.max(np.abs(ch[last])))
    tipc = coords[n + 1][:, 0:2]
    hub_angle = data[n + 2][:, 3]
    for j in np.nonzero(last)[0]:
        _, (rcx, rcy), _, th4j, _, _, _ = rigid(omega * t[j], omega)
        w = -(tipc[j, 0] - rcx) * math.sin(th4j) + (tipc[j, 1] - rcy) * math.cos(th4j)
        tip = max(tip, abs(w))
    drift = float(np.max(np.abs(hub_angle - omega * t)))
    return {'sigma_b': sig, 'chord': chord, 'tip': tip, 'hub_angle_error': drift}


# ------------------------------------------------------------------ flexmech
DECK = """&run
  analysis = 'transient'
  title = 'Four-bar at {omega} rad/s, nonlinear, beta = 1e-5 s: the peer comparison'
/
&mechanism
  n_joints = 4
  joint_name = 'A', 'B', 'C', 'D'
  joint_type = 'clamp', 'pin', 'pin', 'ground_pin'
  joint_x(1) = 0.0, joint_y(1) = 0.0
  joint_x(4) = 10.0, joint_y(4) = 0.0
  n_links = 3
  link_name = 'crank', 'coupler', 'rocker'
  link_joint1 = 1, 2, 4
  link_joint2 = 2, 3, 3
  link_length = 5.0, 11.0, 10.5
  link_b = 3*0.25
  link_h = 3*1.0
  link_n_elements = 3*{n}
  driver_link = 1
  omega = {omega}
  theta0_deg = 0.0
  branch = 'open'
/
&transient
  method = 'bdf'
  rtol = {rtol}
  atol = 1.0e-7
  atol_rate = {atol_rate}
  revolutions = {turns}
  output_step_deg = 0.25
  output_rows = 'last_revolution'
  stress_columns = 'all'
  point_link = 'coupler'
  point_at = 0.5
  damping_beta = 1.0e-5
/
&effects
  stretching = T, curvature = T, material = F, rotary_inertia = F, coupling = T
/
"""


def flexmech_outputs(path, n):
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                if line.startswith('#') and line.split()[1:2] == ['t']:
                    header = line[1:].split()
                continue
            if line.strip():
                rows.append([float(v) for v in line.split()])
    col = {name: k for k, name in enumerate(header)}
    coupler = [col['sigma_b_e%d' % (n + k)] for k in range(1, n + 1)]
    sig = max(abs(r[c]) for r in rows for c in coupler)
    chord = max(abs(r[col['coupler_s0.5_chord']]) for r in rows)
    tip = max(abs(r[col['rocker_w_end']]) for r in rows)
    return {'sigma_b': sig, 'chord': chord, 'tip': tip}


def flexmech_case(exe, work, n, rtol, omega):
    tag = 'flexmech_%g_n%d_rtol%g' % (omega, n, rtol)
    deck = os.path.join(work, tag + '.nml')
    out = os.path.join(work, tag + '.out')
    with open(deck, 'w') as f:
        f.write(DECK.format(n=n, rtol=rtol, atol_rate=1.0e4 * rtol, omega=omega, turns=TURNS))
    cpu = run_timed([exe, deck, '-o', out])
    return cpu, (flexmech_outputs(out, n) if cpu is not None else None)


def exudyn_child(work, n, steps, omega):
    return run_child(__file__, os.path.join(work, 'exudyn_%g_n%d_s%d.json' % (omega, n, steps)), n, steps,
                     ['--omega', str(omega)])


def within(o, ref, tol):
    return all(abs(o[k] - ref[k]) <= tol * abs(ref[k]) for k in ('sigma_b', 'chord', 'tip'))


def main():
    def extra(ap):
        ap.add_argument('--omega', type=float, default=150.0)
        ap.add_argument('--repeats', type=int, default=3)
    a, work = start(extra, lambda a, n, steps: exudyn_case(n, steps, a.omega), 'fourbar_planar')
    if a is None:
        return
    om = a.omega
    print('Tennant four-bar, %g rad/s, beta 1e-5 s, geometrically nonlinear; peaks over turn %d of %d'
          % (om, TURNS, TURNS))
    print('outputs: sigma_b = coupler bending stress (psi), chord = coupler mid-span from the chord (in), '
          'tip = rocker-tip elastic displacement (in)')

    fm_ladder = [(n, r) for n in (1, 2, 4) for r in (1e-3, 5e-4, 1e-4)]
    ex_ladder = [(n, s) for n in (4, 8, 16) for s in (500, 1000, 2000)]
    fm_ref = flexmech_case(a.flexmech, work, 8, 1e-6, om)[1]
    ex_ref = exudyn_child(work, 32, 4000, om)[1]
    print('\nconverged (flexmech 8 elements per link, rtol 1e-6; Exudyn 32 elements per link, 4000 steps per turn):')
    print('%-10s %14s %14s %9s' % ('output', 'flexmech', 'Exudyn', 'diff'))
    for k in ('sigma_b', 'chord', 'tip'):
        print('%-10s %14.6g %14.6g %+8.2f%%' % (k, fm_ref[k], ex_ref[k], 100 * (ex_ref[k] / fm_ref[k] - 1)))

    def ladder(name, cases, run, ref, label):
        print('\n%s ladder (each against its own converged values):' % name)
        print('%-24s %9s %9s %9s %9s %s' % (label, 'CPU (s)', 'sigma_b', 'chord', 'tip', ''))
        cheapest = None
        for c in cases:
            cpu, o = run(*c)
            if o is None:
                print('%-24s %9s  (the run failed)' % (str(c), '-'))
                continue
            ok = within(o, ref, 0.01)
            print('%-24s %9.3f %+8.2f%% %+8.2f%% %+8.2f%% %s' % (
                str(c), cpu, *(100 * (o[k] / ref[k] - 1) for k in ('sigma_b', 'chord', 'tip')),
                'within 1 %' if ok else ''))
            if ok and (cheapest is None or cpu < cheapest[0]):
                cheapest = (cpu, c, o)
        return cheapest

    fm = ladder('flexmech', fm_ladder, lambda n, r: flexmech_case(a.flexmech, work, n, r, om), fm_ref,
                '(elements/link, rtol)')
    ex = ladder('Exudyn', ex_ladder, lambda n, s: exudyn_child(work, n, s, om), ex_ref,
                '(elements/link, steps/turn)')
    if fm is None or ex is None:
        print('\nno setting within 1 % for %s' % ('flexmech' if fm is None else 'Exudyn'))
        return
    # the two cheapest settings, run alternately
    fc, ec = [], []
    for _ in range(a.repeats):
        fc.append(flexmech_case(a.flexmech, work, *fm[1], om)[0])
        ec.append(exudyn_child(work, *ex[1], om)[0])
    fmed, emed = sorted(fc)[len(fc) // 2], sorted(ec)[len(ec) // 2]
    print('\ncheapest 1 %% settings: flexmech %s, Exudyn %s' % (fm[1], ex[1]))
    print('whole-process CPU, run alternately %d times (median): flexmech %.3f s (%.1f ms per turn), '
          'Exudyn %.3f s (%.1f ms per turn)' % (a.repeats, fmed, 1e3 * fmed / TURNS, emed, 1e3 * emed / TURNS))
    print('CPU ratio Exudyn / flexmech: %.2f' % (emed / fmed))
    print('%-10s %14s %14s %9s' % ('output', 'flexmech', 'Exudyn', 'diff'))
    for k in ('sigma_b', 'chord', 'tip'):
        print('%-10s %14.6g %14.6g %+8.2f%%' % (k, fm[2][k], ex[2][k], 100 * (ex[2][k] / fm[2][k] - 1)))

    # equal meshes, each code at the step setting of its cheapest 1 % run
    print('\nequal elements per link (flexmech rtol %g, Exudyn %d steps per turn): whole-process CPU per turn'
          % (fm[1][1], ex[1][1]))
    print('%-10s %14s %14s %14s' % ('n/link', 'flexmech (ms)', 'Exudyn (ms)', 'Exudyn/flexmech'))
    prev = None
    for n in (2, 4, 8, 16, 32):
        fcpu = flexmech_case(a.flexmech, work, n, fm[1][1], om)[0]
        ecpu = exudyn_child(work, n, ex[1][1], om)[0] if n >= 8 else None
        growth = '' if prev is None or fcpu is None else '  (flexmech x%.2f per doubling)' % (fcpu / prev)
        prev = fcpu
        print('%-10d %14s %14s %14s%s' % (
            n, '-' if fcpu is None else '%.1f' % (1e3 * fcpu / TURNS),
            '-' if ecpu is None else '%.1f' % (1e3 * ecpu / TURNS),
            '-' if (ecpu is None or fcpu is None) else '%.2f' % (ecpu / fcpu), growth))


if __name__ == '__main__':
    main()
