#!/usr/bin/env python3
"""Peak and resting memory of `close serve` under maximal requests (loopback only).

    scripts/abuse_rss.py [path/to/close]      (default: target/release/close)

Starts the server on a free 127.0.0.1 port and, reading its /proc status (peak RSS reset
between phases through /proc/PID/clear_refs), reports:
  1. baseline RSS;
  2. one maximal analysis (4 frames of 5000 vertices: the whole cell budget), its peak;
  3. one maximal upload (a ~60 MB Sample JSON, refused by the cell budget after reading);
  4. 20 such uploads at once: the peak, and the RSS 2 s after the last answer;
  5. how long /healthz takes meanwhile.
Targets (issue 11): under 1 GiB for any single request, under 2 GiB for 20 concurrent
maximal uploads, back within 100 MB of the baseline afterwards. Bounded in count and time;
stops the server when done.
"""
import json
import math
import os
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/close"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def status(pid, key):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1]) // 1024  # MiB
    return 0


def reset_peak(pid):
    with open(f"/proc/{pid}/clear_refs", "w") as f:
        f.write("5")


def post(url, body, timeout=120):
    req = urllib.request.Request(url, data=body, headers={"content-type": "application/json"})
    t = time.time()
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            code, text = r.status, r.read()
    except urllib.error.HTTPError as e:
        code, text = e.code, e.read()
    return code, time.time() - t, text[:160].decode("utf-8", "replace")


def circle(n, r):
    return [[round(r * math.cos(2 * math.pi * k / n), 6), round(r * math.sin(2 * math.pi * k / n), 6), 0] for k in range(n)]


def main():
    port = free_port()
    base = f"http://127.0.0.1:{port}"
    server = subprocess.Popen([BIN, "serve", "--addr", f"127.0.0.1:{port}"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(100):
            try:
                urllib.request.urlopen(base + "/healthz", timeout=1).read()
                break
            except OSError:
                time.sleep(0.1)
        pid = server.pid
        time.sleep(0.5)
        baseline = status(pid, "VmRSS")
        print(f"baseline RSS: {baseline} MiB")

        maximal = json.dumps({"name": "maximal", "frames": [circle(5000, 1.0 - 0.01 * f) for f in range(4)]}).encode()
        reset_peak(pid)
        code, took, text = post(base + "/api/analyze", maximal)
        print(f"maximal analysis (4 x 5000 vertices, {len(maximal) >> 20} MiB): {code} in {took:.1f} s, peak RSS {status(pid, 'VmHWM')} MiB")

        frame = json.dumps(circle(5000, 1.0))
        frames = (60 << 20) // (len(frame) + 1)
        upload = ("{\"frames\": [" + ",".join([frame] * frames) + "]}").encode()
        reset_peak(pid)
        code, took, text = post(base + "/api/analyze", upload)
        print(f"maximal upload ({len(upload) >> 20} MiB, {frames} frames): {code} in {took:.1f} s, peak RSS {status(pid, 'VmHWM')} MiB: {text}")

        reset_peak(pid)
        results, health = [], []
        def one(k):
            body = upload.replace(b"{", b'{"name": "u%d", ' % k, 1)
            results.append(post(base + "/api/analyze", body, timeout=300))
        threads = [threading.Thread(target=one, args=(k,)) for k in range(20)]
        t = time.time()
        for th in threads:
            th.start()
        while any(th.is_alive() for th in threads):
            h = time.time()
            try:
                urllib.request.urlopen(base + "/healthz", timeout=10).read()
                health.append(time.time() - h)
            except OSError:
                health.append(float("inf"))
            time.sleep(0.2)
        codes = sorted({r[0] for r in results})
        peak = status(pid, "VmHWM")
        print(f"20 concurrent maximal uploads: status {codes} in {time.time() - t:.1f} s, peak RSS {peak} MiB, /healthz worst {max(health) * 1000:.0f} ms")
        time.sleep(2)
        after = status(pid, "VmRSS")
        print(f"RSS 2 s after: {after} MiB ({after - baseline:+d} MiB against the baseline)")
    finally:
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
