"""Dragging the tissue through the live view (ctest live/view_mouse):

    view_mouse.py TISSUEFEM SCENE WORKDIR [PROCESSES]

SCENE is a unit cube of St Venant-Kirchhoff material on 2 x 2 x 2
hexahedra held by rollers on x = 0, y = 0, z = 0 and otherwise free and
unloaded, solved quasistatically (prm/uniaxial_stretch_stvk.prm with the
pull on x = 1 taken away). The test is a page that, one step at a time,
grasps the corner (1, 1, 1), drags it by 0.01 per step to (0.05, 0, 0),
releases it and lets the run finish. Checks:
- the grasped vertex follows the drag exactly (the frames' displacement
  there equals the drag, float32) and the frames report the mouse holding,
  at the picked point, with the force of the previous step;
- energy balance, a law the code does not use: the work the mouse did,
  the trapezoidal sum of -f . dD over the steps from tool_force.csv (f the
  force of the tissue on the tool), equals the stored energy in the frame
  within 2 % (the response is nearly linear at 5 % strain);
- after the release the unloaded cube springs back: displacements and
  stored energy fall to 1e-6 of their peak;
- a grasp outside the body and a drag farther than its diameter are
  refused with a message, and the run goes on;
- the run exits 0.
"""
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, work = sys.argv[1:4]
processes = int(sys.argv[4]) if len(sys.argv) > 4 else 1
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()


run, host, port = wc.start_run(exe, scene, work, wc.PAUSED_VIEW + [
    "Boundary conditions/Dirichlet=0: x: 0 | 2: y: 0 | 4: z: 0",
    "Mouse/Grasp radius=0.01",
    "Time integration/Time step=0.1", "Output/Summary interval=1"],
    processes)
frames = {}
try:
    page = wc.WebSocket(host, port)
    page.sock.settimeout(20)
    topology = None
    errors = []

    def until_step(step):
        global topology
        while step not in frames:
            what, body = wc.decode(*page.receive())
            if what == "topology":
                topology = body
            elif what == "frame":
                frames[body["step"]] = body
            elif what == "text" and body.get("type") == "error":
                errors.append(body["message"])
        return frames[step]

    until_step(0)
    corner = [i for i in range(topology["n"])
              if topology["x"][3 * i:3 * i + 3] == (1.0, 1.0, 1.0)]
    check(len(corner) == 1, "the corner (1, 1, 1) is a surface vertex")
    corner = corner[0]

    page.send_text("grasp 5 5 5")
    page.send_text("grasp 1 1 1")
    page.send_text("drag 3 0 0")
    page.send_text("drag 0 0 0")
    page.send_text("step")
    first = until_step(1)
    check(any("outside the body" in e for e in errors),
          "a grasp outside the body is refused: %s" % errors)
    check(any("diameter" in e for e in errors),
          "a drag beyond the diameter is refused: %s" % errors)
    check(first["holding"] and first["grasp_point"] == (1.0, 1.0, 1.0),
          "the frame shows the mouse holding at the picked point")
    for k in range(1, 6):
        page.send_text("drag %g 0 0" % (0.01 * k))
        page.send_text("step")
        frame = until_step(1 + k)
        u = frame["u"][3 * corner:3 * corner + 3]
        check(abs(u[0] - 0.01 * k) < 1e-7 and abs(u[1]) < 1e-7 and
              abs(u[2]) < 1e-7,
              "step %d: the corner at %s, not (%g, 0, 0)" % (1 + k, u,
                                                          0.01 * k))
    peak = frames[6]["stored"]
    page.send_text("release")
    page.send_text("step")
    after = until_step(7)
    check(not after["holding"], "released")
    largest = max(abs(x) for x in after["u"])
    check(largest <= 1e-6 * 0.05 and after["stored"] <= 1e-6 * peak,
          "springs back: |u| %g, energy %g of the peak" %
          (largest, after["stored"] / peak))
    page.send_text("play")
    while True:
        what, body = wc.decode(*page.receive())
        if what == "text" and body.get("type") == "end":
            break
    page.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()

# Work by the mouse against the stored energy at the peak (t = 0.6).
rows = list(csv.DictReader(open(os.path.join(work, "results",
                                             "tool_force.csv"))))
by_time = {round(float(r["time"]), 9): r for r in rows}
work_done = 0.0
for k in range(1, 6):
    a, b = by_time[round(0.1 * (1 + k), 9)], by_time[round(0.1 * k, 9)]
    check(abs(float(a["tool_x"]) - 0.01 * k) < 1e-12 and a["holding"] == "1",
          "tool_force.csv at t = %g: the drag" % (0.1 * (1 + k)))
    df = 0.5 * (float(a["force_x"]) + float(b["force_x"]))
    work_done -= df * (float(a["tool_x"]) - float(b["tool_x"]))
check(peak > 0 and abs(work_done - peak) <= 0.02 * peak,
      "work of the mouse %g against stored energy %g" % (work_done, peak))
print("work of the mouse %.6g, stored energy %.6g (relative difference %.2e)"
      % (work_done, peak, abs(work_done - peak) / peak))
if check.failures:
    print(open(os.path.join(work, "run.log")).read()[-3000:])
    sys.exit(1)
print("live view mouse: all checks passed")
