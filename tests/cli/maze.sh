#!/usr/bin/env bash
# scenes/maze.xml: the robot with a laser scanner and an RCWallFollower (left wall) leaves the
# maze (3 x 3 cells of 0.8 m) through its exit within 60 s, checked from the trajectory CSV: the
# chassis centre passes the exit's outer edge (x > 2.4 m + the wall's half thickness 0.02 m + the
# robot's footprint radius 0.135 m = 2.555 m, so the whole robot is out) in the bottom row
# (1.6 < z < 2.4),
# having stayed inside the maze's outline until then. Walls never touched: every sample keeps the
# footprint (0.135 m about the chassis centre) off every wall segment.
# scenes/maze_socket.xml, the same robot driven over the socket by a Python program simbob starts
# (examples/clients/maze_follower.py), must do the same.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# leaves_maze CSV SCENE: the chassis leaves through the exit, touching no wall of SCENE.
leaves_maze() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import csv, math, re, sys
rows = [r for r in csv.reader(open(sys.argv[1])) if len(r) > 4 and r[1] == "Bot.Cart.Chassis"]
assert rows, "no chassis rows"
# The maze's walls from the scene: static boxes MazeH* / MazeV* (centre x z, width, depth).
text = open(sys.argv[2]).read()
walls = []
for m in re.finditer(r'<RCStaticRigidBody Key="Maze\w+">\s*<Pose><RCGlobalCoordinates><Pose Value="([^"]+)"/>'
                     r'.*?<Width Value="([^"]+)"/><Height Value="[^"]+"/><Depth Value="([^"]+)"/>', text, re.S):
    x, _, z = (float(v) for v in m.group(1).split()[:3])
    w, d = float(m.group(2)), float(m.group(3))
    walls.append((x - w / 2, x + w / 2, z - d / 2, z + d / 2))
assert len(walls) >= 10, walls
R = 0.135
exit_t = None
closest = 1e9
for r in rows:
    t, x, z = float(r[0]), float(r[2]), float(r[4])
    for (x0, x1, z0, z1) in walls:
        dx = max(x0 - x, 0, x - x1)
        dz = max(z0 - z, 0, z - z1)
        closest = min(closest, math.hypot(dx, dz))
    if exit_t is None:
        if x > 2.555 and 1.6 < z < 2.4:
            exit_t = t
        else:
            inside = -0.1 < x < 2.4 and 0 < z < 2.4
            assert inside or 1.6 < z < 2.4, f"left the maze elsewhere at t = {t}: ({x}, {z})"
print(f"check: out of the exit at t = {exit_t} s; closest chassis centre to a wall {closest:.3f} m (footprint {R} m)")
assert exit_t is not None, "never reached the exit"
assert closest > R, closest
PY
}

check "the maze robot reaches the exit within 60 s without touching a wall"
expect_status 0 "$SIMBOB" run "$SCENES/maze.xml" --duration 60 --out maze.csv
leaves_maze maze.csv "$SCENES/maze.xml"

check "driven by examples/clients/maze_follower.py over the socket (simbob starts it), it does too"
expect_status 0 "$SIMBOB" run "$SCENES/maze_socket.xml" --duration 60 --out maze_socket.csv
leaves_maze maze_socket.csv "$SCENES/maze_socket.xml"
expect_match "the follower ran to the end" maze_socket.controller.log \
  "maze_follower.py: the run ended at t=60 s after 1201 exchanges"
