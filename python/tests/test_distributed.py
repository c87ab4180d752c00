"""topocontour.distributed on a LocalCluster of two one-thread workers: map_images equals
`topocontour batch` file for file (the binary built from this repository: TOPOCONTOUR_BIN,
else target/release or target/debug), survives a killed worker and skips what is done;
segment_large matches one run over the whole image object for object and refuses an
object larger than the overlap."""

import os
import signal
import subprocess
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest

dd = pytest.importorskip("dask.distributed")
import topocontour  # noqa: E402
from topocontour._napari import png_bytes  # noqa: E402
from topocontour.distributed import map_images, segment_large  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


def write_png(path, img):
    Path(path).write_bytes(png_bytes(img))


def blobs(size, n, seed, rmin=6.0, rmax=14.0, gap=6.0):
    """Dark disks of radius rmin..rmax on a bright noisy background, apart by `gap`."""
    rng = np.random.default_rng(seed)
    img = np.full((size, size), 200.0)
    cells, grid = [], {}
    cell = 2 * rmax + gap
    for _ in range(n * 60):
        if len(cells) >= n:
            break
        r = rng.uniform(rmin, rmax)
        x, y = rng.uniform(r + 4, size - r - 4, 2)
        gx, gy = int(x // cell), int(y // cell)
        near = [c for i in (-1, 0, 1) for j in (-1, 0, 1) for c in grid.get((gx + i, gy + j), [])]
        if all(np.hypot(x - cx, y - cy) > r + cr + gap for cx, cy, cr in near):
            cells.append((x, y, r))
            grid.setdefault((gx, gy), []).append((x, y, r))
    for x, y, r in cells:
        y0, y1, x0, x1 = int(y - r - 2), int(y + r + 3), int(x - r - 2), int(x + r + 3)
        yy, xx = np.mgrid[y0:y1, x0:x1]
        d = np.hypot(xx + 0.5 - x, yy + 0.5 - y)
        img[y0:y1, x0:x1] = np.minimum(img[y0:y1, x0:x1], 200 - 140 * np.clip(r + 0.5 - d, 0, 1))
    img += rng.normal(0, 8, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8), cells


def cli_binary():
    env = os.environ.get("TOPOCONTOUR_BIN")
    found = [Path(env)] if env else []
    found += [REPO / "target" / k / "topocontour" for k in ("release", "debug")]
    return next((p for p in found if p.is_file()), None)


@pytest.fixture(scope="module")
def client():
    with dd.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                         dashboard_address=None) as cluster, dd.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """200 small images (img000.png and img000.tif share a stem, one is called summary)
    and one file that is no image."""
    tifffile = pytest.importorskip("tifffile")
    d = tmp_path_factory.mktemp("images")
    for i in range(198):
        write_png(d / f"img{i:03d}.png", blobs(96, 4, i)[0])
    write_png(d / "summary.png", blobs(96, 3, 500)[0])
    tifffile.imwrite(d / "img000.tif", blobs(96, 3, 501)[0])
    (d / "broken.png").write_bytes(b"not a png")
    return d


def files_of(d):
    return {p.name: p.read_bytes() for p in Path(d).iterdir() if p.is_file()}


SETTINGS = dict(object="dark", auto_seeds=True)


def test_map_images_equals_batch(client, folder, tmp_path):
    report = map_images(folder, tmp_path / "dask", client=client, formats=("json", "csv"),
                        progress=False, **SETTINGS)
    assert report.done == 200 and list(report.failed) == [str(folder / "broken.png")]
    ours = files_of(tmp_path / "dask")
    assert len(ours) == 2 * 200 + 1
    assert {"summary.png.json", "img000.png.json", "img000.tif.csv"} <= set(ours)
    assert ours["summary.csv"].count(b"\n") == 1 + report.objects > 600
    binary = cli_binary()
    if binary is None:
        pytest.skip("no topocontour binary (set TOPOCONTOUR_BIN or cargo build): "
                    "the comparison with batch was not run")
    run = subprocess.run([str(binary), "batch", str(folder), "--out", str(tmp_path / "cli"),
                          "--object", "dark", "--auto-seeds", "--formats", "json,csv"],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "broken.png" in run.stderr, run.stderr
    theirs = files_of(tmp_path / "cli")
    assert sorted(ours) == sorted(theirs)
    differ = [n for n in ours if ours[n] != theirs[n]]
    assert not differ, differ[:5]


def test_rerun_skips_what_is_done(client, folder, tmp_path):
    out = tmp_path / "out"
    first = map_images(folder, out, client=client, formats="json", progress=False, **SETTINGS)
    stamp = {p.name: p.stat().st_mtime_ns for p in out.glob("*.json")}
    again = map_images(folder, out, client=client, formats="json", progress=False, **SETTINGS)
    assert (again.done, again.skipped) == (0, first.done)
    assert {p.name: p.stat().st_mtime_ns for p in out.glob("*.json")} == stamp
    other = map_images(folder, out, client=client, formats="json", progress=False,
                       object="dark", auto_seeds=True, min_area=40)
    assert other.done == first.done and other.skipped == 0


def test_killed_worker_loses_nothing(client, tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    for i in range(40):
        write_png(src / f"m{i:02d}.png", blobs(384, 40, 1000 + i)[0])
    ref = map_images(src, tmp_path / "ref", client=client, progress=False, per_task=2, **SETTINGS)
    assert ref.done == 40
    out = tmp_path / "out"
    got = {}
    job = threading.Thread(target=lambda: got.update(r=map_images(
        src, out, client=client, progress=False, per_task=2, **SETTINGS)))
    job.start()
    deadline = time.time() + 60
    while not list(out.glob("*.json")) and time.time() < deadline:
        time.sleep(0.02)
    pids = client.run(os.getpid)
    os.kill(next(iter(pids.values())), signal.SIGKILL)
    assert job.is_alive() and len(list(out.glob("*.json"))) < 40  # killed mid-run
    job.join(timeout=300)
    report = got["r"]
    assert report.done == 40 and not report.failed
    assert files_of(out) == files_of(tmp_path / "ref")
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]


def test_a_killed_writers_temporaries_are_removed(client, tmp_path):
    # A worker killed between writing a temporary and renaming it leaves it behind; the
    # kill above only sometimes lands there, so the leftover is made here.
    src = tmp_path / "in"
    src.mkdir()
    write_png(src / "a.png", blobs(96, 3, 5)[0])
    out = tmp_path / "out"
    (out / ".topocontour").mkdir(parents=True)
    stale = [out / f".a.json.{'0' * 32}.tmp", out / ".topocontour" / f".a.json.{'f' * 32}.tmp"]
    mine = [out / f".b.json.{'0' * 32}.tmp", out / ".a.json.tmp", out / "a.json.tmp"]
    for p in stale + mine:
        p.write_bytes(b"")
    assert map_images(src, out, client=client, progress=False, **SETTINGS).done == 1
    assert not any(p.exists() for p in stale) and all(p.exists() for p in mine)


def label_matches(whole, tiled):
    """For each object of `whole`, the IoU with the object of `tiled` it overlaps most."""
    n = int(whole.max())
    pair = whole.astype(np.int64) * (int(tiled.max()) + 1) + tiled
    counts = np.bincount(pair.ravel())
    a = np.bincount(whole.ravel(), minlength=n + 1)
    b = np.bincount(tiled.ravel())
    best = np.zeros(n + 1)
    for code in np.nonzero(counts)[0]:
        i, j = divmod(code, int(tiled.max()) + 1)
        if i and j:
            best[i] = max(best[i], counts[code] / (a[i] + b[j] - counts[code]))
    return best[1:]


@pytest.mark.parametrize("size,objects,tile", [(6000, 1500, 2048)])
def test_segment_large_matches_one_run(client, tmp_path, size, objects, tile):
    img, _ = blobs(size, objects, 7, rmin=10, rmax=22)
    whole = topocontour.segment(img, **SETTINGS)
    wl = np.asarray(whole.labels())
    big = segment_large(img, tile=tile, overlap=256, client=client, out=tmp_path / "l.zarr",
                        object="dark")
    tl = big.labels_array()
    outer = [c for c in big.contours if not c["hole"]]
    assert len(outer) == int(wl.max()) == int(tl.max())
    iou = label_matches(wl, tl)
    assert (iou >= 0.98).mean() >= 0.99, np.sort(iou)[:10]
    # No object cut at a seam: each object crossing a core boundary is whole.
    seams = np.arange(tile, size, tile)
    for k, c in enumerate(big.contours):
        pts = c["points"]
        if any(((pts[:, i].min() < s) & (pts[:, i].max() > s)).any() for s in seams for i in (0, 1)):
            assert iou[np.bincount(wl[tl == c["label"]]).argmax() - 1] >= 0.98
    # Each kept ring lies on the whole run's ring of that object: the tiles differ from the
    # whole run only in their pyramid's depth and the local statistics' radius.
    rings = {int(wl[int(p[1]), int(p[0])]): c["points"] for c in whole.contours if not c["hole"]
             for p in [c["points"].mean(0)] if wl[int(p[1]), int(p[0])]}
    far = []
    for c in outer:
        p = c["points"].mean(0)
        q = rings.get(int(wl[int(p[1]), int(p[0])]))
        if q is not None:
            d = np.sqrt(((c["points"][:, None] - q[None]) ** 2).sum(-1))
            far.append(max(d.min(1).max(), d.min(0).max()))
    far = np.array(far)
    assert len(far) >= 0.99 * len(outer)
    assert np.median(far) < 0.5 and np.percentile(far, 99) < 2.0, np.percentile(far, [50, 99, 100])


def test_segment_large_takes_dask_and_zarr(client, tmp_path):
    da = pytest.importorskip("dask.array")
    zarr = pytest.importorskip("zarr")
    img, _ = blobs(1100, 120, 3)
    ref = segment_large(img, tile=512, overlap=128, client=client, object="dark",
                        out=tmp_path / "ref.zarr").labels_array()
    z = zarr.open_array(tmp_path / "in.zarr", mode="w", shape=img.shape, chunks=(256, 256), dtype="u1")
    z[...] = img
    for k, given in enumerate((da.from_array(img, chunks=300), z)):
        got = segment_large(given, tile=512, overlap=128, client=client, object="dark",
                            out=tmp_path / f"got{k}.zarr")
        assert np.array_equal(got.labels_array(), ref)


@pytest.mark.parametrize("radius,centre,others,says", [
    (100, (600, 580), 60, r"give overlap=256 or more"),  # its owner sees it reach the cut
    (300, (512, 600), 60, r"give overlap=512 or more"),
    (300, (512, 600), None, r"larger than the 128 px overlap"),  # no tile sees it whole
])
def test_object_larger_than_overlap_is_refused(client, radius, centre, others, says,
                                               tmp_path, monkeypatch):
    img = np.full((1200, 1200), 200, np.uint8) if others is None else blobs(1200, others, 11)[0]
    yy, xx = np.mgrid[0:1200, 0:1200]
    img[np.hypot(xx - centre[0], yy - centre[1]) < radius] = 60
    # The labels go to a temporary folder of the run's own, removed when it is refused.
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    with pytest.raises(ValueError, match=says) as e:
        segment_large(img, tile=512, overlap=128, client=client, object="dark")
    assert "\n" not in str(e.value)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="2-D"):
        segment_large(np.zeros((4, 4, 4), np.uint8), client=client)


def test_an_object_on_a_seam_comes_out_once(client, tmp_path):
    """Disks centred on the seams between tiles, where two tiles' runs put an object's
    lowest point on either side of the seam: each comes out exactly once."""
    size, tile, r = 1024, 256, 11.0
    rng = np.random.default_rng(5)
    img = np.full((size, size), 200.0)
    cells = []
    seams = np.arange(tile, size, tile)
    for s in seams:
        # Along the seam, away from the crossing seams (disks there would touch).
        for t in [t for t in np.arange(30.0, size - 30.0, 44.0) if np.abs(seams - t).min() > 30]:
            dx, dy = rng.uniform(-0.6, 0.6, 2)
            cells += [(s + dx, t + dy), (t + dy, s + dx)]
    yy, xx = np.mgrid[0:size, 0:size]
    for x, y in cells:
        d = np.hypot(xx + 0.5 - x, yy + 0.5 - y)
        img = np.minimum(img, 200 - 140 * np.clip(r + 0.5 - d, 0, 1))
    img += rng.normal(0, 8, img.shape)
    img = np.clip(img, 0, 255).astype(np.uint8)
    big = segment_large(img, tile=tile, overlap=128, client=client, object="dark",
                        out=tmp_path / "seams.zarr")
    outer = [c for c in big.contours if not c["hole"]]
    centres = np.array([c["points"].mean(0) for c in outer])
    ours = [int(np.argmin(np.hypot(centres[:, 0] - x, centres[:, 1] - y))) for x, y in cells]
    assert len(outer) == len(set(ours)) == len(cells), (len(outer), len(set(ours)), len(cells))
    assert int(big.labels_array().max()) == len(cells)
