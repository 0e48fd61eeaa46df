# Yade (Debian's 2023.02a) on the shared bonded specimen (benchmarks/specimens/README.md), for peers_bench.py:
#   yade -n -j1 -x yade_bonded.py SPHERES MODEL STEPS
# MODEL "cohfrict": cohesive-frictional bonds carrying normal and shear force, bending and twisting moment (Yade's
# counterpart of a parallel bond); "cpm": Yade's concrete particle model (the counterpart of ours). The bonds are
# every pair closer than 1.05 (r_i + r_j): Yade makes them in the first step from an enlarged detection range,
# which is then set back. CohFrict measures a bond's stretch from touching, not from its first length, so a bond
# across a gap would start stretched and break: its strengths are made unbreakable (a throughput run, no fracture).
# The bottom layer (tag 1) is held, the top one (tag 2) moves down so that the strain reaches 1e-4 at the end; 10
# steps warm up, then STEPS are timed (the stepping loop alone). Prints one line: "RESULT ... particle_steps_per_s=".
import math
import sys
import time

spheres_path, model, steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
WARM_UP, REACH = 10, 1.05
E, DENSITY, HEIGHT, STRAIN = 30e9, 2600.0, 0.2, 1e-4

if model == "cohfrict":
    material = CohFrictMat(young=E, poisson=0.25, density=DENSITY, frictionAngle=math.atan(0.5), isCohesive=True,
                           normalCohesion=1e15, shearCohesion=1e15, momentRotationLaw=True, alphaKr=2.0,
                           alphaKtw=2.0, etaRoll=-1, etaTwist=-1)
    geometry = Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=REACH)
    physics = Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True)
    law = Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True)
elif model == "cpm":
    material = CpmMat(young=E, poisson=0.2, density=DENSITY, frictionAngle=math.atan(0.8), sigmaT=3.5e6,
                      epsCrackOnset=1e-4, relDuctility=30)
    geometry = Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=REACH)
    physics = Ip2_CpmMat_CpmMat_CpmPhys()
    law = Law2_ScGeom_CpmPhys_Cpm()
else:
    sys.exit("yade_bonded.py: MODEL must be cohfrict or cpm, not '%s'" % model)

mat = O.materials.append(material)
tag_of, r_min = {}, float("inf")
with open(spheres_path) as f:
    for line in f:
        i, x, y, z, r, tag = line.split()
        body = O.bodies.append(sphere((float(x), float(y), float(z)), float(r), material=mat))
        tag_of[body] = int(tag)
        r_min = min(r_min, float(r))

bounds = Bo1_Sphere_Aabb(aabbEnlargeFactor=REACH)
O.engines = [ForceResetter(), InsertionSortCollider([bounds]), InteractionLoop([geometry], [physics], [law]),
             NewtonIntegrator(damping=0.2)]
O.dt = 0.3 * r_min * math.sqrt(DENSITY / E)
speed = STRAIN * HEIGHT / ((WARM_UP + steps) * O.dt)
for body, tag in tag_of.items():
    if tag:
        O.bodies[body].state.blockedDOFs = "xyzXYZ"
        O.bodies[body].state.vel = Vector3(0, 0, -speed if tag == 2 else 0)

O.step()  # the bonds, from the enlarged range
bounds.aabbEnlargeFactor = 1.0
geometry.interactionDetectionFactor = 1.0
bonds = O.interactions.countReal()
O.run(WARM_UP - 1, True)
start = time.time()
O.run(steps, True)
wall = time.time() - start
n = len(O.bodies)
print("RESULT engine=yade model=%s particles=%d bonds=%d threads=%d steps=%d wall_s=%.3f particle_steps_per_s=%.5g"
      % (model, n, bonds, O.numThreads, steps, wall, n * steps / wall))
