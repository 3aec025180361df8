"""Malformed input at the live view's server (ctest live/view_fuzz):

    view_fuzz.py TISSUEFEM SCENE EXPECTED_OUTPUT WORKDIR [SEED]

Runs SCENE with the live view on, started paused, a driving page connected
and reading. While it waits, throws at the server, from a fixed seed:
random bytes, garbage request lines, a header beyond the 8 kB limit, a
request with a body, unknown methods, traversal paths, half requests,
upgrades elsewhere, without a key and from another web site (Origin), and, on WebSocket connections,
unmasked frames, oversized messages, binary messages, bad opcodes,
invalid UTF-8, fragments, random bytes, watchers' commands and a page
that never reads. Then the driving page must still get answers, the page
must still be served, and after 'play' the run must end with exit 0 and a
summary file equal to EXPECTED_OUTPUT (the closed form of the run without
a view), with the refusals in its log.
"""
import os
import random
import shutil
import socket
import struct
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, expected, work = sys.argv[1:5]
seed = int(sys.argv[5]) if len(sys.argv) > 5 else 20261128
rng = random.Random(seed)
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()


def raw_http(data, read=True):
    """Sends DATA on a new connection; returns what came back (b'' if
    the server closed without answering)."""
    try:
        with socket.create_connection((host, port), timeout=5) as s:
            s.sendall(data)
            if not read:
                return b""
            s.shutdown(socket.SHUT_WR)
            answer = b""
            while True:
                chunk = s.recv(65536)
                if not chunk:
                    return answer
                answer += chunk
    except OSError:
        return b""


def status_of(answer):
    try:
        return int(answer.split()[1])
    except (IndexError, ValueError):
        return 0


def ws_abuse(frames, expect_close):
    """Opens a WebSocket, sends FRAMES (bytes), reads until closed or 1 s
    of quiet; returns whether the server closed it."""
    try:
        w = wc.WebSocket(host, port)
        for f in frames:
            w.raw(f)
        w.sock.settimeout(1)
        while True:
            opcode, _ = w.receive()
            if opcode == 8:
                return True
    except socket.timeout:
        w.sock.close()
        return False
    except (ConnectionError, OSError):
        return True


run, host, port = wc.start_run(exe, scene, work, wc.PAUSED_VIEW + [
    "Time integration/Time step=0.05", "Output/Summary interval=20"])
try:
    driver = wc.WebSocket(host, port)
    driver.sock.settimeout(20)

    # HTTP.
    for _ in range(20):
        raw_http(bytes(rng.randrange(256) for _ in range(rng.randrange(1, 4096))))
    check(status_of(raw_http(b"GARBAGE\r\n\r\n")) == 400,
          "a garbage request line is answered 400")
    check(status_of(raw_http(b"GET / HTTP/1.1\r\nX-Big: " + b"a" * 20000
                             + b"\r\n\r\n")) in (0, 400),
          "a header beyond the limit is refused")
    check(status_of(raw_http(b"POST / HTTP/1.1\r\nHost: x\r\n"
                             b"Content-Length: 5\r\n\r\nhello")) in (400, 405),
          "a request with a body is refused")
    check(status_of(raw_http(b"DELETE / HTTP/1.1\r\nHost: x\r\n\r\n")) == 405,
          "an unknown method is answered 405")
    for target in (b"/../../../../etc/passwd", b"/..%2f..%2fetc%2fpasswd",
                   b"/view.js/../../CMakeLists.txt", b"/" + b"a" * 6000,
                   b"/\x00", b"*"):
        check(status_of(raw_http(b"GET " + target + b" HTTP/1.1\r\nHost: x"
                                 b"\r\n\r\n")) in (0, 400, 404),
              "GET %r is refused" % target[:40])
    raw_http(b"GET / HTTP/1.1\r\nHo", read=False)
    check(status_of(raw_http(b"GET /other HTTP/1.1\r\nHost: x\r\nUpgrade: "
                             b"websocket\r\nConnection: Upgrade\r\n"
                             b"Sec-WebSocket-Key: AAAAAAAAAAAAAAAAAAAAAA==\r\n"
                             b"Sec-WebSocket-Version: 13\r\n\r\n")) == 404,
          "an upgrade elsewhere than /ws is answered 404")
    raw_http(b"GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\n"
             b"Connection: Upgrade\r\n\r\n")
    upgrade = (b"GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\n"
               b"Connection: Upgrade\r\nSec-WebSocket-Key: "
               b"AAAAAAAAAAAAAAAAAAAAAA==\r\nSec-WebSocket-Version: 13\r\n")
    check(status_of(raw_http(upgrade + b"Origin: http://evil.example\r\n\r\n"))
          == 403, "a WebSocket from another web site is refused (403)")
    check(status_of(raw_http(upgrade + b"Origin: http://127.0.0.1:%d\r\n\r\n"
                             % port)) == 101,
          "a WebSocket from the server's own page is accepted")
    sockets = [socket.create_connection((host, port)) for _ in range(50)]
    for s in sockets:
        s.close()

    # WebSocket.
    frame = wc.WebSocket.frame
    check(ws_abuse([frame(1, b"pause", mask=False)], True),
          "an unmasked frame closes the connection")
    check(ws_abuse([frame(1, b"x" * 4096)], True),
          "an oversized message closes the connection")
    check(ws_abuse([frame(3, b"??")], True),
          "a reserved opcode closes the connection")
    check(ws_abuse([frame(1, b"\xff\xfe\xfd")], True),
          "invalid UTF-8 closes the connection")
    ws_abuse([frame(1, b"pa", fin=False), frame(0, b"use")], False)
    ws_abuse([frame(2, os.urandom(100))], False)
    for _ in range(10):
        ws_abuse([bytes(rng.randrange(256) for _ in range(rng.randrange(1, 300)))],
                 True)
        ws_abuse([frame(1, bytes(rng.choice(b"abcdefgh pqrs0123.-e")
                                 for _ in range(rng.randrange(0, 200))))], False)
    sleeper = wc.WebSocket(host, port)  # never reads

    # The run is unharmed: the driver is answered, the page is served.
    driver.send_text("nonsense")
    while True:
        what, body = wc.decode(*driver.receive())
        if what == "text" and body.get("type") == "error":
            check("unknown command" in body["message"], "the driver answered")
            break
    status, page = wc.http_get(host, port, "/")
    check(status == 200 and b"TissueFEM live view" in page,
          "the page is still served")
    driver.send_text("play")
    while True:
        what, body = wc.decode(*driver.receive())
        if what == "text" and body.get("type") == "end":
            break
    driver.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
    sleeper.sock.close()
finally:
    if run.poll() is None:
        run.kill()

check(wc.same_summary(os.path.join(work, "output"), expected),
      "summary file equals the closed form (the mouse's force lines zero)")
log = open(os.path.join(work, "run.log")).read()
check("malformed HTTP request refused" in log, "refusals are logged")
check("no such page file" in log, "unknown paths are logged")
if check.failures:
    print(log[-3000:])
    sys.exit(1)
print("live view fuzz (seed %d): all checks passed" % seed)
