#!/usr/bin/env python3
"""A device driver for tissuefem's live tool ('Tool/Live port'), as a haptic
loop runs one: positions streamed at a fixed rate of the client's own wall
clock, not waiting for answers, and every answer timed.

    stream_client.py TISSUEFEM SCENE WORKDIR [options] [-- --set ...]

starts TISSUEFEM on SCENE in WORKDIR (its 'Output/Directory' set to
'results'), connects to the port it writes to results/live_port, and for
--seconds of wall time sends at --rate per second the line 't x y z' with t
the client's time since the first line and the tool position --amplitude *
min(t, --ramp) along x (the remaining coordinates 0); a second thread reads
the answers 't fx fy fz'. Then it says 'bye', waits for tissuefem and prints
what the device saw:

  - answered: answers received / positions sent;
  - latency (ms) from sending a position to receiving its answer: median,
    99th percentile, largest, and the share within one period (1/rate);
  - tissuefem's own report line (its latencies, answers sent while a step
    ran, and the simulation's lag behind the client's clock).

With --check it is a test (tests/live, ctest), with no timing in its
verdict: tissuefem must exit 0, every position must be answered with
finite numbers in order, and tissuefem must report at least one answer sent
while a step ran (steps of the scene are chosen far longer than the period,
so answers that waited for steps would make that count 0).
"""
import argparse
import math
import os
import re
import socket
import statistics
import subprocess
import sys
import threading
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tissuefem")
    parser.add_argument("scene")
    parser.add_argument("workdir")
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--rate", type=float, default=500.0)
    parser.add_argument("--amplitude", type=float, default=0.075)
    parser.add_argument("--ramp", type=float, default=0.2)
    parser.add_argument("--dim", type=int, default=3)
    parser.add_argument("--check", action="store_true")
    # Whatever follows '--' goes to tissuefem (e.g. --set 'A/B=c').
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    args = parser.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    args.extra = extra

    os.makedirs(args.workdir, exist_ok=True)
    port_file = os.path.join(args.workdir, "results", "live_port")
    if os.path.exists(port_file):
        os.remove(port_file)  # a stale one from an earlier run
    log = open(os.path.join(args.workdir, "run.log"), "w")
    command = [os.path.abspath(args.tissuefem), os.path.abspath(args.scene),
               "--set", "Output/Directory=results"] + args.extra
    process = subprocess.Popen(command, cwd=args.workdir, stdout=log,
                               stderr=subprocess.STDOUT)
    for _ in range(600):
        if os.path.exists(port_file) and os.path.getsize(port_file) > 0:
            break
        if process.poll() is not None:
            sys.exit("stream client: tissuefem exited before listening")
        time.sleep(0.1)
    else:
        process.kill()
        sys.exit("stream client: no results/live_port after 60 s")
    port = int(open(port_file).read())
    connection = socket.create_connection(("127.0.0.1", port))
    connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    period = 1.0 / args.rate
    count = int(round(args.seconds * args.rate)) + 1
    sent = [None] * count        # wall time each position was sent
    received = [None] * count    # wall time its answer arrived
    bad = []

    def read_answers():
        buffer = b""
        answered = 0
        while answered < count:
            data = connection.recv(65536)
            if not data:
                return
            now = time.perf_counter()
            buffer += data
            while b"\n" in buffer:
                line, buffer = buffer.split(b"\n", 1)
                fields = line.split()
                try:
                    values = [float(f) for f in fields]
                except ValueError:
                    values = []
                if len(values) != args.dim + 1 or not all(
                        math.isfinite(v) for v in values):
                    bad.append(line.decode(errors="replace"))
                    continue
                k = int(round(values[0] / period))
                if 0 <= k < count and received[k] is None:
                    received[k] = now
                    answered += 1

    reader = threading.Thread(target=read_answers)
    reader.start()
    start = time.perf_counter()
    for k in range(count):
        # Streamed on the client's clock, whatever the answers do.
        delay = start + k * period - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
        t = k * period
        position = [args.amplitude * min(t, args.ramp)] + [0.0] * (args.dim - 1)
        line = "%.6f " % t + " ".join("%.9g" % x for x in position) + "\n"
        sent[k] = time.perf_counter()
        try:
            connection.sendall(line.encode())
        except OSError:  # tissuefem ended its run (End time reached)
            sent[k] = None
            break
    reader.join(timeout=30)
    try:
        connection.sendall(b"bye\n")
    except OSError:
        pass
    status = process.wait(timeout=600)
    connection.close()
    log.close()
    output = open(os.path.join(args.workdir, "run.log")).read()

    latencies = sorted(1e3 * (r - s) for s, r in zip(sent, received)
                       if r is not None and s is not None)
    planned, count = count, sum(1 for s in sent if s is not None)
    answered = len(latencies)
    print("answered: %d of %d positions" % (answered, count))
    if latencies:
        p99 = latencies[min(len(latencies) - 1, int(0.99 * len(latencies)))]
        within = sum(1 for x in latencies if x <= 1e3 * period)
        print("latency seen by the client (ms): median %.3f, 99th percentile "
              "%.3f, max %.3f; %.1f %% within one period (%.3g ms)"
              % (statistics.median(latencies), p99, latencies[-1],
                 100.0 * within / len(latencies), 1e3 * period))
    report = re.search(r"live client: .*", output)
    if report:
        print("tissuefem: " + report.group(0))
    if not args.check:
        return 0
    failures = []
    if status != 0:
        failures.append("tissuefem exited with status %d" % status)
    if count != planned:
        failures.append("tissuefem stopped reading after %d of %d positions"
                        % (count, planned))
    if answered != count:
        failures.append("%d of %d positions answered" % (answered, count))
    if bad:
        failures.append("malformed answer '%s'" % bad[0])
    during = re.search(r"(\d+) answered while a step ran", output)
    if not during or int(during.group(1)) == 0:
        failures.append("no answer was sent while a step ran (answers "
                        "waited for the simulation)")
    for failure in failures:
        print("stream client: " + failure)
    if failures:
        print(output[-2000:])
        return 1
    print("stream client: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
