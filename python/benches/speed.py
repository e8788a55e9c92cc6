"""The package's speed against the library job it calls (docs/python.md, "Speed").

1. Overhead: `fit(V, F)` plus reading `.nets` on a 10⁵-face mesh given as arrays (positions
   and triangles only, so the job repairs, estimates, fits and measures G1), against the job's
   own wall time measured inside the call (`Fit.job_seconds`). Medians of REPEATS runs.
2. Threads: two fits run one after the other on one thread against the same two fits on two
   Python threads, each with `threads=1` (a pool of its own), and with the shared pool.

    python python/benches/speed.py [--repeats N] [--faces-side R]
"""

import argparse
import gc
import json
import statistics
import threading
import time

import triwb


def median_run(fn, repeats):
    times = []
    for _ in range(repeats):
        gc.collect()
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def overhead(V, F, repeats):
    walls, jobs, nets = [], [], []
    for _ in range(repeats):
        gc.collect()
        t = time.perf_counter()
        fit = triwb.fit(V, F)
        t1 = time.perf_counter()
        fit.nets
        t2 = time.perf_counter()
        walls.append(t1 - t)
        nets.append(t2 - t1)
        jobs.append(fit.job_seconds)
        del fit
    job = statistics.median(jobs)
    call = statistics.median([w + n for w, n in zip(walls, nets)])
    return {
        "faces": int(F.shape[0]),
        "job_seconds": job,
        "call_seconds": call,
        "nets_seconds": statistics.median(nets),
        "overhead_percent": 100 * (call - job) / job,
    }


def both(fn):
    ts = [threading.Thread(target=fn) for _ in range(2)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()


def threads(resolution, repeats):
    own = lambda: triwb.fit("ring", resolution=resolution, threads=1)  # noqa: E731
    shared = lambda: triwb.fit("ring", resolution=resolution)  # noqa: E731
    serial_own = median_run(lambda: (own(), own()), repeats)
    parallel_own = median_run(lambda: both(own), repeats)
    serial_shared = median_run(lambda: (shared(), shared()), repeats)
    parallel_shared = median_run(lambda: both(shared), repeats)
    return {
        "faces": resolution * resolution,
        "two_fits_one_thread_seconds": serial_own,
        "two_fits_two_threads_seconds": parallel_own,
        "speedup_threads_1": serial_own / parallel_own,
        "two_fits_shared_pool_seconds": serial_shared,
        "two_fits_two_threads_shared_pool_seconds": parallel_shared,
        "speedup_shared_pool": serial_shared / parallel_shared,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--faces-side", type=int, default=317, help="ring resolution (faces = R²)")
    args = ap.parse_args()
    V, F = triwb.ring(args.faces_side)
    out = {"overhead": overhead(V, F, args.repeats), "threads": threads(args.faces_side, args.repeats)}
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
