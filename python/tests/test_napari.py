"""The napari plugin without Qt: its manifest validates, the segmentation's layers go into
a `napari.components.ViewerModel` (holes as napari >= 0.6 reads them), a session file
opens as its image and shapes, and a Shapes layer is written as GeoJSON."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

napari = pytest.importorskip("napari")
npe2 = pytest.importorskip("npe2")
from napari.components import ViewerModel  # noqa: E402
from napari.layers import Layer  # noqa: E402

from topocontour import _napari  # noqa: E402
from test_distributed import write_png  # noqa: E402


def annulus_and_disk():
    """A dark ring (an object with a hole) and a dark disk on a bright background."""
    yy, xx = np.mgrid[0:160, 0:200]
    r = np.hypot(xx - 60, yy - 80)
    img = np.full((160, 200), 210, np.uint8)
    img[(r > 18) & (r < 40)] = 50
    img[np.hypot(xx - 150, yy - 80) < 20] = 50
    return img


def test_manifest_validates():
    pm = npe2.PluginManifest.from_distribution("topocontour")
    assert pm.name == "topocontour"
    ids = {c.id for c in pm.contributions.commands}
    assert {"topocontour.segment", "topocontour.get_reader", "topocontour.write_geojson"} <= ids
    path = Path(_napari.__file__).with_name("napari.yaml")
    assert npe2.PluginManifest.from_file(path).name == "topocontour"
    npe2_cli = Path(sys.executable).with_name("npe2")
    if npe2_cli.exists():
        run = subprocess.run([str(npe2_cli), "validate", "topocontour"], capture_output=True, text=True)
        assert run.returncode == 0 and "valid" in run.stdout, run.stdout + run.stderr


def add(viewer, tuples):
    for data, meta, kind in tuples:
        viewer.add_layer(Layer.create(data, meta, kind))


def test_seeds_from_points_give_shapes_and_labels():
    img = annulus_and_disk()
    viewer = ViewerModel()
    viewer.add_image(img, name="cells")
    points = viewer.add_points(np.array([[80.0, 31.0], [80.0, 150.0]]), size=8)
    seeds = _napari.seeds_of_points(points.data, points.size)
    assert seeds[0] == (31.0, 80.0, 4.0)
    layers = _napari.segment_in_thread(img, seeds=seeds, object="dark", name="cells").result(60)
    add(viewer, layers)
    shapes, labels = viewer.layers["cells contours"], viewer.layers["cells objects"]
    assert len(shapes.data) == 2 and labels.data.max() == 2
    # The ring's polygon holds its hole: napari's own raster of it leaves the hole empty.
    masks = shapes.to_masks(mask_shape=img.shape)
    ring = masks[np.argmax([m[80, 21] for m in masks])]
    assert not ring[80, 60] and ring[80, 25]
    theirs = labels.data == labels.data[80, 25]
    iou = (ring & theirs).sum() / (ring | theirs).sum()
    assert iou > 0.95, iou


def test_auto_seeds_and_strokes():
    img = annulus_and_disk()
    (shapes, _, _), (labels, _, _) = _napari.segment_layers(img, auto_seeds=True)
    assert len(shapes) == labels.max() >= 2
    strokes = np.zeros(img.shape, np.uint8)
    strokes[5:10, 5:195] = 1
    strokes[78:82, 140:160] = 2
    strokes[78:82, 40:50] = 2
    (shapes, _, _), (labels, _, _) = _napari.segment_layers(img, strokes=strokes, auto_seeds=True)
    assert labels.max() >= 2 and labels[80, 150] > 0
    with pytest.raises(ValueError, match="seeds"):
        _napari.segment_layers(img)


def test_session_reader(tmp_path):
    img = annulus_and_disk()
    write_png(tmp_path / "cells.png", img)
    session = {"format": "topocontour-session", "version": 1,
               "image": {"path": "cells.png", "width": 200, "height": 160, "crc32": 0},
               "shapes": [{"Disk": {"center": {"x": 150.0, "y": 80.0}, "radius": 5.0}},
                          {"Rect": {"min": {"x": 10.0, "y": 20.0}, "max": {"x": 30.0, "y": 40.0}}}],
               "params": {}, "frames": 10, "finished": True, "edits": []}
    path = tmp_path / "cells.session.json"
    path.write_text(json.dumps(session))
    assert _napari.get_reader(str(tmp_path / "cells.png")) is None
    reader = _napari.get_reader(str(path))
    viewer = ViewerModel()
    add(viewer, reader(str(path)))
    assert viewer.layers["cells.png"].data.shape == (160, 200)
    shapes = viewer.layers["cells.session shapes"]
    assert list(shapes.shape_type) == ["ellipse", "rectangle"]
    (tmp_path / "cells.png").unlink()
    with pytest.raises(ValueError, match="missing"):
        reader(str(path))


def test_geojson_writer_keeps_holes(tmp_path):
    img = annulus_and_disk()
    (shapes, meta, _), _ = _napari.segment_layers(img, seeds=[(31, 80, 4), (150, 80, 4)])
    viewer = ViewerModel()
    layer = Layer.create(shapes, meta, "shapes")
    viewer.add_layer(layer)
    out = _napari.write_geojson(str(tmp_path / "c.geojson"), layer.data, {"shape_type": layer.shape_type})
    doc = json.loads(Path(out[0]).read_text())
    rings = sorted(len(f["geometry"]["coordinates"]) for f in doc["features"])
    assert rings == [1, 2]
    for f in doc["features"]:
        for ring in f["geometry"]["coordinates"]:
            assert ring[0] == ring[-1]
