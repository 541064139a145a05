"""flexmech's general_transient analysis against Exudyn on a flexible planar two-link arm
(doc/general_mechanism.md, "Verification").

The arm of inputs/general_two_link_arm.nml in both codes: upper arm 20 in from the grounded shoulder,
forearm 16 in to the free tip, circular aluminium bars of radius 0.25 in (E = 10.87e6 psi,
rho = 2.536e-4 lb s^2/in^4), linear material, no rotary inertia (the peer's cable element has none),
geometrically nonlinear; stiffness-proportional damping beta = 1e-5 s (zeta = 3.5e-4 in the first
mode).  Both joints are driven from rest by the smooth spin-up profile (shoulder to 10 rad/s, elbow
to -15 rad/s, over 0.3 s): theta = w T (tau^2/2 - (1 - cos 2 pi tau)/(4 pi^2)), tau = t/T, then
w (T/2 + t - T).  The driven joints clamp the link ends: the shoulder to the ground, the forearm's
first end to the upper arm's last, at the prescribed angles.

flexmech: the consistent element, two elements a link (and four, the mesh check), DLSODE's BDF.
Exudyn: ANCFCable2D elements (cubic Hermite positions), generalized-alpha; each driven joint a
generic joint (x, y and the rotation about z held) whose rotation offset is the joint angle.

Output: the tip's elastic deflection normal to the rigid forearm (flexmech's fore_v_end) every
5 ms over 0.5 s; the figure of merit is the largest difference over the history against the peak
|deflection|.

Usage: python general_two_link.py --flexmech build/bin/flexmech --work build/peers
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), 'lib'))
from peer_run import run_child, run_timed, start  # noqa: E402

L_UPPER, L_FORE, RADIUS = 20.0, 16.0, 0.25
E1, RHO, BETA = 10.87e6, 2.536e-4, 1.0e-5
AREA = math.pi * RADIUS**2
INERTIA = math.pi * RADIUS**4 / 4.0
RATES, SPINUP = (10.0, -15.0), 0.3
T_END, DT_OUT = 0.5, 0.005
DECK = 'inputs/general_two_link_arm.nml'
HUB_MASS = 1.0e-9          # the drive hubs' mass (lb s^2/in) and inertia (lb s^2 in): 1e-6 of the arm's


def spinup(w, t):
    """The spin-up profile's angle (rad) at t (module linkage's driver_angle)."""
    if t <= 0.0:
        return 0.0
    if t < SPINUP:
        tau = t / SPINUP
        return w * SPINUP * (0.5 * tau**2 - (1.0 - math.cos(2.0 * math.pi * tau)) / (4.0 * math.pi**2))
    return w * (0.5 * SPINUP + t - SPINUP)


def exudyn_case(n, steps):
    import numpy as np
    import exudyn as exu
    from exudyn.itemInterface import (NodePoint2DSlope1, ObjectANCFCable2D, MarkerBodyRigid,
                                      ObjectJointGeneric, SensorNode, NodePointGround, NodeRigidBody2D,
                                      ObjectRigidBody2D, MarkerNodeCoordinate, CoordinateConstraint)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()

    def link(x0, length):
        nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[x0 + length * k / n, 0.0, 1.0, 0.0]))
                 for k in range(n + 1)]
        cables = [mbs.AddObject(ObjectANCFCable2D(
            length=length / n, massPerLength=RHO * AREA, bendingStiffness=E1 * INERTIA, axialStiffness=E1 * AREA,
            bendingDamping=BETA * E1 * INERTIA, axialDamping=BETA * E1 * AREA, nodeNumbers=[nodes[k], nodes[k + 1]]))
            for k in range(n)]
        return nodes, cables

    upper_nodes, upper = link(0.0, L_UPPER)
    fore_nodes, fore = link(L_UPPER, L_FORE)

    ground_node = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0))

    def hub(x):
        """A light rigid hub at (x, 0): node, body and the markers of its three coordinates."""
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0, 0]))
        body = mbs.AddObject(ObjectRigidBody2D(mass=HUB_MASS, inertia=HUB_MASS, nodeNumber=node))
        return body, [mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=k)) for k in range(3)]

    def clamp(body_a, pos_a, body_b, pos_b):
        mbs.AddObject(ObjectJointGeneric(markerNumbers=[
            mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_a, localPosition=pos_a)),
            mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_b, localPosition=pos_b))], constrainedAxes=[1, 1, 0, 0, 0, 1]))

    def prescribed(m0, m1, w):
        """The angle coordinate of m1 held at that of m0 plus the spin-up angle."""
        mbs.AddObject(CoordinateConstraint(markerNumbers=[m0, m1],
                                           offsetUserFunction=lambda mbs, t, item, offset: spinup(w, t)))

    # shoulder: hub 1 held at the origin, turned by the shoulder's angle, the upper arm clamped to it
    shoulder, ms = hub(0.0)
    for k in range(2):
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, ms[k]]))
    prescribed(mg, ms[2], RATES[0])
    clamp(shoulder, [0, 0, 0], upper[0], [0, 0, 0])
    # elbow: hub 2 clamped to the upper arm's end; hub 3 on its point, turned by the elbow's angle
    # relative to it, the forearm clamped to hub 3
    arm_end, m2 = hub(L_UPPER)
    clamp(upper[-1], [L_UPPER / n, 0, 0], arm_end, [0, 0, 0])
    elbow, m3 = hub(L_UPPER)
    for k in range(2):
        mbs.AddObject(CoordinateConstraint(markerNumbers=[m2[k], m3[k]]))
    prescribed(m2[2], m3[2], RATES[1])
    clamp(elbow, [0, 0, 0], fore[0], [0, 0, 0])
    tip = mbs.AddSensor(SensorNode(nodeNumber=fore_nodes[-1], outputVariableType=exu.OutputVariableType.Position,
                                   storeInternal=True, writeToFile=False))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = T_END
    ss.timeIntegration.numberOfSteps = steps
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = DT_OUT
    ss.timeIntegration.newton.relativeTolerance = 1e-7
    ss.timeIntegration.newton.absoluteTolerance = 1e-6   # the residual at rest is zero: relative errors alone never converge there
    ss.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    ss.show.computationTime = False
    ss.show.statistics = False
    exu.SolveDynamic(mbs, ss)
    data = np.array(mbs.GetSensorStoredData(tip))
    out = []
    for row in data:
        t = float(row[0])
        th1, th12 = spinup(RATES[0], t), spinup(RATES[0], t) + spinup(RATES[1], t)
        rx = L_UPPER * math.cos(th1) + L_FORE * math.cos(th12)
        ry = L_UPPER * math.sin(th1) + L_FORE * math.sin(th12)
        out.append((t, -(row[1] - rx) * math.sin(th12) + (row[2] - ry) * math.cos(th12)))
    return out


def flexmech_case(exe, work, n):
    deck = os.path.join(work, 'arm_n%d.nml' % n)
    out = os.path.join(work, 'arm_n%d.out' % n)
    with open(DECK) as f:
        text = f.read().replace('link_n_elements = 2, 2', 'link_n_elements = %d, %d' % (n, n))
    with open(deck, 'w') as f:
        f.write(text)
    cpu = run_timed([exe, deck, '-o', out])
    if cpu is None:
        return None, None
    names, rows = None, []
    with open(out) as f:
        lines = f.read().splitlines()
    for k, line in enumerate(lines):
        if line.startswith('#') or not line.strip():
            continue
        if names is None:
            names = lines[k - 1][1:].split()
        rows.append([float(v) for v in line.split()])
    j = names.index('fore_v_end')
    return cpu, [(r[0], r[j]) for r in rows]


def compare(a, b):
    """Largest difference of two histories at the common times, against b's peak |value|."""
    bt = {round(t, 9): v for t, v in b}
    diffs = [abs(v - bt[round(t, 9)]) for t, v in a if round(t, 9) in bt]
    peak = max(abs(v) for _, v in b)
    return max(diffs) / peak, peak, len(diffs)


def main():
    a, work = start(lambda ap: None, lambda a, n, steps: exudyn_case(n, steps), 'general_two_link')
    if a is None:
        return
    print('flexible two-link arm, shoulder and elbow spun up to 10 and -15 rad/s over 0.3 s; tip deflection '
          'normal to the rigid forearm every 5 ms over 0.5 s')
    runs = {}
    for n in (2, 4):
        cpu, h = flexmech_case(a.flexmech, work, n)
        runs['flexmech n=%d' % n] = h
        print('flexmech %d elements a link: CPU %.2f s, peak |tip deflection| %.5f in'
              % (n, cpu, max(abs(v) for _, v in h)))
    for n, steps in ((8, 5000), (16, 10000)):
        cpu, h = run_child(__file__, os.path.join(work, 'exudyn_n%d_s%d.json' % (n, steps)), n, steps, [])
        if h is None:
            print('Exudyn %d elements, %d steps: the run failed' % (n, steps))
            return
        runs['Exudyn n=%d' % n] = [tuple(x) for x in h]
        print('Exudyn %d elements a link, %d steps: CPU %.2f s, peak |tip deflection| %.5f in'
              % (n, steps, cpu, max(abs(v) for _, v in h)))
    ref = runs['Exudyn n=16']
    for name in ('flexmech n=2', 'flexmech n=4', 'Exudyn n=8'):
        rel, peak, m = compare(runs[name], ref)
        print('%-14s against Exudyn n=16: largest difference %.3f %% of the peak %.5f in (%d times)'
              % (name, 100 * rel, peak, m))


if __name__ == '__main__':
    main()
