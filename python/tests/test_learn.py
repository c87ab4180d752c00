"""Teaching by example from Python against the command line: train() saves the file
`topocontour train` writes, byte for byte; segment() taught by a Classifier or by a
strokes array in memory gives the JSON of `segment --classifier` / `--train`; bad strokes
raise with the CLI's line."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import cli_message, discs, write_png

import topocontour as tc


def strokes_for(img: np.ndarray) -> np.ndarray:
    """A few strokes as a user paints them: object (2) inside two discs, background (1)
    in two strips of the background."""
    s = np.zeros(img.shape, np.uint8)
    s[27:34, 25:36] = 2  # disc at (30, 30)
    s[88:93, 40:50] = 2  # disc at (45, 90)
    s[5:8, 70:100] = 1
    s[110:114, 10:60] = 1
    return s


@pytest.fixture()
def taught(tmp_path, cli):
    img = discs()
    s = strokes_for(img)
    png = write_png(tmp_path / "img.png", img)
    spng = write_png(tmp_path / "strokes.png", s)
    clf = tmp_path / "cli.classifier"
    code, err = cli("train", png, spng, "--out", clf)
    assert code == 0, err
    return img, s, png, spng, clf


def test_train_saves_the_cli_file(tmp_path, taught):
    img, s, png, spng, clf = taught
    from_arrays = tc.train(img, s, name="img.png")
    from_files = tc.train(png, spng)
    assert from_arrays.classes == ["background", "object"] and from_arrays.images == ["img.png"]
    for i, c in enumerate([from_arrays, from_files]):
        out = tmp_path / f"py{i}.classifier"
        c.save(out)
        assert out.read_bytes() == clf.read_bytes()
    assert tc.Classifier.load(clf) == from_arrays


def test_train_on_two_images_is_the_cli_pairs(tmp_path, cli, taught):
    img, s, png, spng, _ = taught
    img2 = discs(seed=5, bright=False)
    png2 = write_png(tmp_path / "two.png", img2)
    out = tmp_path / "two.classifier"
    code, err = cli("train", png, spng, png2, spng, "--out", out)
    assert code == 0, err
    c = tc.train([img, img2], [s, s.astype(np.int64)], name=["img.png", "two.png"])
    c.save(tmp_path / "py.classifier")
    assert (tmp_path / "py.classifier").read_bytes() == out.read_bytes()


def test_segment_taught_in_memory_is_the_cli_run(tmp_path, cli, taught):
    img, s, png, spng, clf = taught
    for flags, keywords in [
        (["--classifier", clf], dict(classifier=tc.Classifier.load(clf))),
        (["--classifier", clf], dict(classifier=clf)),
        (["--train", spng], dict(strokes=s)),
        (["--train", spng], dict(strokes=s.astype(np.int32))),
        (["--train", spng], dict(strokes=spng)),
    ]:
        out, saved = tmp_path / "cli.json", tmp_path / "cli-saved.classifier"
        code, err = cli("segment", png, *flags, "--auto-seeds", "--object", "dark", "--json", out,
                        "--save-classifier", saved)
        assert code == 0, err
        r = tc.segment(img, name="img.png", auto_seeds=True, **keywords)
        assert r.to_json() == out.read_text()
        assert len(r.contours) >= 4
        r.classifier.save(tmp_path / "py-saved.classifier")
        assert (tmp_path / "py-saved.classifier").read_bytes() == saved.read_bytes()
    assert tc.segment(img, wrap=4).classifier is None


def test_bad_strokes_raise_the_cli_message(tmp_path, cli, taught):
    img, s, png, spng, clf = taught
    small = s[:60, :80]
    seven = s.copy()
    seven[50, 61] = 7
    only_object = np.where(s == 2, 2, 0).astype(np.uint8)
    for strokes in (small, seven, only_object):
        f = write_png(tmp_path / "bad.png", strokes)
        code, err = cli("segment", png, "--train", f, "--wrap", "4", "--object", "dark", "--json",
                        tmp_path / "o.json")
        assert code == 2
        with pytest.raises(ValueError) as e:
            tc.segment(img, strokes=strokes, wrap=4)
        assert str(e.value) == cli_message(err)
    with pytest.raises(ValueError) as e:
        tc.segment(img, strokes=seven.astype(np.int64), wrap=4)
    assert str(e.value).startswith("the strokes hold the value 7 at (61, 50)")
    # Strokes and a classifier together: clap's line, whether given as files or objects.
    code, err = cli("segment", png, "--train", spng, "--classifier", clf, "--wrap", "4", "--object",
                    "dark", "--json", tmp_path / "o.json")
    assert code == 2
    for keywords in (dict(strokes=s, classifier=tc.Classifier.load(clf)), dict(strokes=spng, classifier=clf),
                     dict(strokes=s, classifier=clf)):
        with pytest.raises(ValueError) as e:
            tc.segment(img, wrap=4, **keywords)
        assert str(e.value) == cli_message(err)
    # Training on one class only: `train`'s line.
    code, err = cli("train", png, write_png(tmp_path / "one.png", only_object), "--out", tmp_path / "x")
    assert code == 2
    with pytest.raises(ValueError) as e:
        tc.train(png, tmp_path / "one.png")
    assert str(e.value) == cli_message(err)


def test_a_damaged_classifier_file_is_refused_as_the_cli_refuses_it(tmp_path, cli, taught):
    img, s, png, spng, clf = taught
    broken = tmp_path / "broken.classifier"
    broken.write_text(clf.read_text().replace('"feature_version":', '"feature_version":9', 1))
    code, err = cli("segment", png, "--classifier", broken, "--wrap", "4", "--object", "dark", "--json",
                    tmp_path / "o.json")
    assert code == 2
    with pytest.raises(ValueError) as e:
        tc.Classifier.load(broken)
    assert str(e.value) == cli_message(err)
