"""Ctrl-C works: a SIGINT sent from a timer while `analyze_many` or `evaluate` runs becomes
`KeyboardInterrupt` long before the batch could end, and leaves none of its threads running.

Each case runs in a child interpreter (a stray KeyboardInterrupt must not hit pytest), on a
batch certain to outlast the signal by far: 40,000 analyses of a physics sample, minutes of
work on any machine. The signal goes 0.5 s after the first item is done. The child reports
how many items were done when the signal went and when the call returned, how long that
took, and its native thread count (from /proc) before and after.
"""

import json
import subprocess
import sys

import pytest

from conftest import PHYSICS

CHILD = r"""
import json, os, signal, sys, threading, time
import close

def threads():
    return len(os.listdir("/proc/self/task"))

# Ctrl-C raises KeyboardInterrupt, as in a terminal, even when this test runs in the
# background, where the shell starts it with SIGINT ignored and Python keeps that.
signal.signal(signal.SIGINT, signal.default_int_handler)

sample = close.load(sys.argv[1])
call = sys.argv[2]
items = [sample] * 40000
close.analyze_many(items[:4], threads=2)            # warm-up: the global pool exists
close.evaluate(items[:4], threads=2)
before = threads()
state = {"done": 0, "at_signal": None, "sent": None}

def interrupt():
    state["at_signal"] = state["done"]
    state["sent"] = time.monotonic()
    os.kill(os.getpid(), signal.SIGINT)

timer = None

def progress(done, total):
    global timer
    state["done"] = done
    if timer is None and done > 0:
        timer = threading.Timer(0.5, interrupt)
        timer.start()

outcome = "finished"
try:
    if call == "analyze_many":
        close.analyze_many(items, threads=2, progress=progress)
    else:
        close.evaluate(items, threads=2, progress=progress)
except KeyboardInterrupt:
    outcome = "KeyboardInterrupt"
returned = time.monotonic()
if timer is not None:
    timer.join()  # the test's own thread
print(json.dumps({
    "outcome": outcome,
    "total": len(items),
    "at_signal": state["at_signal"],
    "done": state["done"],
    "latency": returned - state["sent"] if state["sent"] else None,
    "threads_before": before,
    "threads_after": threads(),
}))
"""


@pytest.mark.parametrize("call", ["analyze_many", "evaluate"])
def test_ctrl_c_stops_the_batch_and_its_threads(call):
    done = subprocess.run(
        [sys.executable, "-c", CHILD, str(PHYSICS[0]), call], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    print(report)
    assert report["outcome"] == "KeyboardInterrupt"
    # It stopped near where the signal found it, not at the end of the batch.
    assert report["at_signal"] is not None and report["done"] < report["total"] // 2
    # Every thread the call started has ended.
    assert report["threads_after"] == report["threads_before"]
