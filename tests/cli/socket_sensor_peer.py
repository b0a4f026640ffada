#!/usr/bin/env python3
"""A listening-only peer for tests/cli/socket.sh: connects to simbob on 127.0.0.1:--port
(retrying while simbob starts), checks the protocol 2 hello, answers every exchange with a bare
"step" and prints each hello "sensor" line and each period's "sensor KEY 0|1" as "T KEY 0|1"."""
import argparse
import socket
import sys
import time

ap = argparse.ArgumentParser()
ap.add_argument("--port", type=int, required=True)
args = ap.parse_args()

deadline = time.monotonic() + 60
while True:
    try:
        sock = socket.create_connection(("127.0.0.1", args.port), timeout=60)
        break
    except ConnectionRefusedError:
        if time.monotonic() > deadline:
            sys.exit("socket_sensor_peer: simbob never listened")
        time.sleep(0.05)
reader = sock.makefile("r", encoding="ascii", newline="\n")
first = reader.readline().split()
if first[:2] != ["simbob", "2"]:
    sys.exit(f"socket_sensor_peer: not a protocol 2 hello: {first}")
for line in reader:
    if line == "end\n":
        break
    if line.startswith("sensor "):
        print("hello " + line.rstrip("\n"), flush=True)
t = None
for line in reader:
    w = line.split()
    if w[0] == "bye":
        sys.exit(0)
    if w[0] == "t":
        t = w[1]
    elif w[0] == "sensor":
        print(t, w[1], w[2], flush=True)
    elif w[0] == "end":
        sock.sendall(b"step\n")
sys.exit("socket_sensor_peer: simbob closed without 'bye'")
