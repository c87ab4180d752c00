"""topocontour: 2D polygonal active contours that change topology correctly.

The engine is the Rust crate's (the motion-region algorithm of seed 003); this package
runs it on NumPy arrays and image files. Every keyword of :func:`segment` is a flag of
``topocontour segment`` in snake case (``seeds`` for ``--seed``, ``rects`` for
``--rect``, ``strokes`` for ``--train``) and is parsed by the command line's own
definitions, so it means the same and a bad value gets the flag's message. The GIL is
released while the contours evolve.
"""

from __future__ import annotations

import os
from typing import Any, Iterable, Optional, Sequence, Union

import numpy as np

from . import _core
from ._core import Classifier, Tracks, load
from ._core import Segmentation as Result

__all__ = [
    "segment",
    "train",
    "track",
    "load",
    "Result",
    "Classifier",
    "Tracks",
    "segment_flags",
    "track_flags",
    "python_name",
]
__version__ = _core.__version__

# Python names that are not the flag's own (a list takes the plural).
_RENAMED = {"seed": "seeds", "rect": "rects", "train": "strokes"}
_LISTS = {"seed", "rect"}


def python_name(long: str) -> str:
    """The keyword of :func:`segment` for the flag ``--long``."""
    return _RENAMED.get(long, long.replace("-", "_"))


def segment_flags() -> list[tuple[str, str, str, str, str]]:
    """Every flag of ``topocontour segment``'s run settings, as (keyword, flag, value
    name, the values it takes, help); the README's table lists exactly these."""
    return [(python_name(long), long, *rest) for long, *rest in _core.segment_flags()]


def track_flags() -> list[tuple[str, str, str, str, str]]:
    """Every flag of ``topocontour track`` that is a keyword of :func:`track` (its
    output flags are not: the :class:`Tracks` result holds those outputs)."""
    return [(python_name(long), long, *rest) for long, *rest in _core.track_flags()]


_FLAGS = {python_name(long): (long, value) for long, value, _, _ in _core.segment_flags()}
_TRACK_FLAGS = {python_name(long): (long, value) for long, value, _, _ in _core.track_flags()}


def _number(x: Any) -> str:
    # repr of a float round-trips: the flag parses to the same double.
    if isinstance(x, bool):
        raise TypeError(f"expected a number, got {x!r}")
    if isinstance(x, int) or (hasattr(x, "dtype") and x.dtype.kind in "iu"):
        return str(int(x))
    return repr(float(x))


def _values(long: str, value: Any) -> list[str]:
    if long in _LISTS:
        return [",".join(_number(c) for c in item) for item in value]
    if isinstance(value, (bool, int, float)) or hasattr(value, "dtype"):
        return [_number(value)]
    return [os.fspath(value) if isinstance(value, os.PathLike) else str(value)]


def _argv(func: str, keywords: dict[str, Any], flags: Optional[dict] = None) -> list[str]:
    """The keywords as the command line's flags (``--wrap=6``): ``None`` and ``False``
    leave a flag out, ``True`` sets a switch."""
    flags = _FLAGS if flags is None else flags
    argv = []
    for key, value in keywords.items():
        if key not in flags:
            raise TypeError(f"{func}() got an unexpected keyword argument {key!r}")
        long, takes = flags[key]
        if value is None or value is False:
            continue
        if not takes:
            if value is not True:
                raise TypeError(f"{key} is a switch: give True or False, got {value!r}")
            argv.append(f"--{long}")
            continue
        argv.extend(f"--{long}={v}" for v in _values(long, value))
    return argv


def _is_path(x: Any) -> bool:
    return isinstance(x, (str, os.PathLike))


def _strokes_array(strokes: Any) -> np.ndarray:
    """A label array as the engine's uint8 strokes: an integer array whose values are
    0-3 (napari's Labels are int32 or int64); a value past 3 gets the engine's message."""
    a = np.asarray(strokes)
    if a.dtype.kind not in "iub" or a.ndim != 2:
        raise ValueError(
            f"strokes must be a 2-D integer label array (0 none, 1 background, 2 object, "
            f"3 boundary), got {a.dtype} of shape {a.shape}"
        )
    if a.dtype != np.uint8:
        off = np.flatnonzero((a < 0) | (a > 3))
        if off.size:
            y, x = divmod(int(off[0]), a.shape[1])
            raise ValueError(
                f"the strokes hold the value {a.flat[off[0]]} at ({x}, {y}); labels are "
                "0 none, 1 background, 2 object, 3 boundary"
            )
        a = a.astype(np.uint8)
    return np.ascontiguousarray(a)


def segment(
    image: Union["os.PathLike[str]", str, Any],
    *,
    seeds: Optional[Iterable[Sequence[float]]] = None,
    wrap: Optional[float] = None,
    rects: Optional[Iterable[Sequence[float]]] = None,
    auto_seeds: bool = False,
    object: str = "dark",
    modality: Optional[str] = None,
    mode: Optional[str] = None,
    classifier: Optional[Union[Classifier, "os.PathLike[str]", str]] = None,
    strokes: Optional[Union["os.PathLike[str]", str, Any]] = None,
    name: Optional[str] = None,
    **params: Any,
) -> Result:
    """Segments a 2-D image: a NumPy array (any integer or float dtype but float16, as a
    TIFF page with those samples reads) or the path of an image file.

    ``seeds`` are (x, y, r) disks, ``wrap`` a margin, ``rects`` (x0, y0, x1, y1)
    rectangles, ``auto_seeds`` one seed per object found; ``mode`` the engine (``None``:
    the command line's default, ``"track"`` for a taught run, else ``"adaptive"``);
    ``classifier`` a
    :class:`Classifier` (from :func:`train`) or a classifier file, ``strokes`` a label
    array of the image's shape or a strokes PNG (0 none, 1 background, 2 object, 3
    boundary) that a classifier is trained on for this run; ``params`` are the other
    flags of ``topocontour segment`` in snake case (``max_frames=200``,
    ``min_area=20``, …; see :func:`segment_flags`). ``name`` is the file name an array
    stands for (the JSON's ``image``; default ``"array"``). Bad input raises
    ``ValueError`` with the command line's message.
    """
    teach = None
    # An object in memory stands in a placeholder in its flag, so that clap refuses
    # strokes together with a classifier in its own words; the engine gets the object.
    if classifier is not None and not _is_path(classifier):
        if not isinstance(classifier, Classifier):
            raise TypeError(f"classifier must be a Classifier or a path, got {type(classifier).__name__}")
        teach, classifier = classifier, "<Classifier>"
    if strokes is not None and not _is_path(strokes):
        if teach is None:
            teach = _strokes_array(strokes)
        strokes = "<array>"
    keywords = dict(
        seeds=seeds,
        wrap=wrap,
        rects=rects,
        auto_seeds=auto_seeds,
        object=object,
        modality=modality,
        mode=mode,
        strokes=strokes,  # before classifier, as the flags are listed
        classifier=classifier,
        **params,
    )
    argv = _argv("segment", keywords)
    if _is_path(image):
        if name is not None:
            raise TypeError("name= is for arrays; a file is named by its path")
        return _core.segment_path(os.fspath(image), argv, teach)
    return _core.segment_array(image, argv, "array" if name is None else name, teach)


def train(
    image: Union["os.PathLike[str]", str, Any, Sequence[Any]],
    strokes: Union["os.PathLike[str]", str, Any, Sequence[Any]],
    *,
    name: Optional[Union[str, Sequence[str]]] = None,
) -> Classifier:
    """A pixel classifier taught by strokes, as ``topocontour train IMAGE STROKES …``
    trains it (``Classifier.save`` writes the same file). ``image`` is an array or a
    path, ``strokes`` a label array of its shape or a strokes PNG (0 none, 1
    background, 2 object, 3 boundary); give lists of both to train on several images.
    ``name`` names the arrays (the file's ``images``; default ``"array"``)."""
    several = isinstance(image, (list, tuple))
    images = list(image) if several else [image]
    strokes_list = list(strokes) if isinstance(strokes, (list, tuple)) else [strokes]
    if name is None:
        names = ["array"] * len(images)
    else:
        names = [name] * len(images) if isinstance(name, str) else list(name)
    if not (len(names) == len(images) == len(strokes_list)) or not images:
        raise ValueError(
            f"train takes pairs of an image and its strokes; got {len(images)} images, "
            f"{len(strokes_list)} strokes and {len(names)} names"
        )
    images = [os.fspath(i) if _is_path(i) else i for i in images]
    strokes_list = [os.fspath(s) if _is_path(s) else _strokes_array(s) for s in strokes_list]
    return _core.train(images, strokes_list, names)


def track(
    movie: Union["os.PathLike[str]", str, Any],
    *,
    object: str = "dark",
    seeds: Optional[Iterable[Sequence[float]]] = None,
    wrap: Optional[float] = None,
    rects: Optional[Iterable[Sequence[float]]] = None,
    auto_seeds: bool = False,
    name: Optional[str] = None,
    **params: Any,
) -> Tracks:
    """Tracks cells through a movie, as ``topocontour track`` does: ``movie`` is a
    multi-page TIFF or a folder of frames, or an array of frames (frames, height, width;
    any integer or float dtype but float16), each normalised by its own quantiles as the CLI reads a
    movie. Shapes (``seeds``, ``wrap``, ``rects``) are on frame 0 (automatic seeds
    without any); ``params`` are ``track``'s other flags in snake case (``shrink``,
    ``levels``, ``no_new_cells``, …; see :func:`track_flags`). The :class:`Tracks` holds
    the JSON, the tracks CSV, the CTC lineage and every frame's track labels."""
    keywords = dict(object=object, seeds=seeds, wrap=wrap, rects=rects, auto_seeds=auto_seeds, **params)
    argv = _argv("track", keywords, _TRACK_FLAGS)
    if _is_path(movie):
        if name is not None:
            raise TypeError("name= is for arrays; a movie file is named by its path")
        return _core.track(os.fspath(movie), argv, "")
    frames = movie
    if hasattr(movie, "ndim"):
        if movie.ndim != 3:
            shape = "(" + ", ".join(map(str, movie.shape)) + ("," if movie.ndim == 1 else "") + ")"
            raise ValueError(f"the movie must be a 3-D array (frames, height, width), got shape {shape}")
        frames = list(movie)
    return _core.track(frames, argv, "array" if name is None else name)
