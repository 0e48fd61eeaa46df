"""The shared specimen as the peers read it (benchmarks/specimens/README.md): ESyS-Particle geometry (LSMGeometry
1.2) with its spheres, their tags and, as connections of tag 0, the bonds, every pair closer than 1.05 (r_i + r_j);
and a LIGGGHTS granular data file without bonds."""
import numpy as np

REACH = 1.05


def bond_pairs(x, r):
    """Every pair (i < j) with |x_i − x_j| ≤ REACH (r_i + r_j), by rows of the distance matrix in blocks."""
    pairs = []
    for lo in range(0, len(x), 2000):
        d = np.linalg.norm(x[lo:lo + 2000, None, :] - x[None, :, :], axis=2)
        i, j = np.nonzero(d <= REACH * (r[lo:lo + 2000, None] + r[None, :]))
        keep = i + lo < j
        pairs.append(np.c_[i[keep] + lo, j[keep]])
    return np.vstack(pairs)


def write_geo(spheres_path, geo_path):
    s = np.loadtxt(spheres_path)
    ids, x, r, tag = s[:, 0].astype(int), s[:, 1:4], s[:, 4], s[:, 5].astype(int)
    pairs = bond_pairs(x, r)
    lo, hi = (x - r[:, None]).min(0), (x + r[:, None]).max(0)
    margin = 0.02 * (hi - lo)
    with open(geo_path, "w") as f:
        f.write("LSMGeometry 1.2\nBoundingBox %s\nPeriodicBoundaries 0 0 0\nDimension 3D\n"
                % " ".join("%.9e" % v for v in np.r_[lo - margin, hi + margin]))
        f.write("BeginParticles\nSimple\n%d\n" % len(ids))
        for k in range(len(ids)):
            f.write("%.9e %.9e %.9e %.9e %d %d\n" % (x[k, 0], x[k, 1], x[k, 2], r[k], ids[k], tag[k]))
        f.write("EndParticles\nBeginConnect\n%d\n" % len(pairs))
        for a, b in pairs:
            f.write("%d %d 0\n" % (ids[a], ids[b]))
        f.write("EndConnect\n")
    return len(pairs)


def write_liggghts_data(spheres_path, data_path):
    """The shared specimen as a LIGGGHTS granular data file (id type diameter density x y z; type = tag + 1), no
    bonds. Returns the least radius."""
    s = np.loadtxt(spheres_path)
    ids, x, r, tag = s[:, 0].astype(int), s[:, 1:4], s[:, 4], s[:, 5].astype(int)
    lo, hi = (x - r[:, None]).min(0), (x + r[:, None]).max(0)
    margin = 0.02 * (hi - lo)
    with open(data_path, "w") as f:
        f.write("LIGGGHTS data: the shared specimen\n\n%d atoms\n3 atom types\n\n" % len(ids))
        for d, axis in enumerate("xyz"):
            f.write("%.9e %.9e %slo %shi\n" % (lo[d] - margin[d], hi[d] + margin[d], axis, axis))
        f.write("\nAtoms\n\n")
        for k in range(len(ids)):
            f.write("%d %d %.9e 2600 %.9e %.9e %.9e\n" % (ids[k] + 1, tag[k] + 1, 2 * r[k], x[k, 0], x[k, 1], x[k, 2]))
    return float(r.min())
