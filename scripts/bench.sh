#!/usr/bin/env bash
# Benchmark: simbob against the bare ODE loop (bench/bare_ode) and MuJoCo (mujoco-testspeed) on
# the same scene of N boxes resting on a plane, N = 10, 100, 1000, 5000; plus simbob's scene
# load time for 10,000 bodies and its CSV writing speed. See bench/README.md.
#
# Usage: scripts/bench.sh [--quick]
#   --quick   about a minute (shorter runs, fewer repetitions) instead of about 5-10 minutes
# Installs what the measurements need (apt: libmujoco-samples for mujoco-testspeed,
# libmujoco-dev for bench/peers, time for GNU time), builds with scripts/build.sh, prints a
# table of medians and saves it in bench/results/<date>-<machine>.csv (every single run in
# ...-runs.csv beside it).
set -euo pipefail
cd "$(dirname "$0")/.."

quick=()
for arg in "$@"; do
  case "$arg" in
    --quick) quick=(--quick) ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench.sh: unknown option '$arg' (try --help)" >&2; exit 64 ;;
  esac
done

# What only the benchmark needs, from Debian's packages (before the build: bench/peers's
# peers_mujoco is built only where libmujoco-dev is installed).
need=()
command -v mujoco-testspeed >/dev/null || need+=(libmujoco-samples)
[ -f /usr/include/mujoco/mujoco.h ] || need+=(libmujoco-dev)
[ -x /usr/bin/time ] || need+=(time)
command -v python3 >/dev/null || need+=(python3)
if [ ${#need[@]} -gt 0 ]; then
  echo "bench.sh: installing ${need[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  if ! { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null; }; then
    echo "bench.sh: could not install ${need[*]}" >&2
  fi
fi
bash scripts/build.sh
[ -x build/bench/bare_ode ] || { echo "bench.sh: build/bench/bare_ode was not built (SIMBOB_BENCH off?)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench.sh: /usr/bin/time (package 'time') is needed" >&2; exit 1; }
mujoco=()
if command -v mujoco-testspeed >/dev/null; then
  mujoco=(--mujoco "$(command -v mujoco-testspeed)")
else
  echo "bench.sh: mujoco-testspeed missing; running without MuJoCo" >&2
fi

exec python3 bench/run_bench.py --simbob build/simbob --bare build/bench/bare_ode "${mujoco[@]}" "${quick[@]}" \
  --results bench/results
