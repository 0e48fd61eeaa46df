# ESyS-Particle (Debian's 2.3.5) on the shared bonded specimen, for peers_bench.py, on WORKERS processes:
#   mpirun -np WORKERS+1 esysparticle esys_rotbond.py GEO STEPS WORKERS   (a master beside the workers; the domain
#   split along z)
# GEO is the specimen with its bonds as ESyS geometry (peers_bench.py writes it: every pair closer than
# 1.05 (r_i + r_j) a connection of tag 0). Rotational spheres; bonds carrying normal and shear force, bending and
# twisting moment (RotBond, ESyS's parallel bond), made unbreakable: RotBond's rest length is r_i + r_j, so a bond
# across a gap starts stretched (a throughput run, no fracture). Unbonded pairs touch by friction; local damping
# 0.2. The bottom layer (tag 1) is bonded to a fixed wall, the top layer (tag 2) to a wall moved down each step so
# that the strain reaches 1e-4 at the end. 10 steps warm up, then STEPS are timed. Prints one RESULT line.
import math
import sys
import time

from esys.lsm import *
from esys.lsm.util import BoundingBox, Vec3

geo_path, steps, workers = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
WARM_UP = 10
E, DENSITY, STRAIN = 30e9, 2600.0, 1e-4

radii, z_lo, z_hi = [], float("inf"), -float("inf")
with open(geo_path) as f:
    lines = f.read().split("\n")
first = lines.index("Simple") + 2
count = int(lines[first - 1])
for line in lines[first:first + count]:
    x, y, z, r = (float(v) for v in line.split()[:4])
    radii.append(r)
    z_lo, z_hi = min(z_lo, z - r), max(z_hi, z + r)
r_min, r_max = min(radii), max(radii)

sim = LsmMpi(numWorkerProcesses=workers, mpiDimList=[1, 1, workers])
sim.initNeighbourSearch(particleType="RotSphere", gridSpacing=2.5 * r_max, verletDist=0.2 * r_min)
dt = 0.3 * r_min * math.sqrt(DENSITY / E)
sim.setTimeStepSize(dt)
sim.setNumTimeSteps(WARM_UP + steps)
sim.setSpatialDomain(BoundingBox(Vec3(-0.01, -0.01, z_lo - 0.01), Vec3(0.11, 0.11, z_hi + 0.01)))
sim.readGeometry(geo_path)
for tag in (0, 1, 2):
    sim.setParticleDensity(tag=tag, mask=-1, Density=DENSITY)
unbreakable = 1e15
sim.createInteractionGroup(RotBondPrms(name="bonds", normalK=E, shearK=0.25 * E, torsionK=0.1 * E, bendingK=0.1 * E,
                                       normalBrkForce=unbreakable, shearBrkForce=unbreakable,
                                       torsionBrkForce=unbreakable, bendingBrkForce=unbreakable, tag=0, scaling=True))
sim.createInteractionGroup(RotFrictionPrms(name="friction", normalK=E, dynamicMu=0.5, staticMu=0.6, shearK=0.25 * E,
                                           scaling=True))
sim.createExclusion("bonds", "friction")
sim.createInteractionGroup(LocalDampingPrms(name="damping", viscosity=0.2))
sim.createInteractionGroup(RotLocalDampingPrms(name="rotational_damping", viscosity=0.2))
sim.createWall(name="bottom", posn=Vec3(0, 0, z_lo), normal=Vec3(0, 0, 1))
sim.createWall(name="top", posn=Vec3(0, 0, z_hi), normal=Vec3(0, 0, -1))
sim.createInteractionGroup(NRotBondedWallPrms(name="bottom_bonds", wallName="bottom", normalK=E * r_min, particleTag=1))
sim.createInteractionGroup(NRotBondedWallPrms(name="top_bonds", wallName="top", normalK=E * r_min, particleTag=2))
step = Vec3(0, 0, -STRAIN * (z_hi - z_lo) / (WARM_UP + steps))
for _ in range(WARM_UP):
    sim.moveWallBy("top", step)
    sim.runTimeStep()
start = time.time()
for _ in range(steps):
    sim.moveWallBy("top", step)
    sim.runTimeStep()
wall = time.time() - start
n = sim.getNumParticles()
print("RESULT engine=esys model=rotbond particles=%d workers=%d steps=%d wall_s=%.3f particle_steps_per_s=%.5g"
      % (n, workers, steps, wall, n * steps / wall))
sim.exit()
