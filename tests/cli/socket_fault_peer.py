#!/usr/bin/env python3
"""A misbehaving peer for tests/cli/socket.sh: speaks simbob's socket protocol
(docs/socket-protocol.md) correctly, answering every exchange with a bare "step", until simulated time reaches
--at, then does what --mode says:
  disconnect  closes the connection
  stall       stops answering but keeps the connection open (until simbob closes it)
  garbage     sends a line the protocol does not allow
  done        sends "done" (and reads on until simbob closes the connection)
  stream      sends valid "set" lines without "step" as fast as simbob reads them, for
              --stream seconds (then stalls until simbob closes the connection)
  step        never deviates: answers "step" until simbob closes the connection
It connects to 127.0.0.1:--port, retrying while simbob starts (after --delay seconds: a late
peer). Prints simbob's "error" line (if any) to stdout, and "at T" once it answered at T
(the test then knows the run is under way)."""
import argparse
import socket
import sys
import time

ap = argparse.ArgumentParser()
ap.add_argument("--port", type=int, required=True)
ap.add_argument("--mode", choices=["disconnect", "stall", "garbage", "done", "stream", "step"], required=True)
ap.add_argument("--at", type=float, default=1.0)
ap.add_argument("--delay", type=float, default=0.0)
ap.add_argument("--stream", type=float, default=20.0)
args = ap.parse_args()

print("ready", file=sys.stderr, flush=True)  # the test starts simbob after this
time.sleep(args.delay)
deadline = time.monotonic() + 60
while True:
    try:
        sock = socket.create_connection(("127.0.0.1", args.port), timeout=60)
        break
    except ConnectionRefusedError:
        if time.monotonic() > deadline:
            sys.exit("socket_fault_peer: simbob never listened")
        time.sleep(0.05)
reader = sock.makefile("r", encoding="ascii", newline="\n")


def drain():
    """Reads until simbob closes the connection; prints its error line."""
    try:
        for line in reader:
            if line.startswith("error "):
                print(line.rstrip("\n"), flush=True)
    except OSError:
        pass  # a reset after simbob closed with our lines unread


t = None
said_at = False
try:
    for line in reader:
        if line.startswith("error "):
            print(line.rstrip("\n"), flush=True)
            continue
        if line.startswith("t "):
            t = float(line.split()[1])
        if line != "end\n" or t is None:  # answer once the whole state block is in
            continue
        if t >= args.at and args.mode == "step":
            if not said_at:
                print(f"at {t}", flush=True)
                said_at = True
        elif t >= args.at:
            if args.mode == "disconnect":
                sock.close()
                sys.exit(0)
            if args.mode == "stall":
                drain()
                sys.exit(0)
            if args.mode == "garbage":
                sock.sendall(b"jump Bot.Motion 3\n")
                drain()
                sys.exit(0)
            if args.mode == "stream":
                end = time.monotonic() + args.stream
                try:
                    while time.monotonic() < end:  # simbob's side never runs dry
                        sock.sendall(b"set Bot.Motion 0 0\n" * 1000)
                except OSError:
                    pass  # simbob closed the connection: the point of the test
                drain()
                sys.exit(0)
            sock.sendall(b"done\n")
            drain()
            sys.exit(0)
        sock.sendall(b"step\n")
except OSError:
    pass  # a reset after simbob closed with our last 'step' unread: its error line came first
