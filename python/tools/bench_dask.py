"""Figures of topocontour.distributed, printed with the command that made them:

  python python/tools/bench_dask.py [--bin target/release/topocontour] [--images 200]
      [--sizes 6000,16000] [--skip-map] [--skip-large]

1. map_images against `topocontour batch --jobs 2` on the same folder (2 workers of one
   thread; the cluster is started before the clock).
2. segment_large on generated images (6000^2 with 1,500 objects, 16k^2 with the same
   density) in 2048^2 tiles: wall time, the peak resident memory of each worker (its
   VmHWM; a fresh cluster per figure), and the objects against the generated truth.
3. The peer: dask-image, a Gaussian smoothing by map_overlap, Otsu's threshold, and
   ndmeasure.label, on the same cluster and image.
"""

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))
from test_distributed import blobs, write_png  # noqa: E402


def cluster():
    from dask.distributed import Client, LocalCluster

    c = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                     memory_limit="4GB")
    return c, Client(c)


def bench_map(binary, n, size):
    from topocontour.distributed import map_images

    work = Path(tempfile.mkdtemp(prefix="bench-map-"))
    src = work / "in"
    src.mkdir()
    for i in range(n):
        write_png(src / f"img{i:04d}.png", blobs(size, max(4, size * size // 6000), i)[0])
    t = time.perf_counter()
    subprocess.run([binary, "batch", str(src), "--out", str(work / "cli"), "--object", "dark",
                    "--auto-seeds", "--jobs", "2"], check=True, capture_output=True)
    t_cli = time.perf_counter() - t
    c, client = cluster()
    client.submit(lambda: 0).result()
    t = time.perf_counter()
    r = map_images(src, work / "dask", client=client, progress=False, object="dark", auto_seeds=True)
    t_dask = time.perf_counter() - t
    client.close(), c.close()
    same = all((work / "cli" / p.name).read_bytes() == p.read_bytes()
               for p in (work / "dask").iterdir() if p.is_file())
    print(f"map_images: {n} images of {size}^2: batch --jobs 2 {t_cli:.2f} s "
          f"({n / t_cli:.1f}/s), map_images on 2 workers {t_dask:.2f} s ({n / t_dask:.1f}/s): "
          f"{t_cli / t_dask:.2f}x batch; outputs identical: {same}; done {r.done}")
    shutil.rmtree(work)


def truth_iou(labels, cells):
    """Share of the generated disks that one object covers with IoU >= 0.9."""
    hits = 0
    for x, y, r in cells:
        y0, y1, x0, x1 = int(y - r - 3), int(y + r + 4), int(x - r - 3), int(x + r + 4)
        yy, xx = np.mgrid[y0:y1, x0:x1]
        disk = np.hypot(xx + 0.5 - x, yy + 0.5 - y) < r
        crop = np.asarray(labels[y0:y1, x0:x1])
        ids, counts = np.unique(crop[disk], return_counts=True)
        k = ids[np.argmax(counts)]
        if k:
            obj = crop == k
            hits += (obj & disk).sum() / (obj | disk).sum() >= 0.9
    return hits / len(cells)


def vm_hwm_mb():
    """This process's peak resident memory (VmHWM: reset by exec, unlike ru_maxrss, which a
    spawned worker inherits from the process that forked it)."""
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmHWM")) / 1024


def worker_peaks(client):
    return list(client.run(vm_hwm_mb).values())


def bench_large(size, tile):
    import dask.array as da
    import zarr
    from dask_image import ndfilters, ndmeasure

    from topocontour.distributed import segment_large

    n = int(1500 * (size / 6000) ** 2)
    work = Path(tempfile.mkdtemp(prefix="bench-large-"))
    img, cells = blobs(size, n, 7, rmin=10, rmax=22)
    z = zarr.open_array(work / "img.zarr", mode="w", shape=img.shape, chunks=(tile, tile), dtype="u1")
    z[...] = img
    del img
    c, client = cluster()
    base = max(worker_peaks(client))
    t = time.perf_counter()
    res = segment_large(z, tile=tile, overlap=256, client=client, out=work / "labels.zarr",
                        object="dark")
    took = time.perf_counter() - t
    peaks = worker_peaks(client)
    kept = sum(not c["hole"] for c in res.contours)
    print(f"segment_large {size}^2, {len(cells)} objects, tiles {tile}^2: {took:.1f} s, "
          f"peak RSS per worker {', '.join(f'{p:.0f}' for p in peaks)} MB (idle {base:.0f}); "
          f"{kept} objects, {truth_iou(res.labels, cells):.3f} of the disks found with IoU >= 0.9")
    client.close(), c.close()
    c, client = cluster()
    t = time.perf_counter()
    arr = da.from_zarr(str(work / "img.zarr")).astype(np.float32)
    smooth = ndfilters.gaussian_filter(arr, sigma=1.5)
    sample = np.asarray(smooth[::8, ::8].compute())
    from skimage.filters import threshold_otsu

    mask = smooth < threshold_otsu(sample)
    labels, count = ndmeasure.label(mask)
    out = da.to_zarr(labels.astype(np.uint32), str(work / "peer.zarr"), compute=False)
    client.compute(out).result()
    count = int(count.compute())
    took = time.perf_counter() - t
    peaks = worker_peaks(client)
    found = truth_iou(zarr.open_array(str(work / "peer.zarr")), cells)
    print(f"peer dask-image (gaussian map_overlap, Otsu, ndmeasure.label) {size}^2: {took:.1f} s, "
          f"peak RSS per worker {', '.join(f'{p:.0f}' for p in peaks)} MB; {count} objects, "
          f"{found:.3f} of the disks found with IoU >= 0.9")
    client.close(), c.close()
    shutil.rmtree(work)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=str(HERE.parents[1] / "target" / "release" / "topocontour"))
    ap.add_argument("--images", type=int, default=200)
    ap.add_argument("--image-size", type=int, default=256)
    ap.add_argument("--sizes", default="6000,16000")
    ap.add_argument("--tile", type=int, default=2048)
    ap.add_argument("--skip-map", action="store_true")
    ap.add_argument("--skip-large", action="store_true")
    a = ap.parse_args()
    print("command: python python/tools/bench_dask.py " + " ".join(sys.argv[1:]))
    if not a.skip_map:
        bench_map(a.bin, a.images, a.image_size)
    if not a.skip_large:
        for s in a.sizes.split(","):
            bench_large(int(s), a.tile)


if __name__ == "__main__":
    main()
