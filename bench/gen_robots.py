#!/usr/bin/env python3
"""Writes scenes of small two-wheeled robots with range sensors or a laser scanner.

Usage: bench/gen_robots.py KIND OUT.xml [options]

KIND:
  swarm     N robots (--robots, default 20) with six range sensors and an RCObstacleAvoider in a
            square arena (--arena m, default 4) walled on four sides: scenes/swarm.xml.
  maze      one robot with a 360-degree laser scanner and an RCWallFollower (left wall) in a
            3 x 3 maze of 0.8 m cells, entered on the left of its top row and left on the right of
            its bottom row: scenes/maze.xml.
  scanners  N robots with a 36-ray scanner at 10 Hz (--rays, --period) each following the wall
            of its own lane: the benchmark of bench/README.md.
  open      one avoider robot at the origin facing +X; --wall D puts a wall face D m ahead of
            its chassis centre, turned --angle degrees (tests/robot/sensing_test.cpp).
  corridor  one wall follower at --offset m from its set distance, parallel to a 30 m long
            wall on its left (tests/robot/sensing_test.cpp).

The robot (every kind): a 0.2 x 0.05 x 0.14 m chassis (1 kg) whose centre is 0.06 m above the
ground, two spherical wheels of radius 0.04 m, 0.18 m apart, 0.03 m ahead of the centre, and a
steel caster ball of radius 0.02 m behind. Forward is local +X, left -Z. In the ground plane it
fits in a circle of radius 0.135 m about the chassis centre (the wheels' outer edges).
Y is up; poses are "x y z a b c" (m, degrees).
"""
import math
import sys

ROBOT_RADIUS = 0.135  # m, every point of a robot within this of its chassis centre (ground plane)


def robot(key, x, z, heading, sensors, controller):
    """One robot at (x, z) turned `heading` degrees counter-clockwise seen from above."""
    return f"""    <RCRobot Key="{key}">
      <Construction>
        <RCConstruction Key="Cart">
          <Body>
            <RCMobileRigidBody Key="Chassis">
              <Pose><RCGlobalCoordinates><Pose Value="{x:g} 0.06 {z:g} 0 {heading:g} 0"/></RCGlobalCoordinates></Pose>
              <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.05"/><Depth Value="0.14"/></RCCuboidGeom></Geom>
              <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
            </RCMobileRigidBody>
          </Body>
          <ChildList>
            <RCHingeJoint Key="LeftAxle">
              <Pose><RCLocalCoordinates><Pose Value="0.03 -0.02 -0.09 0 180 0"/></RCLocalCoordinates></Pose>
              <Body>
                <RCMobileRigidBody Key="LeftWheel">
                  <Pose Macro="Origin"/>
                  <Geom><RCSphereGeom><Radius Value="0.04"/></RCSphereGeom></Geom>
                  <Inertia><RCInertiaByGeom><Mass Value="0.1"/></RCInertiaByGeom></Inertia>
                  <Material Ref="Rubber"/>
                </RCMobileRigidBody>
              </Body>
            </RCHingeJoint>
            <RCHingeJoint Key="RightAxle">
              <Pose><RCLocalCoordinates><Pose Value="0.03 -0.02 0.09 0 180 0"/></RCLocalCoordinates></Pose>
              <Body>
                <RCMobileRigidBody Key="RightWheel">
                  <Pose Macro="Origin"/>
                  <Geom><RCSphereGeom><Radius Value="0.04"/></RCSphereGeom></Geom>
                  <Inertia><RCInertiaByGeom><Mass Value="0.1"/></RCInertiaByGeom></Inertia>
                  <Material Ref="Rubber"/>
                </RCMobileRigidBody>
              </Body>
            </RCHingeJoint>
            <RCBallSocketJoint Key="CasterSocket">
              <Pose><RCLocalCoordinates><Pose Value="-0.07 -0.04 0 0 0 0"/></RCLocalCoordinates></Pose>
              <Body>
                <RCMobileRigidBody Key="CasterBall">
                  <Pose Macro="Origin"/>
                  <Geom><RCSphereGeom><Radius Value="0.02"/></RCSphereGeom></Geom>
                  <Inertia><RCInertiaByGeom><Density Value="7800"/></RCInertiaByGeom></Inertia>
                </RCMobileRigidBody>
              </Body>
            </RCBallSocketJoint>
{sensors}
            <RCGenericVelControlledDrive Key="LeftDrive">
              <Joint Ref="{key}.Cart.LeftAxle"/>
              <MaxPower Value="2"/>
              <MaxVelocity Value="15"/>
            </RCGenericVelControlledDrive>
            <RCGenericVelControlledDrive Key="RightDrive">
              <Joint Ref="{key}.Cart.RightAxle"/>
              <MaxPower Value="2"/>
              <MaxVelocity Value="15"/>
            </RCGenericVelControlledDrive>
          </ChildList>
        </RCConstruction>
      </Construction>
      <ControllerList>
{controller}
        <RCTwoWheelMotionControl Key="Motion">
          <ControlLeft Ref="{key}.Cart.LeftDrive"/>
          <ControlRight Ref="{key}.Cart.RightDrive"/>
          <WheelDistance Value="0.18"/>
          <Variation Value="0.04"/>
        </RCTwoWheelMotionControl>
      </ControllerList>
    </RCRobot>"""


# Range sensors at the chassis centre, 0.075 m above the ground, looking along the bearings
# (degrees, counter-clockwise from forward): a ray along local -Z turned b - 90 about Y. Their
# MinRange 0.15 m is just beyond the robot's own hull (0.135 m from the centre at most).
BEARINGS = [-135, -90, -50, -15, 15, 50, 90, 135]


def range_sensors(max_range):
    out = []
    for i, b in enumerate(BEARINGS):
        out.append(
            f'            <RCRangeSensor Key="Range{i}">\n'
            f'              <Pose><RCLocalCoordinates><Pose Value="0 0.015 0 0 {b - 90} 0"/></RCLocalCoordinates></Pose>\n'
            f'              <MinRange Value="0.15"/>\n'
            f'              <MaxRange Value="{max_range:g}"/>\n'
            f"            </RCRangeSensor>")
    return "\n".join(out)


def avoider(key, speed=0.1, turn=2.5, period=0.05):
    refs = "".join(f'<Sensor Ref="{key}.Cart.Range{i}"/>' for i in range(len(BEARINGS)))
    return f"""        <RCObstacleAvoider Key="Avoider">
          <Motion Ref="{key}.Motion"/>
          <Sensors>{refs}</Sensors>
          <Speed Value="{speed:g}"/>
          <TurnRate Value="{turn:g}"/>
          <Period Value="{period:g}"/>
        </RCObstacleAvoider>"""


def scanner(rays=36, period=0.05, max_range=2.0):
    # Upright on the chassis top, turned so that its -Z looks forward (+X of the body).
    return f"""            <RCLaserScanner Key="Scanner">
              <Pose><RCLocalCoordinates><Pose Value="0 0.04 0 0 -90 0"/></RCLocalCoordinates></Pose>
              <Rays Value="{rays}"/>
              <FieldOfView Value="360"/>
              <MaxRange Value="{max_range:g}"/>
              <Period Value="{period:g}"/>
            </RCLaserScanner>"""


def follower(key, side="Left", distance=0.3, speed=0.2, turn=1.5, period=0.05):
    return f"""        <RCWallFollower Key="Follower">
          <Motion Ref="{key}.Motion"/>
          <Scanner Ref="{key}.Cart.Scanner"/>
          <Side Value="{side}"/>
          <Distance Value="{distance:g}"/>
          <Speed Value="{speed:g}"/>
          <TurnRate Value="{turn:g}"/>
          <Period Value="{period:g}"/>
        </RCWallFollower>"""


def wall(key, x0, z0, x1, z1, thick=0.04, height=0.2):
    """A static box from (x0, z0) to (x1, z1) (axis-aligned), `thick` m thick."""
    w = max(abs(x1 - x0), thick)
    d = max(abs(z1 - z0), thick)
    return (f'    <RCStaticRigidBody Key="{key}">\n'
            f'      <Pose><RCGlobalCoordinates><Pose Value="{(x0 + x1) / 2:g} {height / 2:g} {(z0 + z1) / 2:g} 0 0 0"/>'
            f"</RCGlobalCoordinates></Pose>\n"
            f'      <Geom><RCCuboidGeom><Width Value="{w:g}"/><Height Value="{height:g}"/><Depth Value="{d:g}"/>'
            f"</RCCuboidGeom></Geom>\n"
            f"    </RCStaticRigidBody>")


def scene(comment, parts, dt=0.001):
    return "\n".join([
        '<?xml version="1.0" encoding="UTF-8"?>',
        "<!-- " + comment.strip().replace("\n", "\n     ") + " -->",
        "<Simulation>",
        "  <SceneSettings>",
        f'    <MaxTimeStep Value="{dt:g}"/>',
        "  </SceneSettings>",
        "  <ComponentList>",
        '    <RCGround Key="Ground"/>',
        '    <RCGenericMaterial Key="Rubber"><Friction Value="1"/></RCGenericMaterial>',
    ] + parts + ["  </ComponentList>", "</Simulation>", ""])


def arena_walls(half):
    return [
        wall("WallNorth", -half, -half, half, -half), wall("WallSouth", -half, half, half, half),
        wall("WallWest", -half, -half, -half, half), wall("WallEast", half, -half, half, half)
    ]


def swarm(args):
    n, size = int(args.get("robots", 20)), float(args.get("arena", 4))
    cols = math.ceil(math.sqrt(n))
    rows = math.ceil(n / cols)
    step_x, step_z = (size - 0.8) / max(cols - 1, 1), (size - 0.8) / max(rows - 1, 1)
    parts = arena_walls(size / 2)
    for i in range(n):
        r, c = divmod(i, cols)
        x = -size / 2 + 0.4 + c * step_x
        z = -size / 2 + 0.4 + r * step_z
        heading = (i * 137) % 360  # spread headings (golden-angle steps), no two alike nearby
        key = f"Bot{i:02d}"
        parts.append(robot(key, x, z, heading, range_sensors(0.8), avoider(key)))
    return scene(
        f"""{n} small two-wheeled robots in a {size:g} m square arena, each with eight range sensors at its
chassis centre (MinRange 0.15 m, MaxRange 0.8 m, bearings {BEARINGS} degrees from
forward) and an RCObstacleAvoider (Speed 0.1 m/s, TurnRate 2.5 rad/s, Period 0.05 s): they wander and keep clear of each other
and the walls. Every robot fits in a circle of radius {ROBOT_RADIUS} m about its chassis centre;
tests/cli/swarm.sh checks that no two robots and no robot and wall touch in 60 s.
Generated by bench/gen_robots.py swarm. Y is up; poses are "x y z a b c" (m, degrees).""", parts)


# The maze: 3 x 3 cells of CELL m; x grows to the right, z downwards (seen from above, Y up).
# '-' and '|' are walls; the robot enters the top row from the left and leaves the bottom row
# to the right. Following the left wall: east along the top row, down, west along the middle
# row, down, east along the bottom row and out.
CELL = 0.8
MAZE = [
    "+--+--+--+",
    "         |",
    "+--+--+  +",
    "|        |",
    "+  +--+--+",
    "|         ",
    "+--+--+--+",
]


def maze_walls():
    parts = []
    for r, line in enumerate(MAZE):
        for c, ch in enumerate(line):
            if r % 2 == 0 and c % 3 == 1 and ch == "-":  # horizontal wall above cell row r/2
                x0 = (c // 3) * CELL
                z = (r // 2) * CELL
                parts.append(wall(f"MazeH{r // 2}{c // 3}", x0 - 0.02, z, x0 + CELL + 0.02, z))
            if r % 2 == 1 and c % 3 == 0 and ch == "|":  # vertical wall left of cell column c/3
                x = (c // 3) * CELL
                z0 = (r // 2) * CELL
                parts.append(wall(f"MazeV{r // 2}{c // 3}", x, z0 - 0.02, x, z0 + CELL + 0.02))
    return parts


def maze(args):
    parts = maze_walls()
    parts.append(robot("Bot", CELL / 2, CELL / 2, 0, scanner(), follower("Bot", distance=0.25, turn=2.0)))
    return scene(
        f"""A small maze (3 x 3 cells of {CELL} m, walls 4 cm thick) and a robot with a 360-degree,
36-ray laser scanner (MaxRange 2 m, 20 Hz) and an RCWallFollower keeping the wall on its left at
0.25 m (Speed 0.2 m/s, TurnRate 2 rad/s). It starts in the middle of the first cell (the top row's left one,
whose left side is the open entrance), facing +X, and follows the left wall east, down, west, down and east to the exit (the bottom row's open right
side, x = {3 * CELL:g} m; about 36 s), which tests/cli/maze.sh checks it passes within 60 s:

{chr(10).join(MAZE)}

x grows to the right and z downwards in this drawing (seen from above). Generated by
bench/gen_robots.py maze. Y is up; poses are "x y z a b c" (m, degrees).""", parts)


def scanners(args):
    n, rays, period = int(args.get("robots", 100)), int(args.get("rays", 36)), float(args.get("period", 0.1))
    parts = []
    for i in range(n):
        z = i * 1.0
        parts.append(wall(f"Lane{i:03d}", -1, z - 0.3, 40, z - 0.3))
        key = f"Bot{i:03d}"
        parts.append(robot(key, 0, z, 0, scanner(rays, period), follower(key, period=period)))
    return scene(
        f"""Benchmark: {n} robots, each with a {rays}-ray 360-degree laser scanner read every {period:g} s
by an RCWallFollower keeping its lane's wall (0.3 m to its left) while driving at 0.2 m/s.
Generated by bench/gen_robots.py scanners.""", parts)


def open_scene(args):
    parts = []
    if "wall" in args:
        d, a = float(args["wall"]), float(args.get("angle", 0))
        parts.append(f"""    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="{d + 0.05:g} 0.1 0 0 {a:g} 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="0.1"/><Height Value="0.2"/><Depth Value="4"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>""")
    parts.append(robot("Bot", 0, 0, 0, range_sensors(0.65), avoider("Bot", speed=0.12)))
    return scene("One RCObstacleAvoider robot (tests/robot/sensing_test.cpp). Generated by bench/gen_robots.py open.",
                 parts)


def corridor(args):
    off = float(args.get("offset", 0))
    parts = [wall("Wall", -1, -0.32 - off, 30, -0.32 - off)]  # its face at z = -0.3 - off
    parts.append(robot("Bot", 0, 0, 0, scanner(), follower("Bot")))
    return scene(
        f"""One RCWallFollower robot (Distance 0.3 m, left) starting {0.3 + off:g} m from a straight wall on
its left, parallel to it (tests/robot/sensing_test.cpp). Generated by bench/gen_robots.py corridor.""", parts)


def main(argv):
    kinds = {"swarm": swarm, "maze": maze, "scanners": scanners, "open": open_scene, "corridor": corridor}
    if len(argv) < 3 or argv[1] not in kinds or len(argv) % 2 != 1:
        sys.stderr.write(__doc__)
        return 64
    args = {}
    for k in range(3, len(argv), 2):
        if not argv[k].startswith("--"):
            sys.stderr.write(__doc__)
            return 64
        args[argv[k][2:]] = argv[k + 1]
    with open(argv[2], "w") as f:
        f.write(kinds[argv[1]](args))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
