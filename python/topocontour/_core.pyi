"""Type stubs of the extension module (the Rust engine)."""

import os
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

class Segmentation:
    """A finished run (``topocontour.Result``)."""

    @property
    def contours(self) -> list[dict[str, Any]]:
        """Every ring in the JSON's order: id, hole, parent, area, points ((N, 2) float64)."""
    @property
    def events(self) -> list[dict[str, Any]]:
        """The topology events: kind, frame, contours."""
    @property
    def frames(self) -> int: ...
    @property
    def converged(self) -> bool: ...
    @property
    def shape(self) -> tuple[int, int]:
        """(height, width) of the image."""
    def labels(self) -> npt.NDArray[np.uint32]:
        """Each object's number (as --labels, the CSV and GeoJSON), 0 outside."""
    def mask(self) -> npt.NDArray[np.bool_]:
        """True where a pixel's centre lies inside."""
    def to_json(self) -> str:
        """The CLI's --json document, byte for byte."""
    def to_geojson(self) -> str: ...
    def to_csv(self) -> str: ...
    def to_svg(self) -> str: ...

def load(path: Union[str, os.PathLike[str]], page: int = 0) -> npt.NDArray[np.float32]:
    """Page ``page`` (from 0) of an image file as the engine reads it, in [0, 1]."""

def segment_array(image: npt.NDArray[Any], argv: list[str], name: str) -> Segmentation: ...
def segment_path(path: Union[str, os.PathLike[str]], argv: list[str]) -> Segmentation: ...
def segment_flags() -> list[tuple[str, str, str, str]]: ...
