#!/usr/bin/env python3
"""A misbehaving peer for tests/cli/socket.sh: speaks simbob's socket protocol
(docs/socket-protocol.md) correctly, answering every exchange with a bare "step", until simulated time reaches
--at, then does what --mode says:
  disconnect  closes the connection
  stall       stops answering but keeps the connection open (until simbob closes it)
  garbage     sends a line the protocol does not allow
  done        sends "done" (and reads on until simbob closes the connection)
It connects to 127.0.0.1:--port, retrying while simbob starts. Prints simbob's "error" line
(if any) to stdout."""
import argparse
import socket
import sys
import time

ap = argparse.ArgumentParser()
ap.add_argument("--port", type=int, required=True)
ap.add_argument("--mode", choices=["disconnect", "stall", "garbage", "done"], required=True)
ap.add_argument("--at", type=float, default=1.0)
args = ap.parse_args()

print("ready", file=sys.stderr, flush=True)  # the test starts simbob after this
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
    for line in reader:
        if line.startswith("error "):
            print(line.rstrip("\n"), flush=True)


t = None
for line in reader:
    if line.startswith("t "):
        t = float(line.split()[1])
    if line != "end\n" or t is None:  # answer once the whole state block is in
        continue
    if t >= args.at:
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
        sock.sendall(b"done\n")
        drain()
        sys.exit(0)
    sock.sendall(b"step\n")
