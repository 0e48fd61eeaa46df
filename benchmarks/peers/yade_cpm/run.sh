#!/bin/bash
# CPM peer comparison with Yade (Debian package `yade`): the specimen of scenes/cpm_uniax_*.toml
# (scenes/specimens/cpm_1x1x2.spheres) strained in tension and in compression by Yade's CpmMat (yade_uniax.py)
# and by mesocrack's scenes, with the parameters of Yade's public CpmMat — no compressive hardening (Yade's
# epsSoft ≥ 0), the linear yield surface (23) also in compression — and the same straining, each on one
# thread; prints both curves' key figures (E, f_t or f_c, strain at peak), their differences and the wall time
# per step of each.
#   run.sh [MESOCRACK_BINARY] [WORK_DIR]      (defaults: build/mesocrack of the source tree, a fresh temp dir)
# Skipped, with a message and exit status 0, when yade is not on PATH.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
if ! command -v yade >/dev/null 2>&1; then
  echo "yade_cpm: skipped (yade is not on PATH; 'apt-get install yade' provides Yade 2023.02a)"
  exit 0
fi
bin=${1:-$root/build/mesocrack}
work=${2:-$(mktemp -d /tmp/yade_cpm.XXXXXX)}
[ -x "$bin" ] || { echo "yade_cpm: mesocrack binary '$bin' not found; give it as the first argument" >&2; exit 1; }
mkdir -p "$work"
spheres=$root/scenes/specimens/cpm_1x1x2.spheres
echo "yade_cpm: working in $work"
for loading in tension compression; do
  # Each support's speed, as the scene's groups move them (0.05 /s and 0.5 /s over the supports' distance).
  if [ $loading = tension ]; then speed=2.25e-3; else speed=22.5e-3; fi
  log=$("$bin" run "$root/scenes/cpm_uniax_$loading.toml" -o "$work/mc_$loading.h5" --threads 1 \
    --set "contacts[0].compression_hardening=false" --set "contacts[0].compression_yield=linear" \
    --set "bonds.crack_log=false" 2>&1 | tail -1)
  steps=$(echo "$log" | sed -n 's/.*after \([0-9]*\) steps.*/\1/p')
  wall=$(echo "$log" | sed -n 's/.*, \([0-9.]*\) s wall time.*/\1/p')
  OMP_NUM_THREADS=1 yade -j1 -n -x "$here/yade_uniax.py" "$spheres" $loading $speed "$work/yade_$loading.csv" \
    >"$work/yade_$loading.log" 2>&1
  /usr/bin/python3 "$here/compare.py" $loading "$work/mc_${loading}_history.csv" "$wall" "$steps" "$work/yade_$loading.csv"
done
