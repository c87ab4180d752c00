"""What the tests share: images they make (no data files), writers of PNG and
floating-point TIFF in plain Python, and the command line to compare with
(``TOPOCONTOUR_BIN``, else the checkout's release or debug build)."""

from __future__ import annotations

import os
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def cli_binary() -> Path:
    given = os.environ.get("TOPOCONTOUR_BIN")
    if given:
        path = Path(given)
        assert path.is_file(), f"TOPOCONTOUR_BIN={given} does not exist"
        return path
    for profile in ("release", "debug"):
        path = ROOT / "target" / profile / "topocontour"
        if path.is_file():
            return path
    pytest.skip("no topocontour binary: build it (cargo build) or set TOPOCONTOUR_BIN")


@pytest.fixture(scope="session")
def cli():
    """Runs ``topocontour ARGS…``; returns (exit code, stderr)."""
    binary = cli_binary()

    def run(*args: str) -> tuple[int, str]:
        p = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)
        return p.returncode, p.stderr

    return run


def cli_message(stderr: str) -> str:
    """The one line the command line printed, without its ``topocontour: `` prefix."""
    lines = [l for l in stderr.splitlines() if l.strip()]
    assert len(lines) == 1, stderr
    return lines[0].removeprefix("topocontour: ")


def discs(h: int = 120, w: int = 160, *, bright: bool = False, seed: int = 1) -> np.ndarray:
    """Dark (or bright) discs on a noisy background, two of them touching and one a ring
    with a hole: merges, splits and holes for the contours to get right. uint8."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:h, 0:w]
    inside = np.zeros((h, w), bool)
    for cx, cy, r in [(30, 30, 14), (57, 31, 14), (110, 40, 16), (45, 90, 12), (120, 92, 18)]:
        inside |= (xx - cx) ** 2 + (yy - cy) ** 2 <= r * r
    ring = (xx - 120) ** 2 + (yy - 92) ** 2 <= 7 * 7
    inside &= ~ring
    fg, bg = (200, 60) if bright else (50, 190)
    img = np.where(inside, fg, bg) + rng.normal(0, 8, (h, w))
    return np.clip(img, 0, 255).astype(np.uint8)


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def write_png(path: Path, img: np.ndarray) -> Path:
    """A grayscale PNG of a uint8 or uint16 array."""
    h, w = img.shape
    depth = 16 if img.dtype == np.uint16 else 8
    rows = img.astype(">u2" if depth == 16 else np.uint8).tobytes()
    stride = w * depth // 8
    raw = b"".join(b"\0" + rows[i * stride : (i + 1) * stride] for i in range(h))
    ihdr = struct.pack(">IIBBBBB", w, h, depth, 0, 0, 0, 0)
    path.write_bytes(
        b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", ihdr) + _chunk(b"IDAT", zlib.compress(raw)) + _chunk(b"IEND", b"")
    )
    return path


def write_float_tiff(path: Path, img: np.ndarray) -> Path:
    """An uncompressed single-strip float32 grayscale TIFF (little endian)."""
    h, w = img.shape
    data = img.astype("<f4").tobytes()
    tags = [  # (tag, type, count, value); type 3 SHORT, 4 LONG
        (256, 4, 1, w),
        (257, 4, 1, h),
        (258, 3, 1, 32),
        (259, 3, 1, 1),
        (262, 3, 1, 1),
        (273, 4, 1, 8),
        (277, 3, 1, 1),
        (278, 4, 1, h),
        (279, 4, 1, len(data)),
        (339, 3, 1, 3),
    ]
    ifd_at = 8 + len(data)
    out = b"II*\0" + struct.pack("<I", ifd_at) + data + struct.pack("<H", len(tags))
    for tag, kind, count, value in tags:
        packed = struct.pack("<HI", value, 0)[:4] if kind == 3 else struct.pack("<I", value)
        out += struct.pack("<HHI", tag, kind, count) + packed
    path.write_bytes(out + struct.pack("<I", 0))
    return path


def pytest_sessionfinish(session, exitstatus):
    """With TOPOCONTOUR_NO_SKIP=1 (CI, which installs every test extra) a skipped test
    fails the run: a missing dependency must not pass as a green suite."""
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    skipped = reporter.stats.get("skipped", []) if reporter else []
    if os.environ.get("TOPOCONTOUR_NO_SKIP") == "1" and skipped and session.exitstatus == 0:
        for r in skipped:
            reporter.write_line(f"skipped, which CI does not allow: {r.nodeid} {r.longrepr}")
        session.exitstatus = 1
