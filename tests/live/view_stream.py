"""The live view's messages against a closed form (ctest live/view_stream):

    view_stream.py TISSUEFEM SCENE EXPECTED_OUTPUT WORKDIR [PROCESSES]

SCENE is the homogeneous uniaxial stretch of a unit cube of St Venant-
Kirchhoff material on 2 x 2 x 2 hexahedra (prm/uniaxial_stretch_stvk.prm),
run with the live view on, started paused, in steps of 0.05. The test is a
page: it fetches the page's files, connects a driving and a watching
WebSocket, and checks
- the files served, and 404 for every path not on the list;
- the topology: the cube's surface, 26 vertices and 48 triangles, all on
  the faces, each turned outwards;
- the roles: the watcher's commands are refused;
- pause and step: no step while paused, exactly one per 'step';
- every frame's displacements, J and von Mises stress against the closed
  form: stretch l = 1 + 0.2 t along x, lateral stretch s = sqrt(1 + 2 b)
  with b = -lambda a / (2 (lambda + mu)), a = (l^2 - 1) / 2 (S_yy = 0),
  u = (0.2 t X, (s - 1) Y, (s - 1) Z), J = l s^2, von Mises = |sigma_xx| =
  l^2 S_xx / J; float32 in the frames, so relative 1e-5;
- the run ends with exit 0, sends 'end', and its summary file equals
  EXPECTED_OUTPUT (the closed form of the run without a view).
"""
import math
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, expected, work = sys.argv[1:5]
processes = int(sys.argv[5]) if len(sys.argv) > 5 else 1
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()


lam, mu = wc.lame(1000.0, 0.3)


def closed_form(t):
    l = 1 + 0.2 * t
    a = (l * l - 1) / 2
    b = -lam * a / (2 * (lam + mu))
    s = math.sqrt(1 + 2 * b)
    S_xx = lam * (a + 2 * b) + 2 * mu * a
    J = l * s * s
    return l, s, J, abs(l * l * S_xx / J)


def check_frame(frame, x):
    l, s, J, von_mises = closed_form(frame["time"])
    worst = 0.0
    for i in range(frame["n"]):
        X = x[3 * i:3 * i + 3]
        exact = (0.2 * frame["time"] * X[0], (s - 1) * X[1], (s - 1) * X[2])
        for d in range(3):
            worst = max(worst, abs(frame["u"][3 * i + d] - exact[d]))
    # A NaN must fail: compare with 'not <='.
    check(not worst > 1e-5 * max(0.2 * frame["time"], 1e-3) and
          worst == worst,
          "step %d: displacement off the closed form by %g" %
          (frame["step"], worst))
    if frame["field"] in (1, 2):
        exact = J if frame["field"] == 1 else von_mises
        off = max(abs(v - exact) for v in frame["values"]) / max(exact, 1e-3)
        check(off <= 1e-5, "step %d: field %d off by %g (relative)" %
              (frame["step"], frame["field"], off))


backlog = {}


def next_of(ws, kind, timeout=20):
    """The next message of KIND (texts are dicts with 'type'); messages of
    other kinds are kept for later calls, except frames (only the newest
    matters)."""
    queue = backlog.setdefault((id(ws), kind), [])
    if queue:
        return queue.pop(0)
    end = time.time() + timeout
    while time.time() < end:
        what, body = wc.decode(*ws.receive())
        if what == "text":
            what = body.get("type")
        if what == kind:
            return body
        if what != "frame":
            backlog.setdefault((id(ws), what), []).append(body)
    raise TimeoutError("no " + kind)


run, host, port = wc.start_run(exe, scene, work, wc.PAUSED_VIEW + [
    "Output/Live view/Frame rate=240",
    "Time integration/Time step=0.05", "Output/Summary interval=20"],
    processes)
try:
    status, body = wc.http_get(host, port, "/")
    check(status == 200 and b"TissueFEM live view" in body, "GET / gave the page")
    for name in ("/view.js", "/view.css", "/three.min.js", "/OrbitControls.js"):
        status, body = wc.http_get(host, port, name)
        check(status == 200 and len(body) > 100, "GET %s: %d" % (name, status))
    for name in ("/../CMakeLists.txt", "/%2e%2e/CMakeLists.txt", "/etc/passwd",
                 "//usr/share/javascript/three/build/three.js", "/web/view.js"):
        status, _ = wc.http_get(host, port, name)
        check(status == 404, "GET %s: %d, not 404" % (name, status))

    page = wc.WebSocket(host, port)
    check(page.status == 101, "WebSocket upgrade")
    greeting = next_of(page, "scene")
    check(greeting["fields"][:3] == ["displacement", "J", "von Mises"],
          "fields offered: %s" % greeting["fields"])
    topology = next_of(page, "topology")
    check((topology["n"], topology["m"], topology["dim"]) == (26, 48, 3),
          "cube surface: %d vertices, %d triangles" %
          (topology["n"], topology["m"]))
    x = topology["x"]
    check(all(min(abs(c), abs(c - 1)) < 1e-7 for c in
              (min(x[3 * i:3 * i + 3], key=lambda c: min(abs(c), abs(c - 1)))
               for i in range(topology["n"]))),
          "every surface vertex lies on a face of the cube")
    outward = 0
    for k in range(topology["m"]):
        p = [x[3 * v:3 * v + 3] for v in topology["tri"][3 * k:3 * k + 3]]
        e1 = [p[1][d] - p[0][d] for d in range(3)]
        e2 = [p[2][d] - p[0][d] for d in range(3)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0])
        c = [sum(q[d] for q in p) / 3 - 0.5 for d in range(3)]
        outward += sum(n[d] * c[d] for d in range(3)) > 0
    check(outward == topology["m"], "%d of 48 triangles turned outwards" %
          outward)
    check(next_of(page, "role")["drives"], "the first page drives")
    first = next_of(page, "frame")
    check(first["step"] == 0 and first["flags"] & 1, "paused at step 0")

    watcher = wc.WebSocket(host, port)
    check(not next_of(watcher, "role")["drives"], "the second page watches")
    watcher.send_text("play")
    check("drives" in next_of(watcher, "error")["message"],
          "a watcher's command is refused")

    # Paused: no new step within half a second.
    page.sock.settimeout(0.5)
    try:
        what, body = wc.decode(*page.receive())
        check(what != "frame" or body["step"] == 0, "a step while paused")
    except OSError:
        pass
    page.sock.settimeout(20)
    for field, step in ((0, 1), (1, 2), (2, 3)):
        page.send_text("field " + ["displacement", "J", "von Mises"][field])
        page.send_text("step")
        frame = next_of(page, "frame")
        while frame["step"] < step:
            frame = next_of(page, "frame")
        check(frame["step"] == step and frame["field"] == field,
              "'step' gave step %d field %d" % (frame["step"], frame["field"]))
        check_frame(frame, x)
    page.send_text("bogus command")
    check("unknown command" in next_of(page, "error")["message"],
          "an unknown command is answered with an error")
    page.send_text("field displacement")
    page.send_text("play")
    frames = 0
    while True:
        what, body = wc.decode(*page.receive())
        if what == "frame":
            frames += 1
            check_frame(body, x)
        elif what == "text" and body.get("type") == "end":
            check(abs(body["time"] - 1) < 1e-12, "ended at t = 1")
            break
    check(frames >= 1, "frames while playing")
    watcher.close()
    page.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()

check(wc.same_summary(os.path.join(work, "output"), expected),
      "summary file equals the closed form (the mouse's force lines zero)")
log = open(os.path.join(work, "run.log")).read()
check("live view: page 1 connected" in log, "the log names the pages")
if check.failures:
    print(log[-3000:])
    sys.exit(1)
print("live view stream: all checks passed")
