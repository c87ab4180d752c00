"""segment() against the command line on images the tests make: the JSON byte for byte,
the exports, and the messages of bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest
import tifffile
from conftest import cli_message, discs, write_float_tiff, write_png

import topocontour as tc

RUNS = [
    # (keywords, the same as flags)
    (dict(wrap=4), ["--wrap", "4", "--object", "dark"]),
    (dict(seeds=[(30, 30, 5), (110, 40, 6.5)], max_frames=60), ["--seed", "30,30,5", "--seed", "110,40,6.5", "--object", "dark", "--max-frames", "60"]),
    (dict(auto_seeds=True, mode="preserve"), ["--auto-seeds", "--object", "dark", "--mode", "preserve"]),
    (dict(rects=[(5, 5, 150, 110)], min_area=30, no_new_holes=True), ["--rect", "5,5,150,110", "--object", "dark", "--min-area", "30", "--no-new-holes"]),
    (dict(wrap=3, mode="implicit", local_radius=9.5), ["--wrap", "3", "--object", "dark", "--mode", "implicit", "--local-radius", "9.5"]),
]


@pytest.mark.parametrize("keywords,flags", RUNS)
def test_json_is_the_cli_json_byte_for_byte(tmp_path, cli, keywords, flags):
    img = discs()
    png = write_png(tmp_path / "discs.png", img)
    out = tmp_path / "cli.json"
    code, err = cli("segment", png, *flags, "--json", out)
    assert code == 0, err
    expected = out.read_text()
    assert tc.segment(img, name="discs.png", **keywords).to_json() == expected
    assert tc.segment(png, **keywords).to_json() == expected


def test_sixteen_bit_and_bright_objects_match_the_cli(tmp_path, cli):
    img = (discs(bright=True).astype(np.uint16) * 257 + 11).astype(np.uint16)
    png = write_png(tmp_path / "b16.png", img)
    out = tmp_path / "cli.json"
    code, err = cli("segment", png, "--wrap", "4", "--object", "bright", "--json", out)
    assert code == 0, err
    got = tc.segment(img, wrap=4, object="bright", name="b16.png").to_json()
    assert got == out.read_text()


def test_float32_with_nan_reads_as_a_float_tiff(tmp_path, cli):
    img = discs().astype(np.float32) * 3.0 - 100.0  # outside [0, 1]: scaled by its range
    img[10:14, 70:90] = np.nan
    img[100, 5] = np.inf
    tif = write_float_tiff(tmp_path / "f.tif", img)
    out = tmp_path / "cli.json"
    code, err = cli("segment", tif, "--wrap", "4", "--object", "dark", "--json", out)
    assert code == 0, err
    assert tc.segment(img, wrap=4, name="f.tif").to_json() == out.read_text()
    assert tc.segment(tif, wrap=4).to_json() == out.read_text()


def test_load_gives_what_the_engine_reads(tmp_path):
    img = discs()
    png = write_png(tmp_path / "d.png", img)
    a = tc.load(png)
    assert a.dtype == np.float32 and a.shape == img.shape
    assert np.array_equal(a, img.astype(np.float32) / 255.0)
    assert tc.segment(a, wrap=4).to_json() == tc.segment(img, wrap=4).to_json()


def test_exports_agree_with_the_cli_files(tmp_path, cli):
    img = discs()
    png = write_png(tmp_path / "d.png", img)
    files = {k: tmp_path / f"o.{k}" for k in ("geojson", "csv", "svg")}
    labels, mask = tmp_path / "labels.tif", tmp_path / "mask.png"
    code, err = cli("segment", png, "--wrap", "4", "--object", "dark", "--labels", labels, "--mask", mask,
                    *(x for k, p in files.items() for x in (f"--{k}", p)))
    assert code == 0, err
    r = tc.segment(png, wrap=4)
    assert r.to_geojson() == files["geojson"].read_text()
    assert r.to_csv() == files["csv"].read_text()
    assert r.to_svg() == files["svg"].read_text()
    lab = r.labels()
    assert lab.shape == img.shape and lab.max() >= 4
    # Read raw: tc.load reads as the engine does, and stretches a narrow range (labels 0-5).
    assert np.array_equal(lab, tifffile.imread(labels).astype(np.uint32))
    assert np.array_equal(r.mask(), tc.load(mask) == 1.0)
    assert np.array_equal(r.mask(), lab > 0)


def test_contours_and_events_are_the_json(tmp_path):
    r = tc.segment(discs(), wrap=4)
    doc = json.loads(r.to_json())
    assert len(r.contours) == len(doc["contours"]) and any(c["hole"] for c in r.contours)
    for got, want in zip(r.contours, doc["contours"]):
        assert (got["id"], got["hole"], got["parent"]) == (want["id"], want["hole"], want["parent"])
        assert got["area"] == want["area"]
        assert got["points"].shape == (len(want["points"]), 2)
        assert np.array_equal(got["points"], np.array(want["points"]))
    assert r.events == doc["events"] and {e["kind"] for e in r.events} >= {"split", "hole_made"}
    assert (r.frames, r.converged, r.shape) == (doc["frames"], doc["converged"], (120, 160))


BAD = [
    (dict(seeds=[(10, 10, -2)]), ["--seed", "10,10,-2"]),
    (dict(seeds=[(500, 10, 4)]), ["--seed", "500,10,4"]),
    (dict(seeds=[(10, float("nan"), 4)]), ["--seed", "10,nan,4"]),
    (dict(wrap=70), ["--wrap", "70"]),
    (dict(wrap=-1), ["--wrap=-1"]),
    (dict(rects=[(0, 0, 500, 20)]), ["--rect", "0,0,500,20"]),
    (dict(), []),
    (dict(wrap=4, max_frames=0), ["--wrap", "4", "--max-frames", "0"]),
    (dict(wrap=4, min_area=-3), ["--wrap", "4", "--min-area=-3"]),
    (dict(wrap=4, local_radius=0.5), ["--wrap", "4", "--local-radius", "0.5"]),
    (dict(wrap=4, mode="bogus"), ["--wrap", "4", "--mode", "bogus"]),
    (dict(wrap=4, modality="xray"), ["--wrap", "4", "--modality", "xray"]),
    (dict(wrap=4, object="grey"), ["--wrap", "4", "--object", "grey"]),
    (dict(wrap=4, pixel_size=0), ["--wrap", "4", "--pixel-size", "0"]),
]


@pytest.mark.parametrize("keywords,flags", BAD)
def test_bad_settings_raise_the_cli_message(tmp_path, cli, keywords, flags):
    png = write_png(tmp_path / "d.png", discs())
    if "--object" not in flags:
        flags = [*flags, "--object", "dark"]
    code, err = cli("segment", png, *flags, "--json", tmp_path / "o.json")
    assert code == 2
    with pytest.raises(ValueError) as e:
        tc.segment(png, **keywords)
    assert str(e.value) == cli_message(err)


def test_every_integer_and_float_dtype_reads_as_the_tiff_reader_does():
    img = discs()  # uint8
    run = lambda a: tc.segment(a, wrap=4, object="dark").to_json()
    # Signed 8 and 16 bit: their type's range, shifted exactly onto the unsigned one.
    assert run((img.astype(np.int16) - 128).astype(np.int8)) == run(img)
    wide = img.astype(np.uint16) * 257
    assert run((wide.astype(np.int32) - 32768).astype(np.int16)) == run(wide)
    # Wider integers and float64: as float32, by their own range.
    as_f32 = run(img.astype(np.float32))
    for dtype in (np.float64, np.int32, np.uint32, np.int64, np.uint64):
        assert run(img.astype(dtype)) == as_f32, dtype


def test_array_errors_are_one_line_value_errors():
    img = discs()
    cases = [
        (img > 100, "images of dtype bool are not supported: give integers, float32 or float64 (convert with .astype)"),
        (img.astype(np.complex64), "images of dtype complex64 are not supported: give integers, float32 or float64 (convert with .astype)"),
        (img.astype(np.float16), "images of dtype float16 are not supported: give integers, float32 or float64 (convert with .astype)"),
        (np.stack([img] * 3, axis=-1), "the image must be a 2-D array (height, width), got shape (120, 160, 3)"),
        (img[0], "the image must be a 2-D array (height, width), got shape (160,)"),
        (np.zeros((0, 5), np.uint8), "array has no pixels (5×0)"),
    ]
    for array, message in cases:
        with pytest.raises(ValueError) as e:
            tc.segment(array, wrap=1)
        assert str(e.value) == message
    with pytest.raises(ValueError, match="^page applies to a file"):
        tc.segment(img, wrap=4, page=2)
    with pytest.raises(TypeError, match="unexpected keyword argument 'json'"):
        tc.segment(img, wrap=4, json="x.json")
    with pytest.raises(TypeError, match="must be a NumPy array or a path"):
        tc.segment([[1, 2], [3, 4]], wrap=1)


def test_strided_arrays_read_as_their_copies():
    img = discs(240, 320)
    view = img[::2, ::2]
    assert not view.flags["C_CONTIGUOUS"]
    assert tc.segment(view, wrap=4).to_json() == tc.segment(np.ascontiguousarray(view), wrap=4).to_json()
    assert tc.segment(img.T.copy().T, wrap=4).to_json() == tc.segment(img, wrap=4).to_json()
