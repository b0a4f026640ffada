#!/usr/bin/env bash
# run --columns pose,velocity (README "Trajectory CSV"): every row gets vx,vy,vz (m/s) and
# wx,wy,wz (rad/s), world frame, after the pose; the default keeps today's bytes; compare and
# plot read files with the block.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

SCENE="$SCENES/bounce.xml"
check "--columns pose,velocity adds the velocity block"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 0.5 --out v.csv --columns pose,velocity -q
expect_eq "header" "$(head -n 1 v.csv)" "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"
check "the default, and --columns pose, write the pose file of before"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 0.5 --out p.csv -q
expect_status 0 "$SIMBOB" run "$SCENE" --duration 0.5 --out p2.csv --columns pose -q
expect_same_file p.csv p2.csv
expect_eq "pose header" "$(head -n 1 p.csv)" "time,body,x,y,z,qw,qx,qy,qz"
cut -d, -f1-9 v.csv | tail -n +2 >v_pose.txt
tail -n +2 p.csv >p_pose.txt
expect_same_file v_pose.txt p_pose.txt
check "compare and plot read it"
expect_status 0 "$SIMBOB" compare v.csv p.csv
expect_status 0 "$SIMBOB" compare p.csv v.csv
expect_status 0 "$SIMBOB" plot v.csv --out v.svg
expect_file v.svg
check "an unknown column set is a usage error"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 0.5 --out x.csv --columns velocity
say "OK"
