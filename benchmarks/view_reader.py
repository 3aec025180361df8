"""A page that reads every frame the live view sends and draws nothing: what
streaming costs the run by itself, without a browser's rendering
(benchmarks/live_view.mjs).

    view_reader.py ADDRESS_FILE

waits for ADDRESS_FILE (<Output directory>/live_view), connects, reads
until the run ends, and prints one JSON line: frames, bytes per frame,
seconds connected.
"""
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "tests", "live"))
import websocket_client as wc  # noqa: E402

address = sys.argv[1]
for _ in range(2400):
    if os.path.exists(address):
        break
    time.sleep(0.025)
url = open(address).read().strip()
host, port = url[len("http://"):].rstrip("/").split(":")
page = wc.WebSocket(host, int(port))
page.sock.settimeout(120)
frames, size, start = 0, 0, time.time()
try:
    while True:
        opcode, payload = page.receive()
        if opcode == 8:
            break
        if opcode == 2 and payload[:4] == b"TFF1":
            frames += 1
            size = len(payload)
        elif opcode == 1 and b'"end"' in payload:
            break
except (ConnectionError, OSError):
    pass
print(json.dumps({"frames": frames, "bytes": size,
                  "seconds": time.time() - start}))
