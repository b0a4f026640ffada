#!/usr/bin/env bash
# A failed run publishes nothing (issue #19, item 4): when the disk fills up at the end of a run
# with --video, after the video is complete but while the trajectory is written out, the run
# exits 74 and the video, the trajectory and the summary of the earlier run all stay as they
# were (all new or all old), with no temporary file left. Skips (77) without a GL back end.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

if ! "$SIMBOB" info >info.txt 2>&1 && ! grep -q ': EGL \|: OSMesa' info.txt; then
  say "SKIP: no GL back end: $(tr '\n' ' ' <info.txt)"
  exit 77
fi
if ! "$SIMBOB" run "$SCENES/pendulum.xml" --duration 0.1 --video probe.avi --out probe.csv -q 2>probe.err; then
  say "SKIP: this build writes no video: $(cat probe.err)"
  exit 77
fi

check "an earlier run's outputs"
expect_status 0 "$SIMBOB" run "$SCENES/box_stack.xml" --duration 0.2 --video v.avi --fps 5 --size 32x32 --out traj.csv -q
before=$(sha1sum v.avi traj.csv traj.json)

check "the same outputs on a full disk: a 12 KiB video fits, the trajectory (written at the end) does not"
# SIGXFSZ ignored (inherited across exec) turns the limit into a failing write(), like ENOSPC.
set +e
(trap '' XFSZ; ulimit -f 12; exec "$SIMBOB" run "$SCENES/box_stack.xml" --duration 1 --video v.avi --fps 5 --size 32x32 --out traj.csv -q) 2>err.txt
status=$?
set -e
expect_eq "exit status ($(cat err.txt))" "$status" 74
expect_match "the trajectory's write failed" err.txt "^traj.csv: error: write failed: File too large"
expect_eq "video, trajectory and summary are the earlier run's" "$(sha1sum v.avi traj.csv traj.json)" "$before"
expect_eq "no temporary files" "$(ls -a | grep -c '\.tmp\.\|\.old\.' || true)" 0
say "ok: disk_full_video"
