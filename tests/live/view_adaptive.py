"""The live view across mesh changes (ctest live/view_adaptive):

    view_adaptive.py TISSUEFEM SCENE EXPECTED_OUTPUT WORKDIR

SCENE is the homogeneous uniaxial stretch of a neo-Hookean unit cube with
the mesh adapted after every load step (prm/uniaxial_stretch_adaptive.prm,
hanging nodes included), started paused. A page reads everything the run
sends and asks for one step after each frame. Checks:
- a new topology arrives after the mesh changes (at least 3 in all, each
  larger than the one before), and every frame has the vertex count of the
  topology before it;
- every frame's displacements equal the closed form on whatever mesh:
  stretch l = 1 + 0.2 t along x, lateral stretch s from P_yy = mu s +
  (lambda ln(l s^2) - mu) / s = 0 (bisection), u = (0.2 t X, (s - 1) Y,
  (s - 1) Z), relative 1e-5 (float32) -- hanging vertices included;
- the run exits 0 and its summary equals EXPECTED_OUTPUT (the closed form
  of the run without a view).
"""
import math
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, expected, work = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()


lam, mu = wc.lame(1000.0, 0.3)


def lateral(t):
    l = 1 + 0.2 * t
    p = lambda s: mu * s + (lam * math.log(l * s * s) - mu) / s
    lo, hi = 0.5, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if p(lo) * p(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


run, host, port = wc.start_run(exe, scene, work, wc.PAUSED_VIEW)
# One step per frame seen ('step' after each): every state is checked.
topologies, frames, meshes = [], 0, set()
try:
    page = wc.WebSocket(host, port)
    page.sock.settimeout(60)
    while True:
        what, body = wc.decode(*page.receive())
        if what == "topology":
            topologies.append(body)
        elif what == "frame":
            frames += 1
            meshes.add(len(topologies))
            page.send_text("step")
            x = topologies[-1]["x"]
            check(body["n"] == topologies[-1]["n"],
                  "step %d: %d vertices, the topology has %d" %
                  (body["step"], body["n"], topologies[-1]["n"]))
            t, s = body["time"], lateral(body["time"])
            worst = 0.0
            for i in range(min(body["n"], topologies[-1]["n"])):
                X = x[3 * i:3 * i + 3]
                exact = (0.2 * t * X[0], (s - 1) * X[1], (s - 1) * X[2])
                for d in range(3):
                    worst = max(worst, abs(body["u"][3 * i + d] - exact[d]))
            check(not worst > 1e-5 * max(0.2 * t, 1e-3),
                  "step %d: displacement off the closed form by %g" %
                  (body["step"], worst))
        elif what == "text" and body.get("type") == "end":
            break
    page.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()
sizes = [t["n"] for t in topologies]
print("topologies (surface vertices): %s; frames: %d" % (sizes, frames))
check(len(sizes) >= 3 and all(b > a for a, b in zip(sizes, sizes[1:])),
      "a new, larger topology after each mesh change")
check(frames == 5 and len(meshes) >= 3,
      "a frame of every state (5: %d) on at least 3 meshes (%d)" %
      (frames, len(meshes)))
check(wc.same_summary(os.path.join(work, "output"), expected),
      "summary file equals the closed form (the mouse's force lines zero)")
if check.failures:
    print(open(os.path.join(work, "run.log")).read()[-3000:])
    sys.exit(1)
print("live view adaptive: all checks passed")
