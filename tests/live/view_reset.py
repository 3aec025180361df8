"""Reset from the live view (ctest live/view_reset):

    view_reset.py TISSUEFEM SCENE EXPECTED_OUTPUT WORKDIR [PROCESSES]

SCENE is the homogeneous uniaxial stretch of prm/uniaxial_stretch_stvk.prm
(as live/view_stream), run with the live view on, started paused, in steps
of 0.05. The test is a page that steps the run to t = 0.15 with the mouse
holding a corner dragged away, then asks for a reset. Checks:
- the page is told 'reset' and its connection closes; the run serves the
  same address again, where the page reconnects and gets a new greeting,
  the topology and a frame of step 0 at t = 0 with zero displacement,
  stored energy 0 and the mouse not holding;
- a page asks for a reset only as the driver: a watcher's is refused;
- the run started again goes to its end: exit 0, and its summary file
  equals EXPECTED_OUTPUT (the closed form of the run without a view; the
  steps before the reset, with their drag, leave nothing in it);
- the run's log says it started again.
"""
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

run, host, port = wc.start_run(exe, scene, work, wc.PAUSED_VIEW + [
    "Output/Live view/Frame rate=240",
    "Time integration/Time step=0.05", "Output/Summary interval=20"],
    processes)


try:
    page = wc.Page(host, port)
    page.until_step(0)
    watcher = wc.Page(host, port)
    watcher.until(lambda: bool(watcher.of_type("role")))
    watcher.send("reset")
    watcher.until(lambda: bool(watcher.of_type("error")))
    refusals = [t.get("message", "") for t in watcher.of_type("error")]
    check(any("drives" in m or "watch" in m for m in refusals),
          "a watcher's reset is refused: %s" % refusals)
    watcher.close()

    page.send("grasp 1 1 1")
    page.send("drag 0 0.05 0")
    for k in range(1, 4):
        page.send("step")
        page.until_step(k)
    check(page.frames[3]["holding"] and page.frames[3]["stored"] > 0,
          "before the reset: the mouse holds, the body stores energy")
    page.send("reset")
    try:
        page.until(lambda: bool(page.of_type("reset")))
        page.until(lambda: False)
    except ConnectionError:
        pass
    check(bool(page.of_type("reset")), "the page is told 'reset'")

    # The same address again (the run sets up anew first).
    again = None
    for _ in range(200):
        try:
            again = wc.Page(host, port)
            break
        except OSError:
            time.sleep(0.05)
    check(again is not None, "the run serves the same address again")
    again.until_step(0)
    first = again.frames[0]
    check(bool(again.of_type("scene")), "a new greeting")
    check(first["time"] == 0 and max(abs(x) for x in first["u"]) == 0
          and first["stored"] == 0 and not first["holding"],
          "step 0 at t = 0: no displacement, no energy, no grasp")
    again.play_to_end()
    again.close()
    check(run.wait(timeout=60) == 0, "tissuefem exited 0")
finally:
    if run.poll() is None:
        run.kill()

log = open(os.path.join(work, "run.log")).read()
check("starts again from t = 0" in log, "the log says the run started again")
check(wc.same_summary(os.path.join(work, "output"), expected),
      "the summary of the run started again equals the closed form")
if check.failures:
    print(log[-3000:])
    sys.exit(1)
print("live view reset: all checks passed")
