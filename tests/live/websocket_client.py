"""A WebSocket client from the standard library alone (RFC 6455), for the
live view's tests: the handshake, masked frames out, frames in, and the
means to send broken ones (unmasked, oversized, bad opcodes)."""
import base64
import hashlib
import json
import os
import socket
import struct
import subprocess
import time


class Checks:
    """check(condition, what): records and prints a failed check; the
    failures are in check.failures."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, what):
        if not condition:
            self.failures.append(what)
            print("FAILED:", what)


def lame(E, nu):
    """Lame's lambda and mu from Young's modulus and Poisson's ratio."""
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


# The live view on any free port, waiting for a page and paused, stepping
# as fast as it can: how the scripted pages start a run (settings for
# start_run).
PAUSED_VIEW = ["Output/Live view/Port=0", "Output/Live view/Wait for page=60",
               "Output/Live view/Start paused=true",
               "Output/Live view/Pace=as fast as possible"]


def start_run(exe, scene, work, settings, processes=1):
    """Starts tissuefem on SCENE in WORK with --set SETTINGS (on PROCESSES
    MPI processes); returns the process and the page's address (from
    results/live_view)."""
    os.makedirs(work, exist_ok=True)
    command = [exe, scene]
    if processes > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(processes)] + command
    for s in settings:
        command += ["--set", s]
    log = open(os.path.join(work, "run.log"), "w")
    run = subprocess.Popen(command, cwd=work, stdout=log,
                           stderr=subprocess.STDOUT)
    address = os.path.join(work, "results", "live_view")
    for _ in range(300):
        if os.path.exists(address):
            break
        if run.poll() is not None:
            raise SystemExit("tissuefem exited early: "
                             + open(os.path.join(work, "run.log")).read())
        time.sleep(0.05)
    url = open(address).read().strip()
    host, port = url[len("http://"):].rstrip("/").split(":")
    return run, host, int(port)


def http_get(host, port, target, extra=b""):
    """One raw request; returns (status code, body bytes)."""
    with socket.create_connection((host, port), timeout=10) as s:
        s.sendall(b"GET " + target.encode() + b" HTTP/1.1\r\nHost: x\r\n"
                  b"Connection: close\r\n" + extra + b"\r\n")
        data = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split()[1]), body


class WebSocket:
    def __init__(self, host, port, path="/ws"):
        self.sock = socket.create_connection((host, port), timeout=10)
        key = base64.b64encode(os.urandom(16))
        self.sock.sendall(b"GET " + path.encode() + b" HTTP/1.1\r\n"
                          b"Host: x\r\nUpgrade: websocket\r\n"
                          b"Connection: Upgrade\r\nSec-WebSocket-Key: " + key
                          + b"\r\nSec-WebSocket-Version: 13\r\n\r\n")
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                raise ConnectionError("closed during the handshake")
            head += chunk
        self.status = int(head.split()[1])
        accept = base64.b64encode(hashlib.sha1(
            key + b"258EAFA5-E914-47DA-95CA-C5AB0DC85B11").digest())
        if self.status == 101 and accept not in head:
            raise ConnectionError("wrong Sec-WebSocket-Accept")
        self.buffer = b""

    def raw(self, data):
        self.sock.sendall(data)

    @staticmethod
    def frame(opcode, payload, mask=True, fin=True):
        first = (0x80 if fin else 0) | opcode
        n = len(payload)
        if n < 126:
            head = struct.pack("!BB", first, (0x80 if mask else 0) | n)
        elif n < 65536:
            head = struct.pack("!BBH", first, (0x80 if mask else 0) | 126, n)
        else:
            head = struct.pack("!BBQ", first, (0x80 if mask else 0) | 127, n)
        if not mask:
            return head + payload
        key = os.urandom(4)
        return head + key + bytes(b ^ key[i % 4] for i, b in
                                  enumerate(payload))

    def send_text(self, text):
        self.raw(self.frame(1, text.encode()))

    def _read(self, n):
        while len(self.buffer) < n:
            chunk = self.sock.recv(1 << 20)
            if not chunk:
                raise ConnectionError("closed")
            self.buffer += chunk
        data, self.buffer = self.buffer[:n], self.buffer[n:]
        return data

    def _frame(self):
        first, second = self._read(2)
        n = second & 0x7F
        if n == 126:
            n = struct.unpack("!H", self._read(2))[0]
        elif n == 127:
            n = struct.unpack("!Q", self._read(8))[0]
        return first & 0x80 != 0, first & 0x0F, self._read(n)

    def receive(self):
        """The next message: (opcode, payload), its fragments joined;
        opcode 8 is a close. Pings are answered and skipped."""
        while True:
            fin, opcode, payload = self._frame()
            if opcode == 9:
                self.raw(self.frame(10, payload))
                continue
            if opcode == 10:
                continue
            while not fin:
                fin, _, more = self._frame()
                payload += more
            return opcode, payload

    def close(self):
        try:
            self.raw(self.frame(8, struct.pack("!H", 1000)))
        except OSError:
            pass
        self.sock.close()


def decode(opcode, payload):
    """A message as ('text', dict), ('topology', dict) or ('frame', dict)."""
    if opcode == 1:
        return "text", json.loads(payload)
    magic = payload[:4]
    if magic == b"TFT1":
        n, m, dim = struct.unpack_from("<III", payload, 4)
        x = struct.unpack_from("<%df" % (3 * n), payload, 16)
        tri = struct.unpack_from("<%dI" % (3 * m), payload, 16 + 12 * n)
        # The obstacles' drawings: corners (x y z) and triangles of each.
        at, obstacles = 16 + 12 * n + 12 * m, []
        (count,) = struct.unpack_from("<I", payload, at)
        at += 4
        for _ in range(count):
            corners, triangles = struct.unpack_from("<II", payload, at)
            at += 8
            xs = struct.unpack_from("<%df" % (3 * corners), payload, at)
            at += 12 * corners
            ts = struct.unpack_from("<%dI" % (3 * triangles), payload, at)
            at += 12 * triangles
            obstacles.append({"x": xs, "tri": ts})
        return "topology", {"n": n, "m": m, "dim": dim, "x": x, "tri": tri,
                            "obstacles": obstacles}
    if magic == b"TFF1":
        step, n, field, flags = struct.unpack_from("<IIII", payload, 4)
        numbers = struct.unpack_from("<10d", payload, 20)
        u = struct.unpack_from("<%df" % (3 * n), payload, 100)
        values = (struct.unpack_from("<%df" % n, payload, 100 + 12 * n)
                  if field > 0 else None)
        at = 100 + 12 * n + (4 * n if field > 0 else 0)
        mouse = struct.unpack_from("<10f", payload, at)
        # Each obstacle: translation, rotation (row by row), the force of
        # the tissue on it, touching, the mouse's offset (19 floats).
        obstacles = []
        for k in range((len(payload) - at - 40) // 76):
            b = struct.unpack_from("<19f", payload, at + 40 + 76 * k)
            obstacles.append({"translation": b[0:3], "rotation": b[3:12],
                              "force": b[12:15], "touching": b[15] != 0,
                              "offset": b[16:19]})
        names = ["time", "dt", "step_seconds", "stored", "kinetic", "rate",
                 "frame_ms", "budget", "latency_median", "latency_p99"]
        frame = dict(zip(names, numbers))
        frame.update(step=step, n=n, field=field, flags=flags, u=u,
                     values=values, bytes=len(payload),
                     holding=mouse[0] != 0, grasp_point=mouse[1:4],
                     drag=mouse[4:7], force=mouse[7:10], obstacles=obstacles)
        return "frame", frame
    return "unknown", payload


class Page:
    """A page on the live view at HOST:PORT: its messages as they arrive,
    kept as frames (by step), the last topology and the text messages."""

    def __init__(self, host, port, timeout=20):
        self.socket = WebSocket(host, port)
        self.socket.sock.settimeout(timeout)
        self.frames, self.texts, self.topology = {}, [], None

    def until(self, test):
        """Reads messages until TEST() holds."""
        while not test():
            what, body = decode(*self.socket.receive())
            if what == "frame":
                self.frames[body["step"]] = body
            elif what == "topology":
                self.topology = body
            elif what == "text":
                self.texts.append(body)

    def until_step(self, step):
        """Reads until the frame of STEP has come; returns it."""
        self.until(lambda: step in self.frames)
        return self.frames[step]

    def of_type(self, kind):
        """The text messages of type KIND so far."""
        return [t for t in self.texts if t.get("type") == kind]

    def send(self, text):
        self.socket.send_text(text)

    def play_to_end(self):
        """Plays the run and reads until it says it ended."""
        self.send("play")
        self.until(lambda: self.of_type("end"))

    def close(self):
        self.socket.close()


def same_summary(output, expected):
    """Whether the summary file OUTPUT of a run with the live view equals
    EXPECTED (that of the run without it) by numdiff, once the lines of the
    mouse tool (which the live view adds) are taken out; those must all
    read zero when no page grasped."""
    lines = open(output).read().splitlines()
    mouse = [l for l in lines if "tool force" in l]
    if any(not l.endswith("tool force = 0 0 0") for l in mouse):
        print("the mouse tool's force is not zero:", mouse[:3])
        return False
    with open(output + ".without_mouse", "w") as f:
        f.write("\n".join(l for l in lines if "tool force" not in l) + "\n")
    return subprocess.run(["numdiff", "-q", "-a", "1e-8", "-r", "1e-6",
                           output + ".without_mouse", expected]).returncode == 0
