"""A client of simbob's socket protocol (docs/socket-protocol.md), Python standard library only.

    from simbob_client import Client
    with Client.connect(port) as c:            # or Client.accept(port) when simbob connects
        print(c.version, c.motions, c.bodies)  # from the hello
        while (s := c.state()) is not None:    # None once simbob said 'bye'
            x = s.bodies["Bot.Cart.Chassis"][0]
            c.reply(sets=[("Bot.Motion", 0.2, 0.0)])

It negotiates version 3 (versions=(2,) keeps version 2), escapes and unescapes keys, reads
camera images (reply(subscribe={"cameras": [key]}), then State.images), and raises SimbobError
when simbob sends `error`. Numbers are written with repr(): the shortest text
that reads back to the same double.
"""
import os
import socket
import time

__all__ = ["Client", "SimbobError", "State", "escape_key", "unescape_key", "SPEAKS"]

SPEAKS = (2, 3)  # the protocol versions this client speaks


class SimbobError(Exception):
    """simbob sent `error MESSAGE` (the run failed) or broke the protocol."""


def escape_key(key):
    """A key as one word: blanks, control bytes, non-ASCII bytes, '%' and ',' as %XX."""
    out = []
    for b in key.encode("utf-8"):
        if b <= 0x20 or b >= 0x7F or b in (0x25, 0x2C):
            out.append("%%%02X" % b)
        else:
            out.append(chr(b))
    return "".join(out)


def unescape_key(word):
    """The key a word stands for (%XX decoded, then UTF-8)."""
    raw = bytearray()
    i = 0
    while i < len(word):
        if word[i] == "%":
            raw.append(int(word[i + 1:i + 3], 16))
            i += 3
        else:
            raw += word[i].encode("utf-8")
            i += 1
    return raw.decode("utf-8")


class State:
    """One exchange's state: t (s); joints {key: (position, velocity)}; sensors {key: [values]};
    bodies {key: [x, y, z, qw, qx, qy, qz] (+ [vx, vy, vz, wx, wy, wz] in version 3)};
    images {key: (width, height, rgb bytes)} of the cameras subscribed to (version 3; RGB, rows
    top first, 3 bytes a pixel)."""

    def __init__(self, t):
        self.t = t
        self.joints = {}
        self.sensors = {}
        self.bodies = {}
        self.images = {}


class Client:
    def __init__(self, sock, versions=SPEAKS):
        self.sock = sock
        sock.settimeout(None)  # simbob may simulate for long between exchanges
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.buf = b""
        self.ended = None  # the 'bye' time once the run completed
        self._first = None
        self._hello()
        self._first = self.state()
        offered = self.offered
        common = [v for v in versions if v in offered]
        if common and max(common) > self.version:
            # The first line of the first reply: simbob answers 'version N', hello and state again.
            self._send("version " + " ".join(str(v) for v in versions) + "\n")
            while True:
                w = self._line().split()
                if w and w[0] == "version":
                    break
                if w and w[0] == "error":
                    raise SimbobError(" ".join(w[1:]))
            self._first = None
            self._hello()
            self._first = self.state()

    # ---- connecting ----
    @classmethod
    def connect(cls, port=None, wait=30.0, versions=SPEAKS):
        """Connects to simbob on 127.0.0.1:port (default $SIMBOB_PORT), retrying for `wait` s."""
        port = int(os.environ["SIMBOB_PORT"]) if port is None else port
        deadline = time.monotonic() + wait
        while True:
            try:
                return cls(socket.create_connection(("127.0.0.1", port), timeout=wait), versions)
            except ConnectionRefusedError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)

    @classmethod
    def accept(cls, port=None, wait=30.0, versions=SPEAKS):
        """Listens on 127.0.0.1:port (default $SIMBOB_PORT) until simbob connects (IsServer false)."""
        port = int(os.environ["SIMBOB_PORT"]) if port is None else port
        server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind(("127.0.0.1", port))
        server.listen(1)
        server.settimeout(wait)
        conn, _ = server.accept()
        server.close()
        return cls(conn, versions)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.sock.close()

    # ---- the protocol ----
    def state(self):
        """The next state block (the first call returns the one at t = 0), or None after 'bye'."""
        if self._first is not None:
            s, self._first = self._first, None
            return s
        while True:
            w = self._line().split()
            if not w:
                continue
            if w[0] == "bye":
                self.ended = float(w[1])
                return None
            if w[0] == "error":
                raise SimbobError(" ".join(w[1:]))
            if w[0] == "t" and len(w) >= 2:
                break  # anything else before 't' is a line this client does not know
        s = State(float(w[1]))
        while (line := self._line()) != "end":
            w = line.split()
            if len(w) < 2:
                continue
            key = unescape_key(w[1])
            if w[0] == "joint" and len(w) >= 4:
                s.joints[key] = (float(w[2]), float(w[3]))
            elif w[0] == "sensor":
                s.sensors[key] = [float(v) for v in w[2:]]
            elif w[0] == "body" and len(w) >= 9:
                s.bodies[key] = [float(v) for v in w[2:]]
            elif w[0] == "image" and len(w) >= 5:
                s.images[key] = (int(w[2]), int(w[3]), self._bytes(int(w[4])))
        return s

    def reply(self, sets=(), subscribe=None, done=False):
        """One reply in one write: `set` lines (key, value...), subscriptions ({kind: [keys] or
        None for all}, kind "bodies", "joints", "sensors" or "cameras"; version 3), then 'step'
        (or 'done')."""
        text = []
        for kind, keys in (subscribe or {}).items():
            words = ["*"] if keys is None else [escape_key(k) for k in keys]
            text.append(" ".join(["subscribe", kind] + words))
        for key, *values in sets:
            text.append(" ".join(["set", escape_key(key)] + [repr(float(v)) for v in values]))
        text.append("done" if done else "step")
        self._send("\n".join(text) + "\n")

    # ---- internals ----
    def _hello(self):
        w = self._line().split()
        if len(w) < 4 or w[0] != "simbob" or not w[1].isdigit():
            raise SimbobError("not a simbob hello: " + " ".join(w))
        self.version, self.key, self.period = int(w[1]), unescape_key(w[2]), float(w[3])
        self.offered = [self.version]
        self.actuators, self.motions, self.joints, self.sensors, self.bodies = {}, [], {}, {}, []
        self.cameras = {}  # version 3: {key: (width, height, period)}
        while (line := self._line()) != "end":
            w = line.split()
            if len(w) >= 2 and w[0] == "versions":
                self.offered = [int(v) for v in w[1:] if v.isdigit()]
            elif len(w) >= 3 and w[0] == "actuator":
                self.actuators[unescape_key(w[1])] = w[2]
            elif len(w) >= 2 and w[0] == "motion":
                self.motions.append(unescape_key(w[1]))
            elif len(w) >= 3 and w[0] == "joint":
                self.joints[unescape_key(w[1])] = w[2]
            elif len(w) >= 2 and w[0] == "sensor":
                self.sensors[unescape_key(w[1])] = (w[2], int(w[3])) if len(w) >= 4 else ("proximity", 1)
            elif len(w) >= 2 and w[0] == "body":
                self.bodies.append(unescape_key(w[1]))
            elif len(w) >= 5 and w[0] == "camera":
                self.cameras[unescape_key(w[1])] = (int(w[2]), int(w[3]), float(w[4]))

    def _line(self):
        while b"\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise SimbobError("simbob closed the connection")
            self.buf += chunk
        line, self.buf = self.buf.split(b"\n", 1)
        return line.rstrip(b"\r").decode("ascii")

    def _bytes(self, n):
        """Exactly n bytes (an image's block after its line)."""
        while len(self.buf) < n:
            chunk = self.sock.recv(max(65536, n - len(self.buf)))
            if not chunk:
                raise SimbobError("simbob closed the connection")
            self.buf += chunk
        data, self.buf = self.buf[:n], self.buf[n:]
        return data

    def _send(self, text):
        self.sock.sendall(text.encode("ascii"))
