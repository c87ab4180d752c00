"""track() against `topocontour track` on a movie the test makes: the JSON and tracks CSV
byte for byte, the CTC lineage and masks, from a file and from an array; bad input raises
with the CLI's line."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import cli_message

import topocontour as tc

tifffile = pytest.importorskip("tifffile")


def movie(frames: int = 5, h: int = 90, w: int = 120, seed: int = 3) -> np.ndarray:
    """Dark discs drifting over a noisy background; one splits into two from frame 3."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w]
    out = []
    for t in range(frames):
        inside = np.zeros((h, w), bool)
        for cx, cy, r in [(25 + 2 * t, 30, 10), (70, 25 + t, 9), (40 - t, 65, 11)]:
            inside |= (xx - cx) ** 2 + (yy - cy) ** 2 <= r * r
        if t < 3:
            inside |= (xx - 95) ** 2 + (yy - 65) ** 2 <= 11**2
        else:
            for dx in (-10, 10):
                inside |= (xx - 95 - dx) ** 2 + (yy - 65) ** 2 <= 8**2
        img = np.where(inside, 60, 190) + rng.normal(0, 6, (h, w))
        out.append(np.clip(img, 0, 255).astype(np.uint8))
    return np.stack(out)


@pytest.mark.parametrize("flags,keywords", [
    ([], {}),
    (["--seed", "25,30,6", "--seed", "70,25,5", "--no-new-cells", "--levels", "3"],
     dict(seeds=[(25, 30, 6), (70, 25, 5)], no_new_cells=True, levels=3)),
])
def test_track_is_the_cli_track(tmp_path, cli, flags, keywords):
    m = movie()
    tif = tmp_path / "movie.tif"
    tifffile.imwrite(tif, m)
    js, csv, ctc = tmp_path / "t.json", tmp_path / "t.csv", tmp_path / "ctc"
    code, err = cli("track", tif, "--object", "dark", *flags, "--json", js, "--tracks-csv", csv,
                    "--ctc", ctc)
    assert code == 0, err
    from_file = tc.track(tif, **keywords)
    from_array = tc.track(m, name=str(tif), **keywords)
    for r in (from_file, from_array):
        assert r.to_json() == js.read_text()
        assert r.to_csv() == csv.read_text()
        assert r.to_ctc_tracks() == (ctc / "res_track.txt").read_text()
        labels = r.labels()
        assert labels.shape == m.shape and labels.dtype == np.uint32
        for t in range(len(m)):
            assert np.array_equal(labels[t], tifffile.imread(ctc / f"mask{t:03d}.tif"))
    assert len(from_file) == 5 and len(from_file.tracks) >= (2 if flags else 6)
    cells = from_file.frames[0]["objects"]
    assert cells and cells[0]["ring"].shape[1] == 2


def test_the_division_is_found():
    r = tc.track(movie())
    assert r.divisions, r.tracks
    frame, parent, children = r.divisions[0]
    assert frame == 3 and {t["parent"] for t in r.tracks if t["label"] in children} == {parent}
    assert all(r.tracks[c - 1]["first"] == 3 for c in children) and r.tracks[parent - 1]["last"] == 2


def test_bad_movies_and_flags_raise_the_cli_message(tmp_path, cli):
    m = movie()
    one = tmp_path / "one.tif"
    tifffile.imwrite(one, m[:1])
    code, err = cli("track", one, "--object", "dark", "--json", tmp_path / "o.json")
    assert code == 2
    with pytest.raises(ValueError) as e:
        tc.track(m[:1], name=str(one))
    assert str(e.value) == cli_message(err)
    with pytest.raises(ValueError) as e:
        tc.track(one)
    assert str(e.value) == cli_message(err)
    tif = tmp_path / "m.tif"
    tifffile.imwrite(tif, m)
    for flags, keywords in [
        (["--shrink=-1"], dict(shrink=-1)),
        (["--levels", "0"], dict(levels=0)),
        (["--seed", "500,10,4"], dict(seeds=[(500, 10, 4)])),
        (["--object", "grey"], dict(object="grey")),
    ]:
        if "--object" not in flags:
            flags = [*flags, "--object", "dark"]
        code, err = cli("track", tif, *flags, "--json", tmp_path / "o.json")
        assert code == 2, err
        with pytest.raises(ValueError) as e:
            tc.track(m, **keywords)
        assert str(e.value) == cli_message(err)
    # Frames of different sizes (a list of 2-D arrays): refused before tracking, as the CLI
    # refuses such a movie.
    with pytest.raises(ValueError, match=r"frame 1 is 100×80 but frame 0 is 120×90; every frame of a movie must have the same size$"):
        tc.track([m[0], m[1][:80, :100], m[2]])
    with pytest.raises(ValueError, match=r"^the movie must be a 3-D array \(frames, height, width\), got shape \(90, 120\)$"):
        tc.track(m[0])
    with pytest.raises(TypeError, match="unexpected keyword argument 'json'"):
        tc.track(m, json="x.json")
