#!/usr/bin/env python3
"""The Python package's targets (issues 17 and 29), measured in one run and reported as
ratios; exits 1 when one is missed.

1. boundary:  a loop of `close.analyze` over the samples (N = 76), against
              `close.analyze_many(same, threads=1)`           (target: at most 1.15x)
2. threads:   `analyze_many(threads=1)` time / `analyze_many(threads=2)` time
                                                              (target: at least 1.6x on 2 cores)
3. disk:      `benches/numpy_baseline.py`'s disk at N = 1000 / `close.dgli_disk` at N = 1000
                                                              (target: at least 50x)
4. authors:   the authors' Python, 9.74 s per analysis at N = 76 (the median of three runs in
              the reference implementation's timing, `get_feature_vector` on a start/end pair),
              / one `close.analyze` at N = 76 here            (reported)
5. verify:    `close.verify` of each sample against its own folds (analysis included) /
              `close.analyze` of the same samples, both from a loop at N = 76 (reported: the
              verification's cost on top of the analysis); and `close.verify` of an Analysis
              already made, per call (reported, µs)

The samples are the reference fixtures with N = 76 (tests/fixtures/reference), cycled to
`--samples` (1,000 by default). Each timing is the best of `--repeats` runs. A ratio of
threads depends on the machine being free: the load average (before and after) and the CPU
seconds each run used are printed beside it, so a miss can be told apart — a run whose CPU
time is twice its wall time had both cores and was slow for its own reasons; one that got
less than that shared them with other work.

usage: python benches/python_targets.py [--samples 1000] [--repeats 3] [--json FILE]
"""

import argparse
import importlib.util
import json
import os
import resource
import sys
import time
from pathlib import Path

import close

ROOT = Path(__file__).resolve().parents[1]
AUTHORS_SECONDS_AT_76 = 9.74


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def best(fn, repeats):
    """The best wall time of `repeats` runs, and the CPU seconds that run used."""
    runs = []
    for _ in range(repeats):
        c0, t0 = cpu_seconds(), time.perf_counter()
        fn()
        runs.append((time.perf_counter() - t0, cpu_seconds() - c0))
    return min(runs)


def numpy_baseline():
    spec = importlib.util.spec_from_file_location("numpy_baseline", ROOT / "benches" / "numpy_baseline.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--disk-n", type=int, default=1000, help="border size of the disk target")
    parser.add_argument("--threads-target", type=float, default=1.6)
    parser.add_argument("--json", metavar="FILE")
    args = parser.parse_args()

    load_before = os.getloadavg()
    pool = [s for s in map(close.load, sorted((ROOT / "tests" / "fixtures" / "reference").glob("*/*.json"))) if s.frames.shape[1] == 76]
    samples = [pool[k % len(pool)] for k in range(args.samples)]

    loop, loop_cpu = best(lambda: [close.analyze(s) for s in samples], args.repeats)
    one, one_cpu = best(lambda: close.analyze_many(samples, threads=1), args.repeats)
    two, two_cpu = best(lambda: close.analyze_many(samples, threads=2), args.repeats)

    baseline = numpy_baseline()
    border = baseline.napkin(args.disk_n)
    numpy_disk, _ = best(lambda: baseline.disk(border), args.repeats)
    rust_disk, _ = best(lambda: close.dgli_disk(border), max(args.repeats, 5))
    load_after = os.getloadavg()

    # Issue 30: verify beside analyze, each sample against the folds found in it.
    goals = [close.analyze(s).folds or [(0.0, 3.14159)] for s in samples]
    verify_loop, _ = best(lambda: [close.verify(s, g) for s, g in zip(samples, goals)], args.repeats)
    analyses = [close.analyze(s) for s in samples]
    verify_only, _ = best(lambda: [close.verify(a, g) for a, g in zip(analyses, goals)], args.repeats)

    per_analysis = loop / len(samples)
    targets = [
        ("boundary loop/many(threads=1)", loop / one, "<=", 1.15),
        ("threads many(1)/many(2)", one / two, ">=", args.threads_target),
        (f"disk numpy/close.dgli_disk at N={args.disk_n}", numpy_disk / rust_disk, ">=", 50.0),
    ]
    results = {
        "cores": os.cpu_count(),
        "load_average_before": load_before,
        "load_average_after": load_after,
        "samples": len(samples),
        "distinct_samples": len(pool),
        "loop_s": loop,
        "many_threads1_s": one,
        "many_threads2_s": two,
        "cpu_s": {"loop": loop_cpu, "many_threads1": one_cpu, "many_threads2": two_cpu},
        "numpy_disk_s": numpy_disk,
        "dgli_disk_s": rust_disk,
        "per_analysis_76_s": per_analysis,
        "verify_loop_s": verify_loop,
        "verify_of_analysis_76_s": verify_only / len(samples),
        "ratios": {f"{name} [{op} {target}]": value for name, value, op, target in targets},
    }
    results["ratios"]["authors' Python 9.74 s / close.analyze at N=76"] = AUTHORS_SECONDS_AT_76 / per_analysis
    results["ratios"]["verify(sample)/analyze(sample) at N=76"] = verify_loop / loop
    missed = [(name, value, op, target) for name, value, op, target in targets
              if not (value <= target if op == "<=" else value >= target)]
    for name, value in results["ratios"].items():
        print(f"{name:<55} {value:10.2f}")
    print(f"(loop {loop:.3f} s, many(1) {one:.3f} s, many(2) {two:.3f} s for {len(samples)} samples; "
          f"CPU s: many(1) {one_cpu:.3f}, many(2) {two_cpu:.3f} (cpu/wall {two_cpu / two:.2f}); "
          f"disk N={args.disk_n}: numpy {numpy_disk * 1e3:.1f} ms, close {rust_disk * 1e3:.2f} ms; {os.cpu_count()} cores)")
    print(f"(close.verify of an Analysis already made, N=76: {verify_only / len(samples) * 1e6:.0f} µs per call)")
    print("load average before: {:.2f} {:.2f} {:.2f}; after: {:.2f} {:.2f} {:.2f}".format(*load_before, *load_after))
    for name, value, op, target in missed:
        print(f"MISSED: {name} = {value:.2f}, target {op} {target}")
    results["missed"] = [name for name, *_ in missed]
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
