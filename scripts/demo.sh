#!/usr/bin/env bash
# From a fresh Debian 12 machine: install what is missing, build, and run an example scene.
# Only what building and running needs is installed, and the tests are not built (test.sh
# installs and builds those). Then records a few seconds of the example robot as a video.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh -DSIMBOB_TESTS=OFF
mkdir -p out
build/simbob run scenes/pendulum.xml --duration 10 --out out/pendulum.csv
echo
echo "Trajectory: out/pendulum.csv (summary: out/pendulum.json). First rows:"
head -n 4 out/pendulum.csv
echo
# The two-wheeled robot drives forward, turns left and stops; rendered off-screen (EGL or
# OSMesa, no display needed) through its scene's camera "Side".
build/simbob run scenes/two_wheel_robot.xml --duration 5 --out out/two_wheel_robot.csv \
  --video out/two_wheel_robot.mp4 --size 640x480 --fps 30
echo "Video of the robot: out/two_wheel_robot.mp4 (5 s, 640x480, 30 fps; trajectory: out/two_wheel_robot.csv)"
# The same run as a page to replay in a browser: one file, opened from disk, no server.
build/simbob view out/two_wheel_robot.csv --scene scenes/two_wheel_robot.xml -o out/two_wheel_robot.html \
  --title "two_wheel_robot: 5 s"
echo "Replay page: out/two_wheel_robot.html -- open it in Chromium or Firefox (file://$(pwd)/out/two_wheel_robot.html);"
echo "  drag to turn the orbit camera, pick the scene's cameras, click a body for its pose, link a moment with #t=2.5"
