# Yade side of the CPM peer comparison (run by run.sh as `yade -n -x yade_uniax.py SPHERES LOADING SPEED OUT`):
# the uniaxial test of Šmilauer's "Simulation setup" with Yade's CpmMat on mesocrack's CPM specimen.
#   SPHERES  `id x y z r tag` (tag 1: negative-end support, 2: positive-end support, 0: inside)
#   LOADING  tension | compression
#   SPEED    [m/s] of each support, moving apart (tension) or together, as the mesocrack scenes' groups
#   OUT      CSV written here: step, time, strain, stress, lateral_strain (signs: positive in the loading sense,
#            lateral expansion positive); a last comment line holds the stepping loop's wall time.
# Straining as in mesocrack's scene: the support spheres' z velocity is prescribed (blockedDOFs 'z'), all else
# free; stress = mean of both supports' axial reactions over the bounding box cross-section; lateral strain =
# slope of the regression of Δx on x and Δy on y over the spheres of the middle half of the length.
import sys, time, math
from yade import O
from yade.wrapper import *
from yade import utils
from yade.minieigenHP import Vector3

spheres, loading, speed, out = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
params = dict(young=24e9, poisson=0.2, sigmaT=3.5e6, frictionAngle=math.atan(0.8), epsCrackOnset=1e-4,
              relDuctility=30, density=4800)
for a in sys.argv[5:]:  # key=value overrides of CpmMat attributes
    k, v = a.split('=')
    params[k] = float(v)
R_I, DAMPING, SAFETY = 1.5, 0.4, 0.8

mat = O.materials.append(CpmMat(**params))
rows = [l.split() for l in open(spheres) if l.strip() and not l.startswith('#')]
ids, tags = [], {}
for r in rows:
    i = O.bodies.append(utils.sphere((float(r[1]), float(r[2]), float(r[3])), float(r[4]), material=mat))
    ids.append(i)
    tags[i] = int(r[5])
lo_ids = [i for i in ids if tags[i] == 1]
hi_ids = [i for i in ids if tags[i] == 2]
mean_z = lambda m: sum(O.bodies[i].state.pos[2] for i in m) / len(m)
l0 = mean_z(hi_ids) - mean_z(lo_ids)
zmid = 0.5 * (mean_z(hi_ids) + mean_z(lo_ids))
inner = [i for i in ids if abs(O.bodies[i].state.pos[2] - zmid) < 0.25 * l0]
x0 = {i: Vector3(O.bodies[i].state.pos) for i in ids}
bb = [[min(O.bodies[i].state.pos[k] - O.bodies[i].shape.radius for i in ids),
       max(O.bodies[i].state.pos[k] + O.bodies[i].shape.radius for i in ids)] for k in range(3)]
area = (bb[0][1] - bb[0][0]) * (bb[1][1] - bb[1][0])
sense = 1.0 if loading == 'tension' else -1.0
v = speed * sense
for i in lo_ids:
    O.bodies[i].state.blockedDOFs = 'z'
    O.bodies[i].state.vel = (0, 0, -v)
for i in hi_ids:
    O.bodies[i].state.blockedDOFs = 'z'
    O.bodies[i].state.vel = (0, 0, v)

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=R_I, label='aabb')]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=R_I, label='geom')],
                    [Ip2_CpmMat_CpmMat_CpmPhys()], [Law2_ScGeom_CpmPhys_Cpm()]),
    GlobalStiffnessTimeStepper(timestepSafetyCoefficient=SAFETY, timeStepUpdateInterval=10),
    NewtonIntegrator(damping=DAMPING),
]
O.dt = 1e-9
O.step()  # cohesive contacts within R_I (Šmilauer: R_I serves only to create them), then R_I = 1
aabb.aabbEnlargeFactor = -1
geom.interactionDetectionFactor = 1

def slope(k):
    m0 = sum(x0[i][k] for i in inner) / len(inner)
    md = sum(O.bodies[i].state.pos[k] - x0[i][k] for i in inner) / len(inner)
    sxy = sum((x0[i][k] - m0) * (O.bodies[i].state.pos[k] - x0[i][k] - md) for i in inner)
    sxx = sum((x0[i][k] - m0) ** 2 for i in inner)
    return sxy / sxx

def sample():
    rp = -sum(O.forces.f(i)[2] for i in hi_ids)
    rm = -sum(O.forces.f(i)[2] for i in lo_ids)
    l = mean_z(hi_ids) - mean_z(lo_ids)
    return (O.iter, O.time, sense * (l - l0) / l0, sense * 0.5 * (rp - rm) / area, 0.5 * (slope(0) + slope(1)))

with open(out, 'w') as f:
    f.write('step,time,strain,stress,lateral_strain\n')
    peak, wall, steps, chunk = 0.0, 0.0, 0, 100
    while True:
        t0 = time.time()
        O.run(chunk, True)
        wall += time.time() - t0
        steps += chunk
        s = sample()
        f.write(','.join('%.12g' % x for x in s) + '\n')
        peak = max(peak, s[3])
        stop = 0.15 if loading == 'tension' else 0.8
        if (peak > 0 and s[3] < stop * peak) or O.iter > 400000:
            break
    f.write('# wall_seconds=%.6g steps=%d dt=%.6g interactions=%d\n' % (wall, steps, O.dt, len(O.interactions)))
