"""Two threads segment two images in about the time one takes (the GIL is released for
the run), against the same two in a row:

  python python/tools/bench_threads.py [--size 1500] [--repeat 3]

Prints the median wall time of one image alone, two in a row, and two on two threads.
"""

import argparse
import statistics
import sys
import threading
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_distributed import blobs  # noqa: E402

import topocontour as tc  # noqa: E402


def timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=1500)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    n = a.size * a.size // 3000
    imgs = [blobs(a.size, n, s)[0] for s in (1, 2)]
    run = lambda img: tc.segment(img, object="dark", auto_seeds=True)  # noqa: E731

    def both_threads():
        ts = [threading.Thread(target=run, args=(img,)) for img in imgs]
        [t.start() for t in ts]
        [t.join() for t in ts]

    one = statistics.median(timed(lambda: run(imgs[0])) for _ in range(a.repeat))
    row = statistics.median(timed(lambda: [run(i) for i in imgs]) for _ in range(a.repeat))
    two = statistics.median(timed(both_threads) for _ in range(a.repeat))
    print(f"command: python python/tools/bench_threads.py --size {a.size} --repeat {a.repeat}")
    print(f"{a.size}^2, {n} objects, auto seeds: one image {one:.2f} s; two in a row {row:.2f} s; "
          f"two on two threads {two:.2f} s = {two / one:.2f}x one image ({row / two:.2f}x faster than in a row)")


if __name__ == "__main__":
    main()
