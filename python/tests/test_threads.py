"""The GIL is released while a run evolves: another Python thread keeps running during
the call. (The two-images-in-the-time-of-one figure is python/tools/bench_threads.py's.)"""

import threading
import time

import numpy as np
from conftest import discs

import topocontour as tc


def test_other_threads_run_while_segment_works():
    img = np.tile(discs(), (8, 8))  # 960 × 1280: about half a second
    t0 = time.perf_counter()
    tc.segment(img, wrap=4)
    alone = time.perf_counter() - t0
    done = threading.Event()
    spans = []

    def work():
        t = time.perf_counter()
        tc.segment(img, wrap=4)
        spans.append(time.perf_counter() - t)
        done.set()

    worker = threading.Thread(target=work)
    ticks, last, gap = 0, time.perf_counter(), 0.0
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        gap, last = max(gap, now - last), now
        ticks += 1
        time.sleep(0.001)
    worker.join()
    call = spans[0]
    # Holding the GIL, the call would stop this loop for its whole length: the longest
    # pause would be the call itself. Released, the loop ticks all along.
    assert call > 0.1, f"the run ({call:.3f} s, alone {alone:.3f} s) is too short to tell"
    assert gap < 0.5 * call, f"this thread stood still {gap:.3f} s of a {call:.3f} s run"
    assert ticks >= 10
