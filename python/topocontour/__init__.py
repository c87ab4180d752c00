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

from . import _core
from ._core import Segmentation as Result
from ._core import load

__all__ = ["segment", "load", "Result", "segment_flags", "python_name"]
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


_FLAGS = {python_name(long): (long, value) for long, value, _, _ in _core.segment_flags()}


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


def _argv(func: str, keywords: dict[str, Any]) -> list[str]:
    """The keywords as the command line's flags (``--wrap=6``): ``None`` and ``False``
    leave a flag out, ``True`` sets a switch."""
    argv = []
    for key, value in keywords.items():
        if key not in _FLAGS:
            raise TypeError(f"{func}() got an unexpected keyword argument {key!r}")
        long, takes = _FLAGS[key]
        if value is None or value is False:
            continue
        if not takes:
            if value is not True:
                raise TypeError(f"{key} is a switch: give True or False, got {value!r}")
            argv.append(f"--{long}")
            continue
        argv.extend(f"--{long}={v}" for v in _values(long, value))
    return argv


def segment(
    image: Union["os.PathLike[str]", str, Any],
    *,
    seeds: Optional[Iterable[Sequence[float]]] = None,
    wrap: Optional[float] = None,
    rects: Optional[Iterable[Sequence[float]]] = None,
    auto_seeds: bool = False,
    object: str = "dark",
    modality: Optional[str] = None,
    mode: str = "adaptive",
    strokes: Optional[Union["os.PathLike[str]", str]] = None,
    name: Optional[str] = None,
    **params: Any,
) -> Result:
    """Segments a 2-D image: a NumPy array (uint8, uint16 or float32, as a file with
    those samples reads) or the path of an image file.

    ``seeds`` are (x, y, r) disks, ``wrap`` a margin, ``rects`` (x0, y0, x1, y1)
    rectangles, ``auto_seeds`` one seed per object found; ``params`` are the other flags
    of ``topocontour segment`` in snake case (``max_frames=200``, ``min_area=20``, …;
    see :func:`segment_flags`). ``name`` is the file name an array stands for (the
    JSON's ``image``; default ``"array"``). Bad input raises ``ValueError`` with the
    command line's message.
    """
    keywords = dict(
        seeds=seeds,
        wrap=wrap,
        rects=rects,
        auto_seeds=auto_seeds,
        object=object,
        modality=modality,
        mode=mode,
        strokes=strokes,
        **params,
    )
    argv = _argv("segment", keywords)
    if isinstance(image, (str, os.PathLike)):
        if name is not None:
            raise TypeError("name= is for arrays; a file is named by its path")
        return _core.segment_path(os.fspath(image), argv)
    return _core.segment_array(image, argv, "array" if name is None else name)
