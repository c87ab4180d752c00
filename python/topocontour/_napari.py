"""The napari plugin (npe2, `napari.yaml`): a widget that segments the selected image
from a Points layer of seeds, automatic seeds, or a Labels layer of strokes, in a
worker thread, and adds the polygons as a Shapes layer and the objects as a Labels
layer; a reader of topocontour session files; a writer of Shapes layers as GeoJSON.

Polygons with holes are given as napari >= 0.6 reads them: one vertex array per object,
its outer ring then each hole, every ring closed (its first vertex repeated), one after
another. napari's vertices are (row, column), the engine's points (x, y).

The layers are built by plain functions (`segment_layers`, `read_session`,
`write_geojson`) that need no Qt, so they are tested through
`napari.components.ViewerModel`; only `segment_widget` builds a Qt widget.
"""

from __future__ import annotations

import json
import struct
import tempfile
import zlib
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path

import numpy as np

import topocontour

OBJECTS = ("dark", "bright")
# "default": as the command line chooses (track for a taught run, else adaptive).
MODES = ("default", "adaptive", "preserve", "implicit", "track")
# One run at a time: the engine already uses the cores it may, and napari stays free.
_POOL = ThreadPoolExecutor(max_workers=1, thread_name_prefix="topocontour")


def png_bytes(img):
    """A gray 8-bit PNG of a 2-D uint8 array (the strokes file `--train` reads)."""
    h, w = img.shape
    raw = b"".join(b"\0" + np.ascontiguousarray(img[y]).tobytes() for y in range(h))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    head = chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
    return b"\x89PNG\r\n\x1a\n" + head + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def polygons(contours):
    """Each object (outer ring and the holes whose parent it is) as one (N, 2) array of
    (row, column) vertices, rings closed and one after another."""
    shapes = []
    for outer in (c for c in contours if not c["hole"]):
        rings = [outer] + [c for c in contours if c["hole"] and c["parent"] == outer["id"]]
        closed = [np.vstack([r["points"], r["points"][:1]]) for r in rings]
        shapes.append(np.vstack(closed)[:, ::-1].astype(float))
    return shapes


def seeds_of_points(points, sizes=None, radius=4.0):
    """Seed disks (x, y, r) from napari points ((row, column), sizes as diameters)."""
    points = np.asarray(points, dtype=float).reshape(-1, points.shape[-1] if np.ndim(points) else 2)
    if sizes is None:
        sizes = np.full(len(points), 2 * radius)
    sizes = np.broadcast_to(np.asarray(sizes, dtype=float), (len(points),))
    return [(float(p[-1]), float(p[-2]), max(float(s) / 2, 1.0)) for p, s in zip(points, sizes)]


def _image_2d(data):
    """The image as the engine takes it: 2-D; integers or floats (float16 and other
    dtypes converted to float32), RGB to its luminance as the engine's loader reads
    colour files."""
    a = np.asarray(data)
    if a.ndim == 3 and a.shape[-1] in (3, 4):
        a = a[..., :3].astype(np.float32) @ np.array([0.2126, 0.7152, 0.0722], np.float32)
        a = a / (255.0 if np.asarray(data).dtype == np.uint8 else 1.0)
    if a.ndim != 2:
        raise ValueError(f"the image layer must be 2-D (or RGB), got shape {a.shape}")
    if a.dtype.kind not in "iuf" or a.dtype == np.float16:
        a = a.astype(np.float32)
    return np.ascontiguousarray(a)


def segment_layers(image, *, seeds=None, strokes=None, auto_seeds=False, object="dark",
                   mode=None, name="image", **params):
    """Segments `image` (a 2-D array) and gives napari's layer data tuples: the objects
    as a Shapes layer of polygons and as a Labels layer. `seeds`: a list of (x, y, r)
    disks; `strokes`: a label array of the image's shape (1 background, 2 object, 3
    boundary)."""
    kwargs = dict(object=object, mode=None if mode == "default" else mode, **params)
    if seeds:
        kwargs["seeds"] = seeds
    if auto_seeds:
        kwargs["auto_seeds"] = True
    if not (seeds or auto_seeds or strokes is not None):
        raise ValueError("give seeds (a Points layer), automatic seeds, or a strokes layer")
    with tempfile.TemporaryDirectory() as tmp:
        if strokes is not None:
            s = np.asarray(strokes)
            if not s.any():
                raise ValueError("the strokes layer is empty: paint background (1) and objects (2)")
            # The engine reads strokes as the CLI's --train does: a PNG of the image's size.
            kwargs["strokes"] = Path(tmp) / "strokes.png"
            kwargs["strokes"].write_bytes(png_bytes(np.clip(s, 0, 3).astype(np.uint8)))
        result = topocontour.segment(_image_2d(image), name=name, **kwargs)
    shapes = polygons(result.contours)
    shape_meta = {
        "name": f"{name} contours",
        "shape_type": ["polygon"] * len(shapes),
        "edge_color": "yellow",
        "face_color": "transparent",
        "edge_width": 1,
    }
    labels = np.asarray(result.labels())
    return [(shapes, shape_meta, "shapes"), (labels, {"name": f"{name} objects"}, "labels")]


def segment_in_thread(image, **kwargs) -> Future:
    """`segment_layers` in the plugin's worker thread; a Future of its layer tuples."""
    return _POOL.submit(segment_layers, image, **kwargs)


def segment_widget():
    """The dock widget (magicgui, so Qt): image, seeds, strokes, settings; the result
    is returned as a Future so napari adds the layers when the run ends."""
    from typing import List

    import napari
    from magicgui import magic_factory

    @magic_factory(call_button="Segment", object={"choices": OBJECTS},
                   mode={"choices": MODES})
    def segment(image: napari.layers.Image, seeds: napari.layers.Points = None,
                strokes: napari.layers.Labels = None, auto_seeds: bool = False,
                object: str = "dark", mode: str = "default",
                ) -> Future[List[napari.types.LayerDataTuple]]:
        pts = None
        if seeds is not None and len(seeds.data):
            pts = seeds_of_points(seeds.data, seeds.size)
        return segment_in_thread(image.data, seeds=pts,
                                 strokes=None if strokes is None else strokes.data,
                                 auto_seeds=auto_seeds, object=object, mode=mode,
                                 name=image.name)

    return segment()


# --------------------------------------------------------------------------- files


def get_reader(path):
    """The reader of a topocontour session file (JSON whose `format` is
    "topocontour-session"), or None for any other file."""
    if isinstance(path, list) or not str(path).endswith(".json"):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return None
    if not isinstance(doc, dict) or doc.get("format") != "topocontour-session":
        return None
    return read_session


def _shape_vertices(shape):
    """A session's shape ({"Disk": ...}, {"Rect": ...}, {"Polygon": [...]}) as napari
    (shape type, (row, column) vertices)."""
    (kind, v), = shape.items()
    if kind == "Disk":
        c, r = v["center"], v["radius"]
        return "ellipse", np.array([[c["y"] - r, c["x"] - r], [c["y"] - r, c["x"] + r],
                                    [c["y"] + r, c["x"] + r], [c["y"] + r, c["x"] - r]])
    if kind == "Rect":
        lo, hi = v["min"], v["max"]
        return "rectangle", np.array([[lo["y"], lo["x"]], [hi["y"], hi["x"]]])
    return "polygon", np.array([[p["y"], p["x"]] for p in v])


def read_session(path):
    """A session's image (its path relative to the session file's folder, as sessions
    store it) and the shapes its evolution started from."""
    path = Path(path)
    doc = json.loads(path.read_text(encoding="utf-8"))
    image_path = Path(doc["image"]["path"])
    if not image_path.is_absolute():
        image_path = path.parent / image_path
    if not image_path.exists():
        raise ValueError(f"{path.name}: its image {image_path} is missing (replay --image points at a moved one)")
    page = doc.get("page", 0) or 0
    image = np.asarray(topocontour.load(str(image_path), page=page))
    kinds, verts = zip(*[_shape_vertices(s) for s in doc["shapes"]]) if doc["shapes"] else ((), ())
    layers = [(image, {"name": image_path.name}, "image")]
    if verts:
        layers.append((list(verts), {"name": f"{path.stem} shapes", "shape_type": list(kinds),
                                     "edge_color": "cyan", "face_color": "transparent"},
                       "shapes"))
    return layers


def _rings(vertices):
    """The closed rings of one napari polygon (rings one after another, each ending on
    its first vertex), as lists of [x, y]; an unclosed polygon is one ring."""
    rings, start = [], 0
    v = np.asarray(vertices, dtype=float)
    for i in range(1, len(v)):
        if i > start + 2 and np.array_equal(v[i], v[start]):
            rings.append(v[start:i + 1])
            start = i + 1
    if start < len(v):
        rest = v[start:]
        rings.append(np.vstack([rest, rest[:1]]))
    return [[[float(p[-1]), float(p[-2])] for p in r] for r in rings if len(r) >= 4]


def write_geojson(path, data, meta):
    """Writes a Shapes layer as a GeoJSON FeatureCollection of Polygons (outer ring, then
    holes; pixel coordinates x, y) as QuPath reads it; the file written, in a list."""
    types = meta.get("shape_type", ["polygon"] * len(data))
    if isinstance(types, str):
        types = [types] * len(data)
    features = []
    for k, (verts, kind) in enumerate(zip(data, types)):
        if kind in ("line", "path"):
            continue
        features.append({
            "type": "Feature",
            "geometry": {"type": "Polygon", "coordinates": _rings(verts)},
            "properties": {"id": k + 1, "name": f"object {k + 1}", "objectType": "annotation"},
        })
    text = json.dumps({"type": "FeatureCollection", "features": features})
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(path)
    return [str(path)]
