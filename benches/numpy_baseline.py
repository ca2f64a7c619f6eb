#!/usr/bin/env python3
"""BASELINE, not part of the product: a vectorised numpy dGLI disk, the speed a competent
Python user gets with the same formula (Levitt's GLI with clamped asin, dGLI by the 2eps/eps
finite difference, all N(N-1)/2 edge pairs). scripts/bench.sh times it beside `cargo bench`.

usage: numpy_baseline.py N [REPEATS]  -> median seconds for one disk of an N-vertex napkin
"""
import sys
import time

import numpy as np

EPS = 1e-5


def unit(v):
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, norm, out=np.zeros_like(v), where=norm > 0)


def gli(a, b, c, d):
    n1, n2 = unit(np.cross(c - a, d - a)), unit(np.cross(d - a, d - b))
    n3, n4 = unit(np.cross(d - b, c - b)), unit(np.cross(c - b, c - a))
    asin = lambda u, v: np.arcsin(np.clip(np.sum(u * v, axis=-1), -1.0, 1.0))
    sign = np.sign(np.sum(np.cross(d - c, b - a) * (c - a), axis=-1))
    return sign * (asin(n1, n2) + asin(n2, n3) + asin(n3, n4) + asin(n4, n1))


def disk(points):
    n = len(points)
    i, j = np.triu_indices(n, k=1)
    a, b, c, d = points[i], points[(i + 1) % n], points[j], points[(j + 1) % n]
    lift = np.array([0.0, 0.0, EPS])
    return (gli(a, b + 2 * lift, c, d + 2 * lift) - gli(a, b + lift, c, d + lift)) / EPS


def napkin(n):
    per = n // 4
    t = np.arange(per) / per
    sides = [(t, 0 * t), (1 + 0 * t, t), (1 - t, 1 + 0 * t), (0 * t, 1 - t)]
    xy = np.concatenate([np.stack(s, axis=1) for s in sides]) - 0.5
    k = np.arange(len(xy))
    xy += 1e-5 * np.stack([np.sin(7 * k), np.cos(3 * k)], axis=1)
    return np.concatenate([xy, np.zeros((len(xy), 1))], axis=1)


if __name__ == "__main__":
    n = int(sys.argv[1])
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    points = napkin(n)
    times = []
    for _ in range(reps):
        t0 = time.perf_counter()
        disk(points)
        times.append(time.perf_counter() - t0)
    print(f"{sorted(times)[len(times) // 2]:.6f}")
