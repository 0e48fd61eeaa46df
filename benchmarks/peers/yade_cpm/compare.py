#!/usr/bin/python3
"""Key figures of two uniaxial stress-strain curves (mesocrack's history CSV and yade_uniax.py's CSV), side by
side: E (secant between 25 % and 50 % of the peak, as `mesocrack summary`), the strength and the strain at the
peak, their relative differences, and the wall time per step of each. Usage:
  compare.py LOADING MESOCRACK_CSV MESOCRACK_WALL_S MESOCRACK_STEPS YADE_CSV"""
import csv, sys


def curve_mesocrack(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    head = [h.split(' [')[0] for h in rows[0]]
    col = {h: i for i, h in enumerate(head)}
    data = [[float(x) for x in r] for r in rows[1:] if r]
    return ([r[col['uniaxial.strain']] for r in data], [r[col['uniaxial.stress']] for r in data],
            [r[col['dt']] for r in data][-1])


def curve_yade(path):
    strain, stress, meta = [], [], {}
    for line in open(path):
        if line.startswith('step'):
            continue
        if line.startswith('#'):
            meta = dict(kv.split('=') for kv in line[1:].split())
            continue
        r = [float(x) for x in line.split(',')]
        strain.append(r[2]), stress.append(r[3])
    return strain, stress, meta


def figures(strain, stress):
    k = max(range(len(stress)), key=lambda i: stress[i])
    peak = stress[k]

    def at(level):  # first pre-peak crossing, interpolated
        for i in range(1, k + 1):
            if stress[i - 1] < level <= stress[i]:
                f = (level - stress[i - 1]) / (stress[i] - stress[i - 1])
                return strain[i - 1] + f * (strain[i] - strain[i - 1])
        return float('nan')
    e = 0.25 * peak / (at(0.5 * peak) - at(0.25 * peak))
    return e, peak, strain[k]


def main():
    loading, mc_csv, mc_wall, mc_steps, y_csv = sys.argv[1:6]
    ms, mq, mdt = curve_mesocrack(mc_csv)
    ys, yq, meta = curve_yade(y_csv)
    m, y = figures(ms, mq), figures(ys, yq)
    strength = 'f_t' if loading == 'tension' else 'f_c'
    print(f'\n### CPM uniaxial {loading}: mesocrack vs Yade 2023.02a (same specimen, parameters, straining)\n')
    print('| figure | mesocrack | Yade | difference |')
    print('|---|---|---|---|')
    for name, a, b, unit, scale in [('E', m[0], y[0], 'GPa', 1e-9), (strength, m[1], y[1], 'MPa', 1e-6),
                                    ('strain at peak', m[2], y[2], '1e-3', 1e3)]:
        print(f'| {name} [{unit}] | {a * scale:.4g} | {b * scale:.4g} | {100 * (a - b) / b:+.2f} % |')
    mw, msteps = float(mc_wall), int(mc_steps)
    yw, ysteps = float(meta['wall_seconds']), int(meta['steps'])
    print(f'| steps to the stop | {msteps} | {ysteps} | |')
    print(f'| dt [s] | {mdt:.4g} | {float(meta["dt"]):.4g} | |')
    print(f'| wall time per step [ms] | {1e3 * mw / msteps:.4g} | {1e3 * yw / ysteps:.4g} | '
          f'Yade/mesocrack = {(yw / ysteps) / (mw / msteps):.2f} |')
    return m, y


if __name__ == '__main__':
    main()
