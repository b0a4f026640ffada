#!/usr/bin/python3
"""Example peer of simbob's RCLocalSocketCommunicator (docs/socket-protocol.md, version 2).

Drives a two-wheeled robot through its RC2DMotionControl (scenes/socket_robot.xml): forward at
0.2 m/s for 2 s, then a turn to the left on the spot with a proportional law on the heading
read from the chassis pose, w = 2 (pi/2 - heading) rad/s clamped to +-1 rad/s, until the robot
faces a quarter turn counter-clockwise (seen from above, Y up) from where it started.

    python3 scripts/simbob_client.py --port 47311 &          # the scene's IsServer is true
    build/simbob run scenes/socket_robot.xml --duration 10

With --listen the client is the server instead (a scene whose IsServer is false connects to
it): start it first, then simbob. Python 3 standard library only.
"""
import argparse
import math
import os
import socket
import sys
import time

PROTOCOL = 2


class Peer:
    """One connection to simbob: line reading and writing."""

    def __init__(self, sock):
        self.sock = sock
        self.buf = b""

    def line(self):
        while b"\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise EOFError("simbob closed the connection")
            self.buf += chunk
        line, self.buf = self.buf.split(b"\n", 1)
        return line.decode("ascii")

    def send(self, text):
        self.sock.sendall(text.encode("ascii"))


def connect(port, wait):
    """Connects to simbob on 127.0.0.1:port, retrying for `wait` s while it starts."""
    deadline = time.monotonic() + wait
    while True:
        try:
            return socket.create_connection(("127.0.0.1", port), timeout=wait)
        except ConnectionRefusedError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.05)


def accept(port, wait):
    """Listens on 127.0.0.1:port and waits `wait` s for simbob to connect."""
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    server.bind(("127.0.0.1", port))
    server.listen(1)
    server.settimeout(wait)
    print(f"simbob_client: listening on 127.0.0.1:{port}", file=sys.stderr, flush=True)
    conn, _ = server.accept()
    server.close()
    return conn


def heading(q):
    """Rotation about +Y (rad, counter-clockwise seen from above) of a body whose forward is +X."""
    w, x, y, z = q
    fx = 1 - 2 * (y * y + z * z)
    fz = 2 * (x * z - w * y)
    return math.atan2(-fz, fx)


def command(t, pose):
    """(linear m/s, angular rad/s) for the robot at simulated time t with chassis pose."""
    if t < 2.0:
        return 0.2, 0.0
    error = math.pi / 2 - heading(pose[3:7])
    return 0.0, max(-1.0, min(1.0, 2.0 * error))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--port", type=int, default=int(os.environ.get("SIMBOB_PORT", "47311")),
                    help="TCP port on 127.0.0.1 (default: $SIMBOB_PORT, set when simbob starts this client, else 47311)")
    ap.add_argument("--listen", action="store_true", help="be the server (the scene's IsServer is false)")
    ap.add_argument("--wait", type=float, default=30.0, help="s to wait for simbob (default 30)")
    ap.add_argument("--motion", help="key of the RC2DMotionControl to drive (default: the first one)")
    ap.add_argument("--body", help="key of the body whose heading is controlled (default: the first one)")
    args = ap.parse_args()

    sock = accept(args.port, args.wait) if args.listen else connect(args.port, args.wait)
    sock.settimeout(None)
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    peer = Peer(sock)

    # Hello: "simbob VERSION KEY PERIOD", then what the peer may read and set, then "end".
    # From version 2 on, simbob promises that lines a peer does not know may be ignored, so
    # this client takes any version from 2 up and skips lines (and extra words) it does not know.
    first = peer.line().split()
    if len(first) < 4 or first[0] != "simbob" or not first[1].isdigit() or int(first[1]) < PROTOCOL:
        sys.exit(f"simbob_client: not a simbob protocol {PROTOCOL} (or later) hello: {' '.join(first)}")
    motions, bodies, sensors = [], [], {}
    while (line := peer.line()) != "end":
        w = line.split()
        if len(w) < 2:
            continue  # a line this client does not know
        kind, key = w[:2]
        if kind == "motion":
            motions.append(key)
        elif kind == "body":
            bodies.append(key)
        elif kind == "sensor":
            sensors[key] = None  # its reading comes with each period's state
    motion = args.motion or (motions[0] if motions else None)
    body = args.body or (bodies[0] if bodies else None)
    if motion not in motions or body not in bodies:
        sys.exit(f"simbob_client: the scene offers motions {motions} and bodies {bodies}")

    steps = 0
    while True:
        words = peer.line().split()
        if not words:
            continue
        if words[0] == "bye":
            print(f"simbob_client: the run ended at t={words[1]} s after {steps} exchanges", file=sys.stderr)
            return 0
        if words[0] == "error":
            sys.exit("simbob_client: simbob says: " + " ".join(words[1:]))
        if words[0] != "t" or len(words) < 2:
            continue  # a line this client does not know
        t = float(words[1])
        poses = {}
        while (line := peer.line()) != "end":
            w = line.split()
            if len(w) >= 9 and w[0] == "body":
                poses[w[1]] = [float(v) for v in w[2:9]]
            elif len(w) >= 3 and w[0] == "sensor":
                # This control law does not use sensors; it reports when one switches.
                touching = w[2] == "1"
                if sensors.get(w[1]) is not None and sensors[w[1]] != touching:
                    print(f"simbob_client: t={words[1]} s sensor {w[1]} {w[2]}", file=sys.stderr)
                sensors[w[1]] = touching
        linear, angular = command(t, poses[body])
        # repr() writes the shortest round-trip form: the same commands give the same bytes.
        peer.send(f"set {motion} {linear!r} {angular!r}\nstep\n")
        steps += 1


if __name__ == "__main__":
    sys.exit(main())
