#!/usr/bin/env python3
"""Every hostile item of issue 27 at once, against `close eval` and `close serve` (loopback).

    scripts/hostile.py build DIR                 write the hostile dataset folder DIR
    scripts/hostile.py eval DIR [BIN]            `close eval DIR --json`: time, rows, peak RSS
    scripts/hostile.py serve DIR [BIN] [SECS]    `close serve --dataset DIR` with attackers
                                                 running beside a normal load for SECS
                                                 (default 60; 600 for the soak)
    scripts/hostile.py crowd DIR [BIN]           item 11: a dataset of 100,000 rows (written
                                                 into DIR when missing), 64 full sample lists
                                                 at once, then 64 /api/disk bodies of 8 MiB;
                                                 peak RSS and /healthz meanwhile

BIN defaults to target/release/close. Run from the repository root (the fixture store of
tests/fixtures/vrfolding is copied and broken). The folder holds: good Sample JSON files, a
.mat, a folder of frame files with a sample inside it, a file 40 folders down, a FIFO, a
link to /etc/passwd, a file that is swapped for that link while the server runs, a good
store, stores with a sparse 1 TiB chunk, FIFOs, forged chunk counts, a .zattrs linked out,
video ids that clash as file names, and a store without its .zgroup.

`serve` starts the server, times it to its first /healthz, then runs, each on threads of
its own and reconnecting: 60 KB searches, slow uploaders (64 MiB announced, 32 KiB/s),
clients that never read a 91 MB interpolation, full sample lists (read and unread), 8 MiB
/api/disk bodies, loads of every broken sample; beside a normal load (analyses, lists,
samples, small interpolations, disk cells). A probe posts a small fresh /api/disk/cells
every second and a normal analysis every 5 s. It reports the statuses of everything (a 5xx
is a bug), the probes' worst and median latency, and the server's RSS (peak and last).
Bounded in time; stops its threads and the server when done.
"""
import http.client
import json
import math
import os
import shutil
import socket
import statistics
import subprocess
import sys
import threading
import time
import urllib.parse

FIXTURE = "tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr"
REFERENCE = "tests/fixtures/reference/folded"


def edit_json(path, edit):
    with open(path) as f:
        value = json.load(f)
    edit(value)
    with open(path, "w") as f:
        json.dump(value, f)


def frames_of(store, category):
    """Frame group folders of the first video of `category`, in sample_id order."""
    samples = os.path.join(store, category, "samples")
    frames = {}
    for name in sorted(n for n in os.listdir(samples) if not n.startswith(".")):
        with open(os.path.join(samples, name, ".zattrs")) as f:
            attrs = json.load(f)
        frames.setdefault(str(attrs["video_id"]), []).append((attrs["sample_id"], os.path.join(samples, name)))
    first = sorted(frames)[0]
    return [path for _, path in sorted(frames[first])]


def copy_store(to, categories):
    os.makedirs(to)
    shutil.copy(os.path.join(FIXTURE, ".zgroup"), to)
    for c in categories:
        shutil.copytree(os.path.join(FIXTURE, c), os.path.join(to, c))


def sparse(path):
    os.remove(path)
    with open(path, "wb") as f:
        f.truncate(1 << 40)


def fifo(path):
    os.remove(path)
    os.mkfifo(path)


def build(root):
    if os.path.exists(root):
        sys.exit(f"{root} exists")
    os.makedirs(os.path.join(root, "good"))
    for name in sorted(os.listdir(REFERENCE)):
        shutil.copy(os.path.join(REFERENCE, name), os.path.join(root, "good", name))
    first = json.load(open(os.path.join(REFERENCE, sorted(os.listdir(REFERENCE))[0])))
    # Item 10: a .mat, a folder of frame files holding a sample of its own, a file too deep.
    shutil.copy("tests/fixtures/formats/napkin_dense.mat", os.path.join(root, "napkin.mat"))
    os.makedirs(os.path.join(root, "run", "later"))
    for k, frame in enumerate(first["frames"][:2]):
        with open(os.path.join(root, "run", f"f{k}.csv"), "w") as f:
            f.writelines(f"{x},{y},{z}\n" for x, y, z in frame)
    json.dump(first, open(os.path.join(root, "run", "later", "again.json"), "w"))
    deep = os.path.join(root, "deep", *[f"d{k}" for k in range(40)])
    os.makedirs(deep)
    json.dump(first, open(os.path.join(deep, "lost.json"), "w"))
    # Items 4 and 6: a FIFO, a link out, and a file the server run swaps for one.
    os.mkfifo(os.path.join(root, "pipe.json"))
    os.symlink("/etc/passwd", os.path.join(root, "passwd.txt"))
    with open(os.path.join(root, "victim.txt"), "w") as f:
        f.writelines(f"{x},{y},{z}\n" for x, y, z in first["frames"][0])
    # Item 7: a good store inside the folder, and one without its .zgroup.
    copy_store(os.path.join(root, "good.zarr"), ["Skirt", "Top", "Trousers", "Tshirt"])
    copy_store(os.path.join(root, "partial.zarr"), ["Top"])
    os.remove(os.path.join(root, "partial.zarr", ".zgroup"))
    # Item 1: sparse 1 TiB chunks, a mesh's (read on loading) and a grip's (at listing).
    store = os.path.join(root, "stores", "sparse.zarr")
    copy_store(store, ["Skirt", "Tshirt"])
    sparse(os.path.join(frames_of(store, "Tshirt")[0], "mesh/cloth_verts/0.0"))
    sparse(os.path.join(frames_of(store, "Skirt")[0], "grip_vertex_id/left_grip_vertex_id/0"))
    # Item 4: FIFOs in a store: a chunk and a frame's attributes.
    store = os.path.join(root, "stores", "fifo.zarr")
    copy_store(store, ["Skirt", "Top"])
    fifo(os.path.join(frames_of(store, "Skirt")[2], "grip_vertex_id/right_grip_vertex_id/0"))
    fifo(os.path.join(frames_of(store, "Top")[0], ".zattrs"))
    # Item 3: four grip arrays of 2·10⁶ one-element chunks, no chunk file, in the limits.
    store = os.path.join(root, "stores", "meta.zarr")
    copy_store(store, ["Skirt"])
    frames = frames_of(store, "Skirt")

    def big(z):
        z["shape"], z["chunks"] = [2000000, 3], [2000000, 3]

    edit_json(os.path.join(frames[0], "mesh/cloth_verts/.zarray"), big)
    for frame in frames[:2]:
        for hand in ("left", "right"):
            grip = os.path.join(frame, f"grip_vertex_id/{hand}_grip_vertex_id")

            def forged(z):
                z["shape"], z["chunks"] = [2000000], [1]

            edit_json(os.path.join(grip, ".zarray"), forged)
            os.remove(os.path.join(grip, "0"))
    # Item 6: a frame's attributes linked out of the store.
    store = os.path.join(root, "stores", "links.zarr")
    copy_store(store, ["Skirt"])
    attrs = os.path.join(frames_of(store, "Skirt")[3], ".zattrs")
    os.remove(attrs)
    os.symlink("/etc/passwd", attrs)
    # Item 9: video ids that clash as file names, and one of 300 characters.
    store = os.path.join(root, "stores", "ids.zarr")
    copy_store(store, ["Skirt", "Top"])
    for category, ids in (("Skirt", ("a/b", "a_b")), ("Top", ("x" * 300, None))):
        samples = os.path.join(store, category, "samples")
        names = [n for n in os.listdir(samples) if not n.startswith(".")]
        videos = sorted({json.load(open(os.path.join(samples, n, ".zattrs")))["video_id"] for n in names})
        for video, new in zip(videos, ids):
            if new is None:
                continue
            for name in names:
                path = os.path.join(samples, name, ".zattrs")
                if json.load(open(path))["video_id"] == video:
                    edit_json(path, lambda a: a.__setitem__("video_id", new))
    print(f"wrote {root}")


def rss(pid, key):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) // 1024
    except OSError:
        pass
    return 0


def peak_of_children():
    """Peak RSS (MiB) of the waited-for children (getrusage)."""
    import resource
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024


def run_eval(root, binary):
    t = time.time()
    out = subprocess.run([binary, "eval", root, "--json"], capture_output=True, timeout=3600)
    took = time.time() - t
    print(f"close eval: exit {out.returncode} in {took:.1f} s, peak RSS {peak_of_children()} MiB")
    report = json.loads(out.stdout)
    rows = report["samples"]
    failed = [r for r in rows if r.get("error")]
    dropped = [r for r in rows if r.get("dropped")]
    print(f"rows: {len(rows)} ({len(rows) - len(failed) - len(dropped)} scored, {len(dropped)} dropped, {len(failed)} errors)")
    for r in failed:
        print(f"  error row {r['name'][:70]}: {r['error'][:150]}")


def circle(n, r=1.0, shift=0.0):
    return [[round(r * math.cos(2 * math.pi * k / n) + shift, 9), round(r * math.sin(2 * math.pi * k / n), 9), 0] for k in range(n)]


def normal_sample(name):
    corners = [(0, 0), (1, 0), (1, 1), (0, 1)]
    flat = []
    for v in range(76):
        (ax, ay), (bx, by), t = corners[v // 19], corners[(v // 19 + 1) % 4], (v % 19) / 19
        flat.append([ax + t * (bx - ax), ay + t * (by - ay), 0.0])
    folded = [[0.8 - p[0], p[1], 0.01] if p[0] > 0.4 else p for p in flat]
    return {"name": name, "category": "napkin", "frames": [flat, folded]}


class Stats:
    def __init__(self):
        self.lock = threading.Lock()
        self.statuses = {}
        self.server_errors = []

    def count(self, who, status, text=""):
        with self.lock:
            self.statuses.setdefault(who, {}).setdefault(status, 0)
            self.statuses[who][status] += 1
            if isinstance(status, int) and status >= 500:
                self.server_errors.append((who, status, text[:200]))


def request(port, method, path, body=None, timeout=60, read=True):
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout)
    headers = {"content-type": "application/json"} if body is not None else {}
    conn.request(method, path, body=body, headers=headers)
    response = conn.getresponse()
    text = response.read() if read else b""
    conn.close()
    return response.status, text


def serve(root, binary, seconds):
    port = 20000 + os.getpid() % 20000
    base = ("127.0.0.1", port)
    t0 = time.time()
    server = subprocess.Popen([binary, "serve", "--addr", f"127.0.0.1:{port}", "--dataset", root],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    stats, stop = Stats(), threading.Event()
    threads = []
    try:
        while True:
            try:
                request(port, "GET", "/healthz", timeout=1)
                break
            except OSError:
                if time.time() - t0 > 120:
                    sys.exit("the server did not start in 120 s")
                time.sleep(0.02)
        print(f"close serve --dataset: first /healthz after {time.time() - t0:.2f} s, RSS {rss(server.pid, 'VmRSS')} MiB")
        status, text = request(port, "GET", "/api/samples")
        listing = json.loads(text)
        rows = listing["samples"]
        mine = [r for r in rows if r["source"] != "builtin"]
        broken = [r for r in mine if r["error"]]
        print(f"listed: {len(rows)} rows, {len(mine)} from the folder ({len(mine) - len(broken)} readable, {len(broken)} error rows); ids unique: {len({r['id'] for r in rows}) == len(rows)}")
        for r in broken:
            print(f"  error row {r['name'][:70]}: {r['error'][:150]}")
        # Item 6: the listed victim.txt swapped for a link to /etc/passwd.
        victim = next(r for r in mine if r["name"] == "victim.txt")
        os.rename(os.path.join(root, "victim.txt"), os.path.join(root, "victim.was"))
        os.symlink("/etc/passwd", os.path.join(root, "victim.txt"))
        status, text = request(port, "GET", f"/api/samples/{victim['id']}")
        print(f"victim.txt swapped for a link to /etc/passwd: {status} {text[:160].decode()}; quotes root: {b'root:' in text}")
        # Item 1: the fold whose mesh chunk is sparse.
        sparse_folds = [r for r in mine if "sparse.zarr" in r["source"] and r["category"].startswith("Tshirt") and not r["error"]]
        for r in sparse_folds[:1]:
            status, text = request(port, "GET", f"/api/samples/{r['id']}")
            print(f"a fold with a sparse 1 TiB chunk: {status} {text[:200].decode()}")

        def loop(who, work):
            def body():
                while not stop.is_set():
                    try:
                        work(who)
                    except (OSError, http.client.HTTPException) as e:
                        stats.count(who, type(e).__name__)
                        time.sleep(0.05)
            th = threading.Thread(target=body, daemon=True)
            th.start()
            threads.append(th)

        # 10,000 'Σ' (60 KB of target once %-encoded: hyper takes targets up to 64 KB).
        quoted = urllib.parse.quote("Σ" * 10000)

        def search(who):
            status, _ = request(port, "GET", f"/api/samples?q={quoted}")
            stats.count(who, status)

        def slow_upload(who):
            s = socket.create_connection(base)
            s.settimeout(1)
            s.sendall(f"POST /api/analyze HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\nContent-Length: {64 << 20}\r\n\r\n".encode())
            answer = b""
            while not stop.is_set():
                try:
                    s.sendall(b" " * 1024)
                except OSError:
                    break
                try:
                    got = s.recv(4096)
                    if not got:
                        break
                    answer += got
                except socket.timeout:
                    pass
                except OSError:
                    break
                time.sleep(1 / 32)
            s.close()
            status = answer[9:12].decode() if answer.startswith(b"HTTP/") else "cut"
            stats.count(who, int(status) if status.isdigit() else status, answer.decode(errors="replace"))

        big = json.dumps({"border": circle(5000), "from": [0.1, 3.0], "to": [1.0, 4.0], "steps": 400}).encode()

        def unread(who):
            s = socket.create_connection(base)
            s.sendall(f"POST /api/interpolate HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: application/json\r\nContent-Length: {len(big)}\r\n\r\n".encode() + big)
            s.settimeout(120)
            head = s.recv(12)
            stats.count(who, int(head[9:12]) if head[9:12].isdigit() else "none")
            # Never read more: wait for the server to give up on it.
            s.settimeout(1)
            while not stop.is_set():
                try:
                    s.send(b"")
                    time.sleep(1)
                    if s.recv(1, socket.MSG_PEEK) == b"":
                        break
                except socket.timeout:
                    continue
                except OSError:
                    break
            s.close()

        def full_list(who):
            status, _ = request(port, "GET", "/api/samples", read=who.endswith("read"))
            stats.count(who, status)

        padding = 8 * (1 << 20) - 4096
        disk_body = (json.dumps({"border": circle(76)}) + " " * padding).encode()

        def disk(who):
            status, _ = request(port, "POST", "/api/disk", disk_body)
            stats.count(who, status)

        bad_ids = [r["id"] for r in broken] + [r["id"] for r in sparse_folds if "00001" in r["name"]]

        def bad_loads(who):
            for id in bad_ids:
                status, text = request(port, "GET", f"/api/samples/{urllib.parse.quote(id)}")
                stats.count(who, status, text.decode(errors="replace"))

        counter = [0]

        def normal(who):
            counter[0] += 1
            k = counter[0]
            kind = k % 5
            if kind == 0:
                status, _ = request(port, "POST", "/api/analyze", json.dumps(normal_sample(f"load {who} {k}")).encode())
            elif kind == 1:
                status, _ = request(port, "GET", "/api/samples?limit=20&q=fold")
            elif kind == 2:
                status, _ = request(port, "GET", f"/api/samples/{rows[k % len(rows)]['id']}")
            elif kind == 3:
                body = {"border": circle(76, 1.0, k * 1e-9), "from": [0.5, 3.6], "to": [1.0, 4.0], "steps": 41}
                status, _ = request(port, "POST", "/api/interpolate", json.dumps(body).encode())
            else:
                status, _ = request(port, "POST", "/api/disk/cells", json.dumps({"border": circle(76, 1.0, k * 1e-9)}).encode())
            stats.count(who, status)

        for k in range(8):
            loop("search", search)
        for k in range(4):
            loop("slow upload", slow_upload)
        for k in range(6):
            loop("unread interpolation", unread)
        for k in range(8):
            loop("full list read", full_list)
            loop("full list unread", full_list)
        for k in range(4):
            loop("8 MiB disk body", disk)
        loop("broken samples", bad_loads)
        for k in range(4):
            loop(f"normal", normal)

        probes, analyses, samples = [], [], []
        t = time.time()
        k = 0
        while time.time() - t < seconds:
            k += 1
            body = json.dumps({"border": circle(76, 1.0, 1e-6 * k)}).encode()
            p = time.time()
            try:
                status, _ = request(port, "POST", "/api/disk/cells", body, timeout=30)
            except OSError as e:
                status = type(e).__name__
            probes.append(time.time() - p)
            stats.count("probe: small POST", status)
            if k % 5 == 0:
                p = time.time()
                try:
                    status, _ = request(port, "POST", "/api/analyze", json.dumps(normal_sample(f"probe {k}")).encode(), timeout=60)
                except OSError as e:
                    status = type(e).__name__
                analyses.append(time.time() - p)
                stats.count("probe: normal analysis", status)
            samples.append((rss(server.pid, "VmRSS"), rss(server.pid, "VmHWM")))
            time.sleep(max(0.0, 1.0 - (time.time() - p)))
        stop.set()
        print(f"ran {time.time() - t:.0f} s beside the attackers")
        print(f"small POST /api/disk/cells: {len(probes)} probes, median {statistics.median(probes) * 1000:.0f} ms, worst {max(probes) * 1000:.0f} ms, over 1 s: {sum(p > 1 for p in probes)}")
        if analyses:
            print(f"normal analysis (N = 76): {len(analyses)} probes, median {statistics.median(analyses) * 1000:.0f} ms, worst {max(analyses) * 1000:.0f} ms")
        print(f"server RSS: peak (VmHWM) {max(h for _, h in samples)} MiB, last {samples[-1][0]} MiB")
        for who, counts in sorted(stats.statuses.items()):
            print(f"  {who}: {dict(sorted(counts.items(), key=str))}")
        print(f"5xx answers: {len(stats.server_errors)}")
        for e in stats.server_errors[:10]:
            print(f"  {e}")
    finally:
        stop.set()
        server.terminate()
        server.wait(timeout=60)
        victim = os.path.join(root, "victim.was")
        if os.path.exists(victim):
            os.remove(os.path.join(root, "victim.txt"))
            os.rename(victim, os.path.join(root, "victim.txt"))


def crowd(root, binary):
    if not os.path.exists(root):
        os.makedirs(root)
        for k in range(100_000):
            with open(os.path.join(root, f"{k:06}.csv"), "w") as f:
                f.write(f"0,0,0\n1,0,0\n1,1,0\n0,1,{k * 1e-6}\n")
    port = 20000 + (os.getpid() + 1) % 20000
    t0 = time.time()
    server = subprocess.Popen([binary, "serve", "--addr", f"127.0.0.1:{port}", "--dataset", root],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        while True:
            try:
                request(port, "GET", "/healthz", timeout=1)
                break
            except OSError:
                time.sleep(0.05)
        print(f"100,000 rows: first /healthz after {time.time() - t0:.1f} s, RSS {rss(server.pid, 'VmRSS')} MiB")
        status, text = request(port, "GET", "/api/samples")
        print(f"one full list: {status}, {len(text) / 1e6:.1f} MB; peak RSS so far {rss(server.pid, 'VmHWM')} MiB")

        def burst(name, work, count):
            before = rss(server.pid, "VmRSS")
            with open(f"/proc/{server.pid}/clear_refs", "w") as f:
                f.write("5")  # reset the peak
            results, health = [], []
            threads = [threading.Thread(target=lambda: results.append(work())) for _ in range(count)]
            t = time.time()
            for th in threads:
                th.start()
            while any(th.is_alive() for th in threads):
                h = time.time()
                try:
                    request(port, "GET", "/healthz", timeout=30)
                    health.append(time.time() - h)
                except OSError:
                    health.append(float("inf"))
                time.sleep(0.05)
            for th in threads:
                th.join()
            codes = {}
            for status in results:
                codes[status] = codes.get(status, 0) + 1
            print(f"{name}: {codes} in {time.time() - t:.1f} s, RSS {before} MiB before, peak {rss(server.pid, 'VmHWM')} MiB, /healthz worst {max(health) * 1000:.0f} ms over {len(health)} probes")

        burst("64 full lists at once", lambda: request(port, "GET", "/api/samples", timeout=300)[0], 64)
        body = (json.dumps({"border": circle(76)}) + " " * (8 * (1 << 20) - 4096)).encode()
        burst("64 /api/disk bodies of 8 MiB", lambda: request(port, "POST", "/api/disk", body, timeout=300)[0], 64)
    finally:
        server.terminate()
        server.wait(timeout=60)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    command, root = sys.argv[1], sys.argv[2]
    binary = sys.argv[3] if len(sys.argv) > 3 else "target/release/close"
    if command == "build":
        build(root)
    elif command == "eval":
        run_eval(root, binary)
    elif command == "serve":
        serve(root, binary, float(sys.argv[4]) if len(sys.argv) > 4 else 60)
    elif command == "crowd":
        crowd(root, binary)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
