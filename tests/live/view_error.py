"""A run that fails tells its pages why (ctest live/view_error):

    view_error.py TISSUEFEM SCENE WORKDIR EXPECTED_TEXT

SCENE must stop in the solver (tests/solver_failure). Run with the live
view on and a page connected: the page must get the scene's greeting
naming the parameter file, then an error message marked fatal that
contains EXPECTED_TEXT, and the connection must close; tissuefem must exit
3 (solver failure) as without a view.
"""
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import websocket_client as wc  # noqa: E402

exe, scene, work, expected = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
run, host, port = wc.start_run(exe, scene, work, [
    "Output/Live view/Port=0", "Output/Live view/Wait for page=60",
    "Output/Live view/Pace=as fast as possible"])
failures = []
try:
    page = wc.WebSocket(host, port)
    page.sock.settimeout(60)
    greeting, fatal = None, None
    try:
        while True:
            opcode, payload = page.receive()
            if opcode == 8:
                break
            what, body = wc.decode(opcode, payload)
            if what == "text" and body["type"] == "scene":
                greeting = body
            if what == "text" and body["type"] == "error" and body.get("fatal"):
                fatal = body
    except ConnectionError:
        pass
    if not greeting or greeting.get("file") != scene:
        failures.append("the greeting names the parameter file: %s" %
                        (greeting or {}).get("file"))
    if not fatal or expected not in fatal["message"]:
        failures.append("a fatal error containing '%s': %s" % (expected, fatal))
    code = run.wait(timeout=60)
    if code != 3:
        failures.append("tissuefem exited %d, not 3" % code)
finally:
    if run.poll() is None:
        run.kill()
for f in failures:
    print("FAILED:", f)
if failures:
    print(open(os.path.join(work, "run.log")).read()[-3000:])
    sys.exit(1)
print("live view error: the page was told '%s'" % fatal["message"][:120])
