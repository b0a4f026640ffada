#!/usr/bin/python3
"""The Python peer of tests/cli/socket_camera.sh, through python/simbob_client.py.

    socket_camera_peer.py PREFIX        subscribes to every camera after the first state and writes
                                        each image it receives to PREFIX_T.rgb (T with 2 decimals)
    socket_camera_peer.py PREFIX bad    subscribes to a camera that does not exist

It prints what the test compares with the C peer (socket_camera_peer.c), line for line.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from simbob_client import Client, SimbobError  # noqa: E402


def main():
    prefix = sys.argv[1]
    c = Client.connect()
    print(f"version {c.version}")
    for key, (w, h, period) in c.cameras.items():
        print(f"camera {key} {w} {h} {period:g}")
    s = c.state()
    print(f"t {s.t:.2f} images {len(s.images)}")  # none: images only on request
    if sys.argv[2:] == ["bad"]:
        c.reply(subscribe={"cameras": ["Bot.Nose"]})
        try:
            c.state()
        except SimbobError as e:
            print(f"error {e}")
        return 0
    c.reply(subscribe={"cameras": list(c.cameras)})
    while (s := c.state()) is not None:
        for key, (w, h, rgb) in s.images.items():
            print(f"t {s.t:.2f} image {key} {w} {h} {len(rgb)}")
            with open(f"{prefix}_{s.t:.2f}.rgb", "wb") as f:
                f.write(rgb)
        c.reply()
    print(f"bye {c.ended:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
