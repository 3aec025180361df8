"""The scene's own grasping tool in the live view (ctest live/view_grasp):

    view_grasp.py TISSUEFEM SCENE WORKDIR

SCENE is Jeffrey's muscle (parameters/jeffrey_muscle.prm): its grasping
tool holds the vertices near (0.015, 0, 0.075) from t = 0 and moves them
by d(t) = (0.075 min(t, 0.2), 0, 0). The test is a page that steps the run
three times (time step 5e-5). Checks:
- the greeting says the mouse cannot grasp (the scene's tool holds the
  tissue);
- each frame's grasp block shows the scene's tool holding, at its grasp
  point, moved by d(t) (the trajectory's closed form), with the force of
  the tissue on it after the previous step: the row of the run's
  tool_force.csv at that step's time (non-zero from the second step);
- the run ends with exit 0.
"""
import csv
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()

run, host, port = wc.start_run(exe, scene, work, [
    "Output/Directory=results", "Output/VTU/Interval=0",
    "Time integration/End time=0.001"] + wc.PAUSED_VIEW)
try:
    page = wc.Page(host, port)
    page.until_step(0)
    mouse = page.of_type("scene")[0]["mouse"]
    check("grasping tool" in mouse, "the mouse cannot grasp: %s" % mouse)
    for k in range(1, 4):
        page.send("step")
        page.until_step(k)
    page.play_to_end()
    page.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()

rows = list(csv.DictReader(open(os.path.join(work, "results",
                                             "tool_force.csv"))))
for k in range(1, 4):
    frame, t = page.frames[k], 5e-5 * k
    check(frame["holding"], "step %d: the frame shows the tool holding" % k)
    check(all(abs(a - b) < 1e-7 for a, b in
              zip(frame["grasp_point"], (0.015, 0, 0.075))),
          "step %d: at the grasp point: %s" % (k, frame["grasp_point"]))
    check(abs(frame["drag"][0] - 0.075 * t) < 1e-10 * (1 + k)
          and frame["drag"][1] == 0 and frame["drag"][2] == 0,
          "step %d: moved by d(t) = (%g, 0, 0): %s" % (k, 0.075 * t,
                                                       frame["drag"]))
    previous = rows[k - 1]
    recorded = [float(previous["force_" + c]) for c in "xyz"]
    size = sum(f * f for f in recorded) ** 0.5
    # Held from t = 0, the tissue pulls back from the second step on.
    check((size > 0 or k == 1) and all(abs(a - b) <= 1e-6 * max(size, 1e-12)
                                       for a, b in zip(frame["force"],
                                                       recorded)),
          "step %d: the force %s is tool_force.csv's at t = %s (%s)"
          % (k, frame["force"], previous["time"], recorded))
if check.failures:
    print(open(os.path.join(work, "run.log")).read()[-3000:])
    sys.exit(1)
print("live view grasping tool: all checks passed")
