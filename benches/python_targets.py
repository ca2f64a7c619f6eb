#!/usr/bin/env python3
"""The Python package's targets (issue 17), measured in one run and reported as ratios.

1. boundary:  a loop of `close.analyze` over 300 samples with N = 76, against
              `close.analyze_many(same, threads=1)`           (target: at most 1.15x)
2. threads:   `analyze_many(threads=1)` time / `analyze_many(threads=2)` time
                                                              (target: at least 1.7x on 2 cores)
3. disk:      `benches/numpy_baseline.py`'s disk at N = 1000 / `close.dgli_disk` at N = 1000
                                                              (target: at least 50x)
4. authors:   the authors' Python, 9.74 s per analysis at N = 76 (the median of three runs in
              the reference implementation's timing, `get_feature_vector` on a start/end pair),
              / one `close.analyze` at N = 76 here            (reported)
5. verify:    `close.verify` of each sample against its own folds (analysis included) /
              `close.analyze` of the same samples, both from a loop at N = 76 (reported: the
              verification's cost on top of the analysis); and `close.verify` of an Analysis
              already made, per call (reported, µs)

The samples are the reference fixtures with N = 76 (tests/fixtures/reference), cycled to 300.
Each timing is the best of `--repeats` runs.

usage: python benches/python_targets.py [--repeats 3] [--json FILE]
"""

import argparse
import importlib.util
import json
import os
import time
from pathlib import Path

import close

ROOT = Path(__file__).resolve().parents[1]
AUTHORS_SECONDS_AT_76 = 9.74


def best(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def numpy_baseline():
    spec = importlib.util.spec_from_file_location("numpy_baseline", ROOT / "benches" / "numpy_baseline.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", metavar="FILE")
    args = parser.parse_args()

    pool = [s for s in map(close.load, sorted((ROOT / "tests" / "fixtures" / "reference").glob("*/*.json"))) if s.frames.shape[1] == 76]
    samples = [pool[k % len(pool)] for k in range(300)]

    loop = best(lambda: [close.analyze(s) for s in samples], args.repeats)
    one = best(lambda: close.analyze_many(samples, threads=1), args.repeats)
    two = best(lambda: close.analyze_many(samples, threads=2), args.repeats)

    baseline = numpy_baseline()
    border = baseline.napkin(1000)
    numpy_disk = best(lambda: baseline.disk(border), args.repeats)
    rust_disk = best(lambda: close.dgli_disk(border), max(args.repeats, 5))

    # Issue 30: verify beside analyze, each sample against the folds found in it.
    goals = [close.analyze(s).folds or [(0.0, 3.14159)] for s in samples]
    verify_loop = best(lambda: [close.verify(s, g) for s, g in zip(samples, goals)], args.repeats)
    analyses = [close.analyze(s) for s in samples]
    verify_only = best(lambda: [close.verify(a, g) for a, g in zip(analyses, goals)], args.repeats)

    per_analysis = loop / len(samples)
    results = {
        "cores": os.cpu_count(),
        "samples": len(samples),
        "distinct_samples": len(pool),
        "loop_s": loop,
        "many_threads1_s": one,
        "many_threads2_s": two,
        "numpy_disk_1000_s": numpy_disk,
        "dgli_disk_1000_s": rust_disk,
        "per_analysis_76_s": per_analysis,
        "verify_loop_s": verify_loop,
        "verify_of_analysis_76_s": verify_only / len(samples),
        "ratios": {
            "boundary loop/many(threads=1) [<= 1.15]": loop / one,
            "threads many(1)/many(2) [>= 1.7]": one / two,
            "disk numpy/close.dgli_disk at N=1000 [>= 50]": numpy_disk / rust_disk,
            "authors' Python 9.74 s / close.analyze at N=76": AUTHORS_SECONDS_AT_76 / per_analysis,
            "verify(sample)/analyze(sample) at N=76": verify_loop / loop,
        },
    }
    for name, value in results["ratios"].items():
        print(f"{name:<50} {value:10.2f}")
    print(f"(loop {loop:.3f} s, many(1) {one:.3f} s, many(2) {two:.3f} s for {len(samples)} samples; "
          f"disk N=1000: numpy {numpy_disk * 1e3:.1f} ms, close {rust_disk * 1e3:.2f} ms; {os.cpu_count()} cores)")
    print(f"(close.verify of an Analysis already made, N=76: {verify_only / len(samples) * 1e6:.0f} µs per call)")
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
