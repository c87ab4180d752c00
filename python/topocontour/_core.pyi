"""Type stubs of the extension module (the Rust engine)."""

import os
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, os.PathLike[str]]

class Classifier:
    """A trained pixel classifier (``topocontour.train``); ``segment(classifier=…)``
    applies it."""

    def save(self, path: _Path) -> None:
        """Writes the classifier file (``topocontour train --out``'s bytes), atomically."""
    @staticmethod
    def load(path: _Path) -> "Classifier":
        """Reads a classifier file; ValueError with the CLI's line if it does not fit."""
    @property
    def classes(self) -> list[str]:
        """"background", "object", "boundary": the classes it knows."""
    @property
    def images(self) -> list[str]:
        """The names of the images it was trained on."""
    def __eq__(self, other: object) -> bool: ...

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
    @property
    def classifier(self) -> Optional[Classifier]:
        """The classifier that taught the run (``--save-classifier``'s), or None."""
    def labels(self) -> npt.NDArray[np.uint32]:
        """Each object's number (as --labels, the CSV and GeoJSON), 0 outside."""
    def mask(self) -> npt.NDArray[np.bool_]:
        """True where a pixel's centre lies inside."""
    def to_json(self) -> str:
        """The CLI's --json document, byte for byte."""
    def to_geojson(self) -> str: ...
    def to_csv(self) -> str: ...
    def to_svg(self) -> str: ...

class Tracks:
    """A tracked movie (``topocontour.track``)."""

    @property
    def frames(self) -> list[dict[str, Any]]:
        """Per frame: frame, objects (track, area, centroid, ring (N, 2)), divisions."""
    @property
    def tracks(self) -> list[dict[str, int]]:
        """Every track: label, first, last, parent (0: none)."""
    @property
    def divisions(self) -> list[tuple[int, int, tuple[int, int]]]:
        """(frame, parent, (child, child)) for each division."""
    def labels(self) -> npt.NDArray[np.uint32]:
        """(frames, height, width) track labels: the values of the CLI's --ctc masks."""
    def to_json(self) -> str:
        """The CLI's track --json document, byte for byte."""
    def to_csv(self) -> str:
        """The CLI's --tracks-csv table."""
    def to_ctc_tracks(self) -> str:
        """The CTC res_track.txt."""
    def __len__(self) -> int: ...

def load(path: _Path, page: int = 0) -> npt.NDArray[np.float32]:
    """Page ``page`` (from 0) of an image file as the engine reads it, in [0, 1] (an
    image of a narrow range stretched to fill it)."""

def segment_array(
    image: npt.NDArray[Any], argv: list[str], name: str, teach: Optional[Union[Classifier, npt.NDArray[np.uint8]]] = None
) -> Segmentation: ...
def segment_path(
    path: _Path, argv: list[str], teach: Optional[Union[Classifier, npt.NDArray[np.uint8]]] = None
) -> Segmentation: ...
def segment_flags() -> list[tuple[str, str, str, str]]: ...
def track_flags() -> list[tuple[str, str, str, str]]: ...
def train(images: Sequence[Any], strokes: Sequence[Any], names: Sequence[str]) -> Classifier: ...
def track(movie: Any, argv: list[str], name: str) -> Tracks: ...
