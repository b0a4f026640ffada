"""A peer for tests/cli/socket_v3.sh, started by simbob (SIMBOB_PORT), speaking the wire protocol
by hand (no client library), printing what it receives to stdout (the run's controller log):

  socket_v3_peer.py send 'LINE' ...   after the version 2 hello and first state, sends the lines
                                      in one write, then prints every line simbob sends until it
                                      closes ("EOF" last)
  socket_v3_peer.py v3 BODY MOTION    negotiates version 3, prints the hello and the first state,
                                      subscribes to body BODY only (escaped as given) and to no
                                      joints, drives MOTION forward, prints the next two states,
                                      then says done
"""
import os
import socket
import sys


class Wire:
    def __init__(self):
        self.sock = socket.create_connection(("127.0.0.1", int(os.environ["SIMBOB_PORT"])), timeout=30)
        self.buf = b""

    def line(self):
        while b"\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                return None
            self.buf += chunk
        line, self.buf = self.buf.split(b"\n", 1)
        return line.decode("ascii")

    def upto(self, last):
        """Lines up to and including the first equal to `last`."""
        out = []
        while True:
            line = self.line()
            if line is None:
                raise SystemExit("socket_v3_peer: EOF before " + last + ": " + repr(out))
            out.append(line)
            if line == last:
                return out

    def send(self, text):
        self.sock.sendall(text.encode("ascii"))


def main():
    w = Wire()
    hello = w.upto("end")
    print("hello2:", " | ".join(hello))
    w.upto("end")  # the state at t = 0
    if sys.argv[1] == "send":
        w.send("".join(line + "\n" for line in sys.argv[2:]))
        while (line := w.line()) is not None:
            print(line)
        print("EOF")
        return 0
    body, motion = sys.argv[2], sys.argv[3]
    w.send("version 2 3\n")
    skipped = w.upto("version 3")
    print("skipped", len(skipped) - 1, "lines before 'version 3'")
    for line in w.upto("end"):
        print("hello3:", line)
    for line in w.upto("end"):
        print("state0:", line)
    w.send(f"subscribe bodies {body}\nsubscribe joints\nset {motion} 0.5 0\nstep\n")
    for i in (1, 2):
        for line in w.upto("end"):
            print(f"state{i}:", line)
        w.send("done\n" if i == 2 else "step\n")
    while (line := w.line()) is not None:
        print(line)
    print("EOF")
    return 0


if __name__ == "__main__":
    sys.exit(main())
