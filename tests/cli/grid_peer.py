"""A socket peer whose commands depend only on simulated time: grid_peer.py PORT

Connects to simbob (protocol 2) on 127.0.0.1:PORT and, at every exchange, commands the first
RC2DMotionControl with a value that changes every 0.1 s of simulated time (a fixed pseudo-random
pattern), whatever the exchange period. Two runs whose peers exchange at different periods that
both meet every multiple of 0.1 s therefore send the same commands at the same instants, and on a
fixed step grid give the same trajectory. Standard library only.
"""
import socket
import sys
import time


def command(t):
    k = int(t * 10 + 1e-6)  # the 0.1 s slot; grid times are exact to the nanosecond
    return 0.05 * (1 + k % 4), 0.3 * ((k * 7) % 5 - 2)


def main():
    port = int(sys.argv[1])
    deadline = time.monotonic() + 30
    while True:
        try:
            sock = socket.create_connection(("127.0.0.1", port), timeout=30)
            break
        except ConnectionRefusedError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.05)
    f = sock.makefile("rb")
    line = lambda: f.readline().decode("ascii").rstrip("\n")
    hello = line().split()
    if hello[:2] != ["simbob", "2"]:
        sys.exit(f"grid_peer: unexpected hello {hello}")
    motions = []
    while (l := line()) != "end":
        w = l.split()
        if len(w) >= 2 and w[0] == "motion":
            motions.append(w[1])
    exchanges = 0
    while True:
        w = line().split()
        if not w or w[0] in ("bye", "error"):
            print(f"grid_peer: {' '.join(w)} after {exchanges} exchanges", file=sys.stderr)
            return 0 if w and w[0] == "bye" else 1
        t = float(w[1])
        while line() != "end":
            pass
        linear, angular = command(t)
        sock.sendall(f"set {motions[0]} {linear!r} {angular!r}\nstep\n".encode("ascii"))
        exchanges += 1


if __name__ == "__main__":
    sys.exit(main())
