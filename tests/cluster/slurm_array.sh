#!/usr/bin/env bash
# A real Slurm job array runs simbob: a single-node cluster on 127.0.0.1 (tests/cluster/slurm.sh)
# takes an `sbatch --array=0-4` script whose task I runs `simbob run` on scene I into a file
# named by $SLURM_ARRAY_TASK_ID; every task's trajectory must be byte-identical to a local run
# of the same command, and every task must have run under Slurm as a task of the same array.
# One task runs a socket scene (socket_robot.xml) whose controller simbob starts itself, for the
# golden's 10 s: its trajectory must equal golden/socket_robot.csv, its controller's log must
# lie beside its CSV, and the controller must not outlive the task.
#
#   bash tests/cluster/slurm_array.sh /path/to/simbob /path/to/repo
#
# Exit 77 (skip) with the reason when Slurm cannot be installed or started here.
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source "$HERE/../cli/lib.sh"
source "$HERE/slurm.sh"
cli_setup "$@"

SCENE_LIST=(pendulum bounce chain box_stack socket_robot)
DURATION=2
SOCKET_TASK=4          # socket_robot: simbob starts its Python client (its Controller)
SOCKET_DURATION=10     # as golden/socket_robot.csv
duration_of() { [[ $1 == "$SOCKET_TASK" ]] && echo $SOCKET_DURATION || echo $DURATION; }

check "a single-node Slurm cluster comes up on 127.0.0.1"
t0=$SECONDS
if ! slurm_start "$WORK/cluster"; then
  printf 'SKIP: no Slurm cluster here: %s\n' "$SLURM_SKIP_REASON"
  exit 77
fi
say "cluster up after $((SECONDS - t0)) s"

check "slurmctld and slurmd listen on 127.0.0.1 only (when the host name resolves to loopback only)"
if [[ "$SLURM_LOOPBACK_ONLY" != 1 ]]; then
  say "note: the host name $(hostname) does not resolve to loopback only: the daemons listen on every address"
elif command -v ss >/dev/null; then
  ss -H -ltnp >"$WORK/listen"
  for pid in "${SLURM_PIDS[@]:1}"; do  # [0] is munged (a Unix socket only)
    grep "pid=$pid," "$WORK/listen" >"$WORK/listen.pid" || fail "pid $pid listens on no TCP port: $(cat "$WORK/listen")"
    if awk '$4 !~ /^127\.0\.0\.1:/' "$WORK/listen.pid" | grep .; then fail "pid $pid listens beyond 127.0.0.1"; fi
  done
else
  say "note: no ss here; the listening addresses are not checked"
fi

check "the job array script"
mkdir -p "$WORK/slurm" "$WORK/local"
# The scenes of the array and their durations, one a line: task I takes line I+1.
for i in "${!SCENE_LIST[@]}"; do printf '%s %s\n' "${SCENE_LIST[$i]}" "$(duration_of "$i")"; done >"$WORK/scenes.txt"
cat >"$WORK/array.sbatch" <<EOF
#!/bin/bash
#SBATCH --job-name=simbob-array
#SBATCH --array=0-$((${#SCENE_LIST[@]} - 1))
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --time=5
#SBATCH --output=$WORK/slurm/task-%a.log
set -euo pipefail
read -r scene duration <<<"\$(sed -n "\$((SLURM_ARRAY_TASK_ID + 1))p" "$WORK/scenes.txt")"
printf '%s %s %s\n' "\$SLURM_ARRAY_JOB_ID" "\$SLURM_ARRAY_TASK_ID" "\$SLURM_JOB_ID" >"$WORK/slurm/ids-\$SLURM_ARRAY_TASK_ID"
exec "$SIMBOB" run "$SCENES/\$scene.xml" --duration "\$duration" --quiet --out "$WORK/slurm/task-\$SLURM_ARRAY_TASK_ID.csv"
EOF

check "sbatch --wait runs the array to the end (bounded: 240 s)"
t1=$SECONDS
status=0
timeout 240 sbatch --wait --parsable "$WORK/array.sbatch" >"$WORK/sbatch.out" 2>"$WORK/sbatch.err" || status=$?
if [[ $status -ne 0 ]]; then
  {
    printf 'sbatch --wait exited %s (124: the 240 s bound ran out)\n' "$status"
    cat "$WORK/sbatch.out" "$WORK/sbatch.err"
    squeue 2>&1 | head -n 10
    for f in "$WORK"/slurm/task-*.log; do [[ -f "$f" ]] && { echo "--- $f"; tail -n 5 "$f"; }; done
    slurm_log_tail
  } >&2
  fail "the job array did not finish cleanly"
fi
jobid=$(head -n 1 "$WORK/sbatch.out")
say "array job $jobid finished after $((SECONDS - t1)) s"
[[ "$jobid" =~ ^[0-9]+$ ]] || fail "sbatch --parsable printed '$jobid', not a job id"

check "every task ran under Slurm as a task of array $jobid, and its output is complete"
for i in "${!SCENE_LIST[@]}"; do
  expect_file "$WORK/slurm/ids-$i"
  read -r array_job task job <"$WORK/slurm/ids-$i"
  expect_eq "task $i: SLURM_ARRAY_JOB_ID" "$array_job" "$jobid"
  expect_eq "task $i: SLURM_ARRAY_TASK_ID" "$task" "$i"
  [[ "$job" =~ ^[0-9]+$ ]] || fail "task $i: SLURM_JOB_ID is '$job'"
  expect_file "$WORK/slurm/task-$i.csv"
  expect_eq "task $i: run status" "$(json_get "$WORK/slurm/task-$i.json" 'j["status"]')" completed
  expect_eq "task $i: scene" "$(json_get "$WORK/slurm/task-$i.json" 'j["scene"]')" "$SCENES/${SCENE_LIST[$i]}.xml"
done
# The task ids are the four array indices, each once (no task ran twice into the same file).
expect_eq "distinct job ids" "$(cat "$WORK"/slurm/ids-* | awk '{print $3}' | sort -u | wc -l)" "${#SCENE_LIST[@]}"

check "each task's trajectory is byte-identical to a local run of the same command"
for i in "${!SCENE_LIST[@]}"; do
  expect_status 0 "$SIMBOB" run "$SCENES/${SCENE_LIST[$i]}.xml" --duration "$(duration_of "$i")" --quiet \
    --out "$WORK/local/task-$i.csv"
  expect_same_file "$WORK/slurm/task-$i.csv" "$WORK/local/task-$i.csv"
  # A trajectory of its duration at the default 0.01 s interval.
  read -r samples _ <<<"$(csv_summary "$WORK/slurm/task-$i.csv")"
  expect_eq "task $i: samples" "$samples" $(($(duration_of "$i") * 100 + 1))
done

check "the socket task: simbob started its controller under Slurm; the trajectory is the golden"
expect_same_file "$WORK/slurm/task-$SOCKET_TASK.csv" "$REPO/golden/socket_robot.csv"
expect_match "the controller's log is beside the task's CSV" "$WORK/slurm/task-$SOCKET_TASK.controller.log" \
  "the run ended at t=10 s"
# Nothing started by the task outlives it: no client whose environment names this cluster
# (SLURM_CONF, under $WORK) is left running.
for pid in $(pgrep -f "scripts/simbob_client.py" || true); do
  if grep -qs "$WORK" "/proc/$pid/environ"; then fail "a controller started by the socket task still runs: pid $pid"; fi
done

check "the cluster stops and leaves no daemon behind"
pids=("${SLURM_PIDS[@]}")
slurm_stop
for pid in "${pids[@]}"; do
  if kill -0 "$pid" 2>/dev/null; then fail "daemon pid $pid still runs after slurm_stop"; fi
done
expect_eq "job steps left" "$(slurm_steps)" ""
say "ok ($((SECONDS - t0)) s)"
