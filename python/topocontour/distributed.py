"""Scale-out on Dask: many images (`map_images`) and one image too large for one run
(`segment_large`), on any `dask.distributed.Client` (a LocalCluster, dask-jobqueue's
SLURMCluster, ...). Dask schedules, retries and shows progress; nothing here is a
scheduler of its own.

`map_images` writes what `topocontour batch` writes: the same names (the stem rule of
`io::folder::output_stems`), bytes and `summary.csv`. An image's outputs are renamed into
place together, then a record in `OUT/.topocontour/` says it is done with these
settings: a retried or re-run task finds it and skips the image, so nothing is written
twice and a killed worker loses only the images Dask then runs again elsewhere. A
worker killed between writing a temporary and renaming it leaves that hidden temporary
behind; once every task is done the client removes those of this run's output names.

`segment_large` segments overlapping tiles with automatic seeds and keeps an object only
in the tile whose core holds its lowest-leftmost point (the ownership rule of StarDist's
big-image prediction, `stardist.big`), so each object comes out once and whole. Two tiles
see an object on their seam a little differently (the lowest point of a round object's
flat bottom moves by pixels along it), so an object that crosses a seam, or comes within
`SEAM` px of one, is not decided by each tile alone: both report it, and the client keeps
one copy (`_settle_seams`) — without that, one object in 10,666 came out twice at 16k². An owned
object reaching a cut edge of its tile, or a part of an object seen at a cut edge that
no tile owns, is refused in one line naming the overlap. The labels go into a zarr
array chunked by the tiles' cores, each chunk written by one task from its tile's and
its eight neighbours' objects: no worker holds the whole image.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import shutil
import tempfile
import uuid
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import topocontour

IMAGE_EXTENSIONS = (".png", ".jpg", ".jpeg", ".tif", ".tiff")
SUMMARY_HEADER = "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,mean_intensity,contour\n"
# batch's formats whose bytes the bindings give (Result.to_<format>), with their names;
# the others (mask, labels, overlay, roi) need the Rust encoders, so they are refused.
FORMATS = {"json": "{}.json", "geojson": "{}.geojson", "csv": "{}.csv", "svg": "{}.svg"}
RECORDS = ".topocontour"
# Objects whose box comes this close to a seam between two cores are settled by the client.
SEAM = 4.0


def list_images(folder):
    """The images of `folder` as `batch` lists them: regular files ending in .png, .jpg,
    .jpeg, .tif or .tiff (any case), not its subfolders, in name order."""
    found = [p for p in Path(folder).iterdir() if p.is_file() and p.suffix.lower() in IMAGE_EXTENSIONS]
    return sorted(found, key=os.fsencode)


def output_stems(paths):
    """The stem each image's outputs are named after, as `batch` names them: the file stem,
    or the whole file name where stems collide (ignoring case) or the stem is `summary`.
    Raises ValueError naming both images where two would still get the same names."""
    stems = [Path(p).stem for p in paths]
    keys = [s.lower() for s in stems]
    chosen = [
        Path(p).name if k == "summary" or keys.count(k) > 1 else s
        for p, s, k in zip(paths, stems, keys)
    ]
    seen = {}
    for p, c in zip(paths, chosen):
        if c.lower() in seen:
            raise ValueError(f"{Path(seen[c.lower()]).name} and {Path(p).name} would get "
                             f"the same output names ({c}.*); rename one")
        seen[c.lower()] = p
    return chosen


def _csv_quoted(text):
    """`text` as one CSV field, as batch quotes names (formula characters guarded)."""
    guard = "'" if text[:1] in ("=", "+", "-", "@", "\t", "\r") else ""
    return '"' + guard + text.replace('"', '""') + '"'


def _ring_measures(pts):
    """(signed area, first moments x, y, perimeter) of a ring, each summed left to right
    as the engine sums them (contours::measure; cumsum adds in order, unlike sum), so
    the figures print identically."""
    p = np.asarray(pts, dtype=np.float64)
    q = np.roll(p, -1, axis=0)
    c = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    d = p - q
    total = lambda v: float(np.cumsum(v)[-1]) if len(v) else 0.0  # noqa: E731
    per = total(np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]))
    mx, my = total((p[:, 0] + q[:, 0]) * c) / 6.0, total((p[:, 1] + q[:, 1]) * c) / 6.0
    return 0.5 * total(c), mx, my, per


def summary_rows(name, result, image):
    """`summary.csv`'s rows of one image (`io::folder::summary_rows`): per region its
    area, perimeter, circularity, centroid, holes, the mean of `image` (the engine's
    [0, 1] luminance, `topocontour.load`) over its pixels, and its outer ring's id."""
    contours = result.contours
    labels = np.asarray(result.labels()).ravel()
    outer = [c for c in contours if not c["hole"]]
    sums = np.bincount(labels, weights=image.ravel().astype(np.float64), minlength=len(outer) + 1)
    counts = np.bincount(labels, minlength=len(outer) + 1)
    quoted = _csv_quoted(name)
    rows = []
    for k, o in enumerate(outer):
        holes = [c for c in contours if c["hole"] and c["parent"] == o["id"]]
        area = mx = my = per = 0.0
        for ring in [o] + holes:
            a, x, y, p = _ring_measures(ring["points"])
            area, mx, my, per = area + a, mx + x, my + y, per + p
        cx, cy = (mx * (1.0 / area), my * (1.0 / area)) if area != 0.0 else (0.0, 0.0)
        circ = 4.0 * math.pi * area / (per * per) if per > 0.0 else 0.0
        mean = sums[k + 1] / max(counts[k + 1], 1)
        rows.append(f"{quoted},{k + 1},{area:.3f},{per:.3f},{circ:.4f},{cx:.3f},{cy:.3f},"
                    f"{len(holes)},{mean:.5f},{o['id']}\n")
    return "".join(rows)


def _write_all(files):
    """Writes {path: bytes} all or nothing: every temporary first, then the renames."""
    temps = []
    try:
        for path, data in files.items():
            tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
            # Not fsynced, as io::atomic: readers see the old file or the whole new one.
            with open(tmp, "wb") as f:
                f.write(data)
            temps.append((tmp, path))
        for tmp, path in temps:
            os.replace(tmp, path)
    finally:
        for tmp, _ in temps:
            if tmp.exists():
                tmp.unlink()


_TEMPORARY = re.compile(r"\.(.+)\.[0-9a-f]{32}\.tmp")  # `_write_all`'s temporaries


def _sweep_temporaries(paths):
    """Removes temporaries a killed writer left beside `paths`; called only when no
    writer of them runs any more."""
    for folder in {p.parent for p in paths}:
        names = {p.name for p in paths if p.parent == folder}
        for entry in folder.iterdir():
            m = _TEMPORARY.fullmatch(entry.name)
            if m and m.group(1) in names:
                entry.unlink(missing_ok=True)


def _settings_key(path, formats, params):
    """What decides an image's outputs: the file (name, size, time) and the settings."""
    st = os.stat(path)
    text = json.dumps([Path(path).name, st.st_size, st.st_mtime_ns, list(formats), params],
                      sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def _record(out_dir, stem):
    return Path(out_dir) / RECORDS / f"{stem}.json"


def _done_rows(path, stem, out_dir, formats, params):
    """The summary rows of an image already done with these settings, else None."""
    try:
        r = json.loads(_record(out_dir, stem).read_text())
    except (OSError, ValueError):
        return None
    outputs = [Path(out_dir) / FORMATS[f].format(stem) for f in formats]
    if r.get("key") != _settings_key(path, formats, params) or not all(map(Path.exists, outputs)):
        return None
    return r["rows"]


def _one_image(path, stem, out_dir, formats, params):
    """Segments one image, writes its outputs and then its record; its summary rows."""
    rows = _done_rows(path, stem, out_dir, formats, params)
    if rows is not None:
        return rows
    result = topocontour.segment(str(path), **params)
    name = Path(path).name
    page = params.get("page") or 1  # the CLI's --page counts from 1, load from 0
    rows = summary_rows(name, result, np.asarray(topocontour.load(str(path), page=page - 1)))
    out_dir = Path(out_dir)
    _write_all({out_dir / FORMATS[f].format(stem): getattr(result, f"to_{f}")().encode()
                for f in formats})
    record = json.dumps({"key": _settings_key(path, formats, params), "rows": rows})
    _write_all({_record(out_dir, stem): record.encode()})
    return rows


def _image_batch(items, out_dir, formats, params):
    """One task: a few images; each gives ("ok", rows) or ("failed", message). A bad
    image fails alone; a crash of the worker makes Dask run the whole task again."""
    done = []
    for path, stem in items:
        try:
            done.append(("ok", _one_image(path, stem, out_dir, formats, params)))
        except (ValueError, RuntimeError, OSError) as e:
            done.append(("failed", str(e).splitlines()[0] if str(e) else type(e).__name__))
    return done


@dataclass
class MapReport:
    """What `map_images` did: images done, skipped (done before), failed (path -> why)."""

    done: int = 0
    skipped: int = 0
    failed: dict = field(default_factory=dict)
    objects: int = 0
    summary: Path = None


def _check_formats(formats):
    formats = [formats] if isinstance(formats, str) else list(formats)
    for i, f in enumerate(formats):
        if f not in FORMATS:
            raise ValueError(f"format {f!r} is not written by map_images (it writes "
                             f"{', '.join(FORMATS)}); use `topocontour batch` for mask, "
                             "labels, overlay or roi")
        if f in formats[:i]:
            raise ValueError(f"formats names {f} twice")
    if not formats:
        raise ValueError("formats is empty: name at least one of " + ", ".join(FORMATS))
    return formats


def map_images(paths, out_dir, *, client, formats=("json",), per_task=None, progress=True,
               retries=2, **params):
    """Segments every image of `paths` (a folder, as `batch` lists it, or a list of
    files) with the same `params` (the keywords of `topocontour.segment`) on `client`,
    writing `OUT/NAME.<format>` and `OUT/summary.csv` as `topocontour batch` does.
    Images already done with the same settings (a re-run) are skipped; a failing image
    is reported in the returned `MapReport` and the others go on."""
    if isinstance(paths, (str, os.PathLike)) and Path(paths).is_dir():
        if not (paths := list_images(paths)):
            raise ValueError("the folder holds no PNG, JPEG or TIFF image")
    paths = [Path(p) for p in paths]
    stems = output_stems(paths)
    formats = _check_formats(formats)
    out_dir = Path(out_dir)
    (out_dir / RECORDS).mkdir(parents=True, exist_ok=True)
    report = MapReport(summary=out_dir / "summary.csv")
    if not os.access(out_dir, os.W_OK):  # as batch, refused before any work
        raise ValueError(f"cannot write {report.summary}: the folder is not writable")
    rows, todo = {}, []
    for p, s in zip(paths, stems):
        r = _done_rows(p, s, out_dir, formats, params)
        if r is None:
            todo.append((str(p), s))
        else:
            rows[s], report.skipped = r, report.skipped + 1
    if per_task is None:
        threads = max(sum(client.nthreads().values()), 1)
        per_task = max(1, min(8, len(todo) // (8 * threads)))
    batches = [todo[i:i + per_task] for i in range(0, len(todo), per_task)]
    token = uuid.uuid4().hex[:8]
    futures = [client.submit(_image_batch, b, str(out_dir), formats, params, retries=retries,
                             key=f"topocontour-images-{token}-{i}", pure=False)
               for i, b in enumerate(batches)]
    if progress and futures:
        from dask.distributed import progress as show

        show(futures)
    try:
        for b, fut in zip(batches, futures):
            for (p, s), (status, value) in zip(b, fut.result()):
                if status == "ok":
                    rows[s], report.done = value, report.done + 1
                else:
                    report.failed[p] = value
    finally:
        # Also when a task failed for good (a worker killed past its retries).
        if all(f.done() for f in futures):
            _sweep_temporaries([out_dir / FORMATS[f].format(s) for s in stems for f in formats]
                               + [_record(out_dir, s) for s in stems])
    text = SUMMARY_HEADER + "".join(rows.get(s, "") for s in stems)
    report.objects = sum(rows[s].count("\n") for s in rows)
    _write_all({report.summary: text.encode()})
    return report


@dataclass
class LargeResult:
    """What `segment_large` gives: the kept objects' rings in image coordinates (dicts as
    `Result.contours`, plus `label`, ids renumbered over the whole image), and `labels`,
    the zarr array (0 outside, each object its own number) chunked by the tiles' cores."""

    contours: list
    labels: object
    tile: int
    overlap: int

    def labels_array(self):
        """The whole label image as one numpy array (only where it fits in memory)."""
        return np.asarray(self.labels[...])


def _grid(height, width, tile, overlap):
    """Each tile's (core, region) as (y0, y1, x0, x1): cores tile the image, regions add
    `overlap` on every side, clipped to it."""
    tiles = []
    for y0 in range(0, height, tile):
        for x0 in range(0, width, tile):
            core = (y0, min(y0 + tile, height), x0, min(x0 + tile, width))
            region = (max(0, y0 - overlap), min(height, core[1] + overlap),
                      max(0, x0 - overlap), min(width, core[3] + overlap))
            tiles.append((core, region))
    return tiles


def _deepest_pixel(mask):
    """(row, column) of a pixel deepest inside `mask` (the last erosion not empty)."""
    inner = mask
    while True:
        e = inner.copy()
        e[1:] &= inner[:-1]
        e[:-1] &= inner[1:]
        e[:, 1:] &= inner[:, :-1]
        e[:, :-1] &= inner[:, 1:]
        if not e.any():
            break
        inner = e
    ys, xs = np.nonzero(inner)
    return int(ys[len(ys) // 2]), int(xs[len(xs) // 2])


def _segment_tile(data, core, region, shape, overlap, reach, params):
    """Segments one tile's region. Returns ("ok", owned objects (rings shifted to image
    coordinates, the label crop from the engine's own raster), probes: a pixel deep
    inside each object that leaves the region, which its owner must cover), or
    ("refused", why) for an owned object that reaches a cut edge of the overlap."""
    ry0, ry1, rx0, rx1 = region
    try:
        result = topocontour.segment(np.ascontiguousarray(data), auto_seeds=True, **params)
    except ValueError as e:
        if "automatic seeds found no" in str(e):  # a tile of background alone
            return ("ok", [], [])
        raise
    labels = np.asarray(result.labels())
    contours = result.contours
    # A cut edge is a side of the region inside the image; the image's own border is not.
    cut = (ry0 > 0, ry1 < shape[0], rx0 > 0, rx1 < shape[1])
    # Seams: core edges that another tile's core shares.
    seams = (core[0] > 0, core[1] < shape[0], core[2] > 0, core[3] < shape[1])
    kept, probes = [], []
    for k, o in enumerate(c for c in contours if not c["hole"]):
        pts = o["points"]
        order = np.lexsort((pts[:, 0], pts[:, 1]))[0]  # lowest y, then lowest x
        ax, ay = pts[order, 0] + rx0, pts[order, 1] + ry0
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        y0, x0 = max(int(lo[1]) - 1, 0), max(int(lo[0]) - 1, 0)
        y1, x1 = min(int(hi[1]) + 2, ry1 - ry0), min(int(hi[0]) + 2, rx1 - rx0)
        crop = labels[y0:y1, x0:x1] == k + 1
        near = (lo[1] < reach, hi[1] > (ry1 - ry0) - reach, lo[0] < reach, hi[0] > (rx1 - rx0) - reach)
        near_cut = any(c and e for c, e in zip(cut, near))
        owned = core[0] <= ay < core[1] and core[2] <= ax < core[3]
        box = (lo[1] + ry0, lo[0] + rx0, hi[1] + ry0, hi[0] + rx0)  # y0, x0, y1, x1
        # Near this core (its box meets the core grown by SEAM), and not well inside it
        # on a seam's side.
        near_core = (box[0] < core[1] + SEAM and box[2] > core[0] - SEAM
                     and box[1] < core[3] + SEAM and box[3] > core[2] - SEAM)
        off_inner = ((seams[0] and box[0] < core[0] + SEAM) or (seams[1] and box[2] > core[1] - SEAM)
                     or (seams[2] and box[1] < core[2] + SEAM) or (seams[3] and box[3] > core[3] - SEAM))
        on_seam = near_core and off_inner
        # An object this tile does not own and does not see whole is its owner's.
        if not owned and (not on_seam or near_cut):
            if near_cut and crop.any():
                py, px = _deepest_pixel(crop)
                probes.append((py + y0 + ry0, px + x0 + rx0))
            continue
        if near_cut:
            size = int(math.ceil(max(hi - lo))) + reach
            return ("refused", (
                f"an object at ({ax:.0f}, {ay:.0f}) spans {size - reach} px and reaches the "
                f"edge of its tile's {overlap} px overlap: give overlap={-(-size // 64) * 64} "
                f"or more (the object plus the {reach} px reach)"))
        rings = [o] + [c for c in contours if c["hole"] and c["parent"] == o["id"]]
        kept.append({
            "rings": [(r["hole"], r["area"], r["points"] + (rx0, ry0)) for r in rings],
            "box": (y0 + ry0, x0 + rx0), "crop": np.packbits(crop), "crop_shape": crop.shape,
            # What the client settles a seam with: the point and the box in the image.
            "seam": (float(ax), float(ay), tuple(float(b) for b in box)) if on_seam else None,
        })
    return ("ok", kept, probes)


def _box_iou(a, b):
    """IoU of two (y0, x0, y1, x1) boxes."""
    h = min(a[2], b[2]) - max(a[0], b[0])
    w = min(a[3], b[3]) - max(a[1], b[1])
    if h <= 0 or w <= 0:
        return 0.0
    area = lambda r: (r[2] - r[0]) * (r[3] - r[1])  # noqa: E731
    return h * w / (area(a) + area(b) - h * w)


def _settle_seams(tiles, seams):
    """Which of the objects that tiles reported on a seam each tile keeps. `seams[t]`:
    tile t's (index in its kept list, x, y, box). Copies of one object from different
    tiles (boxes with IoU above one half) are one object: the copy whose tile's core holds
    the copies' mean point is kept (the first such), the others dropped; an object only one
    tile saw is kept where its point lies. Returns per tile the set of indices to drop."""
    entries = [(t, j, x, y, box) for t, ss in enumerate(seams) for j, x, y, box in ss]
    drop = [set() for _ in tiles]
    group = list(range(len(entries)))
    # Copies lie on one spot: compare only entries whose box centres share a bucket or
    # touch one.
    cell = 64.0
    buckets = {}
    for i, e in enumerate(entries):
        b = e[4]
        key = (int((b[0] + b[2]) / 2 // cell), int((b[1] + b[3]) / 2 // cell))
        buckets.setdefault(key, []).append(i)

    def root(i):
        while group[i] != i:
            group[i] = group[group[i]]
            i = group[i]
        return i

    for (ky, kx), members in buckets.items():
        near = [j for dy in (-1, 0, 1) for dx in (-1, 0, 1) for j in buckets.get((ky + dy, kx + dx), [])]
        for a in members:
            for b in near:
                if a < b and entries[a][0] != entries[b][0] and _box_iou(entries[a][4], entries[b][4]) > 0.5:
                    group[root(a)] = root(b)
    copies = {}
    for i in range(len(entries)):
        copies.setdefault(root(i), []).append(entries[i])
    for members in copies.values():
        mx = sum(m[2] for m in members) / len(members)
        my = sum(m[3] for m in members) / len(members)
        holds = [m for m in members
                 if tiles[m[0]][0][0] <= my < tiles[m[0]][0][1]
                 and tiles[m[0]][0][2] <= mx < tiles[m[0]][0][3]]
        keep = (holds or members)[0]
        for m in members:
            if m is not keep:
                drop[m[0]].add(m[1])
    return drop


def _write_chunk(path, core, pieces, probes):
    """Writes one output chunk (a tile's core) from the objects that reach into it
    (pieces: (first label, that tile's kept objects)); returns the probes in the core
    that no kept object covers."""
    import zarr

    cy0, cy1, cx0, cx1 = core
    out = np.zeros((cy1 - cy0, cx1 - cx0), dtype=np.uint32)
    for first, kept in pieces:
        for j, obj in enumerate(kept):
            h, w = obj["crop_shape"]
            crop = np.unpackbits(obj["crop"], count=h * w).reshape(h, w).astype(bool)
            by, bx = obj["box"]
            ys, xs = max(by, cy0), max(bx, cx0)
            ye, xe = min(by + h, cy1), min(bx + w, cx1)
            if ys < ye and xs < xe:
                part = crop[ys - by:ye - by, xs - bx:xe - bx]
                out[ys - cy0:ye - cy0, xs - cx0:xe - cx0][part] = first + j
    zarr.open_array(path, mode="r+")[cy0:cy1, cx0:cx1] = out
    return [(y, x) for y, x in probes if not out[y - cy0, x - cx0]]


def _tile_data(client, array, region):
    """A future of a tile region's pixels, read where the array lives: a dask array on
    the workers, a zarr array by the worker that needs it, a numpy array from here."""
    y0, y1, x0, x1 = region
    if hasattr(array, "dask"):
        return client.compute(array[y0:y1, x0:x1])
    store = getattr(array, "store", None)
    if type(array).__module__.startswith("zarr") and type(store).__name__ != "MemoryStore":
        return client.submit(lambda a, r: np.asarray(a[r[0]:r[1], r[2]:r[3]]), array, region,
                             pure=False)
    return client.scatter(np.asarray(array[y0:y1, x0:x1]))


def segment_large(array, *, tile=4096, overlap=None, client, out=None, reach=16, **params):
    """Segments a 2-D numpy, dask or zarr `array` too large for one run, tile by tile on
    `client`, with automatic seeds and `params` (the keywords of `topocontour.segment`).
    `overlap` (default tile/8, at least 128) must exceed the largest object plus `reach`;
    an object that does not fit raises ValueError. `out`: where the zarr labels go (a
    folder; default a new temporary one). Returns a `LargeResult`."""
    import zarr

    if len(getattr(array, "shape", ())) != 2:
        raise ValueError(f"segment_large takes a 2-D array (height, width), got shape "
                         f"{tuple(getattr(array, 'shape', ()))}")
    for given in ("seeds", "wrap", "rects", "strokes"):
        if params.get(given) is not None:
            raise ValueError(f"segment_large seeds each tile itself (auto seeds); {given} "
                             "applies to one run: call topocontour.segment on a crop")
    params.pop("auto_seeds", None)
    height, width = (int(n) for n in array.shape)
    if overlap is None:
        overlap = max(128, (tile // 8) // 64 * 64)
    if tile <= 0 or overlap < 0:
        raise ValueError(f"tile ({tile}) must be positive and overlap ({overlap}) not negative")
    made = out is None  # a folder of our own, removed again if the run fails
    out = str(out) if out is not None else tempfile.mkdtemp(suffix=".zarr")
    try:
        labels = zarr.open_array(out, mode="w", shape=(height, width), chunks=(tile, tile),
                                 dtype="uint32", fill_value=0)
        tiles = _grid(height, width, tile, overlap)
        segs = [client.submit(_segment_tile, _tile_data(client, array, region), core, region,
                              (height, width), overlap, reach, params, pure=False)
                for core, region in tiles]
        counted = client.gather([client.submit(  # only counts, probes and seams come here
            lambda r: (r[0], len(r[1]), r[2],
                       [(j, *o["seam"]) for j, o in enumerate(r[1]) if o["seam"] is not None])
            if r[0] == "ok" else r, s) for s in segs])
        refused = [c[1] for c in counted if c[0] == "refused"]
        if refused:
            raise ValueError(refused[0])
        drop = _settle_seams(tiles, [c[3] for c in counted])
        segs = [client.submit(lambda r, d: (r[0], [o for j, o in enumerate(r[1]) if j not in d], r[2]),
                              s, sorted(d)) for s, d in zip(segs, drop)]
        firsts = np.concatenate([[1], 1 + np.cumsum([c[1] - len(d) for c, d in zip(counted, drop)])])[:-1]
        per_row = math.ceil(width / tile)
        writes = []
        for t, (core, _) in enumerate(tiles):
            ty, tx = divmod(t, per_row)
            near = [n for n in range(len(tiles))
                    if abs(n // per_row - ty) <= 1 and abs(n % per_row - tx) <= 1]
            pieces = [client.submit(lambda r, f: (f, r[1]), segs[n], int(firsts[n])) for n in near]
            probes = [p for n in near for p in counted[n][2]
                      if core[0] <= p[0] < core[1] and core[2] <= p[1] < core[3]]
            writes.append(client.submit(_write_chunk, out, core, pieces, probes, pure=False))
        lost = [p for w in client.gather(writes) for p in w]
        if lost:
            raise ValueError(f"an object at ({lost[0][1]}, {lost[0][0]}) is larger than the "
                             f"{overlap} px overlap, so no tile sees it whole: give segment_large "
                             f"a larger overlap (the largest object plus {reach} px)")
        return LargeResult(_gather_contours(segs, firsts), labels, tile, overlap)
    except BaseException:
        if made:
            shutil.rmtree(out, ignore_errors=True)
        raise


def _gather_contours(segs, firsts):
    """The kept objects' rings, renumbered: ring ids in order over the whole image, each
    hole's parent its object's outer ring, an object's label its number in `labels`."""
    contours, next_id = [], 0
    for seg, first in zip(segs, firsts):
        for j, obj in enumerate(seg.result()[1]):
            outer_id = next_id
            for hole, area, pts in obj["rings"]:
                contours.append({"id": next_id, "hole": hole, "parent": outer_id if hole else None,
                                 "area": area, "points": pts, "label": int(first) + j})
                next_id += 1
    return contours
