"""The GIL is released during the work: other Python threads run while a fit runs, and fits
from two threads at once give what they give one at a time."""

import threading
import time

import numpy as np

import triwb

# A fit long enough that the main thread's progress during it is unmistakable (10⁴ faces of the
# ring, optimized curves: about 0.1 s on the 2-core CI machine).
RESOLUTION = 100
# The main thread, counting while the fit runs, must reach at least this share of the count it
# reaches alone in the same time: a held GIL gives it none (the call holds it from start to end).
MIN_SHARE = 0.2


def count_for(seconds):
    n, end = 0, time.perf_counter() + seconds
    while time.perf_counter() < end:
        n += 1
    return n


def test_other_threads_run_while_a_fit_runs():
    done = threading.Event()
    elapsed = {}

    def work():
        t = time.perf_counter()
        triwb.fit("ring", resolution=RESOLUTION, curves="optimized", threads=1)
        elapsed["s"] = time.perf_counter() - t
        done.set()

    worker = threading.Thread(target=work)
    n = 0
    worker.start()
    while not done.is_set():
        n += 1
    worker.join()
    alone = count_for(elapsed["s"])
    assert n >= MIN_SHARE * alone, f"main thread counted {n} during the fit, {alone} alone"


def test_two_threads_fit_as_one_at_a_time():
    meshes = [triwb.sphere(3), triwb.ring(40)]
    serial = [triwb.fit(m.V, m.F, curves="optimized").nets for m in meshes]
    results = [None, None]

    def work(i):
        results[i] = triwb.fit(meshes[i].V, meshes[i].F, curves="optimized", threads=1).nets

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        assert np.array_equal(a, b)


def test_threads_must_be_positive():
    import pytest

    with pytest.raises(triwb.UsageError, match="threads"):
        triwb.fit("octa", threads=0)
