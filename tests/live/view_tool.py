"""The mouse moving a contact tool through the live view (ctest
live/view_tool):

    view_tool.py TISSUEFEM SCENE EXPECTED WORKDIR [PROCESSES]

SCENE is the contact patch test tests/prm/contact_tool_patch_2d.prm (a
press, the half-space y > 0.5 seen from below, pushing a linear elastic
block down), here with the press's own motion set to 0, so that only the
page moves it. The test is a page that moves the press by the mouse,
(0, -0.025) before the step to t = 0.5 and (0, -0.05) before the step to
t = 1: the motion the scripted test gives the press, (0, -0.05 t). Checks:
- the greeting names the press as the obstacle the mouse moves, and the
  topology carries its drawing: a band whose front corners lie on the
  press's plane y = 0.5;
- each frame carries the press's pose, the translation the mouse asked,
  and the force the tissue exerts on it, equal to the run's
  tool_force-contact.csv at the same time;
- an offset that is not a number or farther than the body's diameter is
  refused with a message, and the run goes on;
- the run's summary equals EXPECTED, the closed form of the scripted
  test (tests/prm/contact_tool_patch_2d.output), once the mouse's lines
  are taken out: moving the press by the mouse is the same as scripting
  its motion;
- the run exits 0.
"""
import csv
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, expected, work = sys.argv[1:5]
processes = int(sys.argv[5]) if len(sys.argv) > 5 else 1
shutil.rmtree(work, ignore_errors=True)
check = wc.Checks()

run, host, port = wc.start_run(exe, scene, work, [
    "Contact/Obstacle 1/Motion=0; 0"] + wc.PAUSED_VIEW, processes)
try:
    page = wc.Page(host, port)
    page.until_step(0)
    greeting = page.of_type("scene")[0]
    check(greeting["obstacles"] == [{"name": "press", "role": "mouse"}],
          "the greeting names the press, moved by the mouse: %s"
          % greeting["obstacles"])
    drawn = page.topology["obstacles"]
    check(len(drawn) == 1 and len(drawn[0]["tri"]) == 6,
          "the press is drawn as two triangles")
    ys = sorted(drawn[0]["x"][1::3])
    check(ys[0] == 0.5 and ys[1] == 0.5 and ys[2] > 0.5,
          "the press's drawing: a band behind the plane y = 0.5: %s" % ys)

    page.send("tool 0 nan 0")
    page.send("tool 0 1e308 0")
    page.send("tool 0 -0.025 0")
    page.send("step")
    page.until_step(1)
    errors = [t["message"] for t in page.of_type("error")]
    check(any("three numbers" in e for e in errors),
          "an offset that is not a number is refused: %s" % errors)
    check(any("diameter" in e for e in errors),
          "an offset beyond the diameter is refused: %s" % errors)
    page.send("tool 0 -0.05 0")
    page.send("step")
    page.until_step(2)
    page.send("play")
    for step, offset in [(1, -0.025), (2, -0.05)]:
        press = page.frames[step]["obstacles"][0]
        check(abs(press["translation"][1] - offset) < 1e-7
              and abs(press["offset"][1] - offset) < 1e-7
              and press["translation"][0] == 0,
              "step %d: the press translated by (0, %g): %s"
              % (step, offset, press["translation"]))
        check(press["touching"], "step %d: the press touches" % step)
    page.until(lambda: page.of_type("end"))
    page.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()

# The frames' forces are the tool's as the run records them.
rows = list(csv.DictReader(open(os.path.join(
    work, "results", "tool_force-contact.csv"))))
by_time = {round(float(r["time"]), 9): r for r in rows}
for step, t in [(1, 0.5), (2, 1.0)]:
    f = page.frames[step]["obstacles"][0]["force"]
    row = by_time[t]
    recorded = (float(row["force_x"]), float(row["force_y"]))
    check(all(abs(f[d] - recorded[d]) <= 1e-6 * (1 + abs(recorded[d]))
              for d in range(2)),
          "t = %g: the frame's force %s is tool_force-contact.csv's %s"
          % (t, f[:2], recorded))

# The summary, the mouse's lines out, the contact tool's named as a single
# tool's, against the scripted test's closed form.
lines = open(os.path.join(work, "output")).read().splitlines()
kept = [l.replace("tool force (contact)", "tool force") for l in lines
        if "tool force (mouse)" not in l]
with open(os.path.join(work, "output.without_mouse"), "w") as f:
    f.write("\n".join(kept) + "\n")
check(subprocess.run(["numdiff", "-q", "-a", "1e-8", "-r", "1e-6",
                      os.path.join(work, "output.without_mouse"),
                      expected]).returncode == 0,
      "the summary equals the scripted press's closed form")
if check.failures:
    print(open(os.path.join(work, "run.log")).read()[-3000:])
    sys.exit(1)
print("live view tool: all checks passed")
