#!/usr/bin/env python3
"""Makes assets/cells.png: a phase-contrast-like picture of cells (dark bodies, bright
halos, one cell with a bright vacuole, one pair about to divide) on an unevenly lit
background with noise. Standard library only; deterministic."""
import math, os, random, struct, zlib

W, H = 512, 384
rng = random.Random(20261124)

# (cx, cy, rx, ry, angle, vacuole radius)
cells = [
    (80, 70, 30, 20, 0.4, 0), (200, 60, 22, 16, -0.3, 0), (330, 80, 34, 24, 1.1, 9),
    (450, 70, 20, 20, 0.0, 0), (90, 200, 26, 18, 1.9, 0), (230, 190, 40, 28, 0.2, 0),
    (390, 210, 24, 18, -0.8, 0), (70, 320, 22, 15, 0.9, 0), (200, 310, 18, 18, 0.0, 0),
    (330, 320, 28, 17, 2.6, 0), (455, 310, 19, 26, 0.3, 0),
]
# A dividing pair: two lobes joined by a neck.
lobes = [(145, 125, 14, 11, 0.0), (172, 129, 14, 11, 0.0)]


def inside(x, y, cx, cy, rx, ry, a):
    dx, dy = x - cx, y - cy
    u = dx * math.cos(a) + dy * math.sin(a)
    v = -dx * math.sin(a) + dy * math.cos(a)
    return (u / rx) ** 2 + (v / ry) ** 2


img = [[0.0] * W for _ in range(H)]
for y in range(H):
    for x in range(W):
        bg = 140 + 18 * (x / W - 0.5) + 10 * math.sin(y / H * math.pi)
        val = bg
        for cx, cy, rx, ry, a, vac in cells:
            d = inside(x + 0.5, y + 0.5, cx, cy, rx, ry, a)
            if d <= 1.0:
                val = 95 + 6 * math.cos(x / 7.0) * math.sin(y / 9.0)
                if vac and (x + 0.5 - cx) ** 2 + (y + 0.5 - cy) ** 2 <= vac * vac:
                    val = 185
            elif d <= 1.35:
                val = max(val, 178 - 80 * (d - 1.0))
        for cx, cy, rx, ry, a in lobes:
            d = inside(x + 0.5, y + 0.5, cx, cy, rx, ry, a)
            if d <= 1.0:
                val = 92
            elif d <= 1.4 and val > 120:
                val = max(val, 175 - 70 * (d - 1.0))
        img[y][x] = val


def blur(a):
    # Two passes of a 3-tap box filter in x and y: a soft optical blur.
    for _ in range(2):
        a = [[(r[max(x - 1, 0)] + r[x] + r[min(x + 1, W - 1)]) / 3 for x in range(W)] for r in a]
        a = [[(a[max(y - 1, 0)][x] + a[y][x] + a[min(y + 1, H - 1)][x]) / 3 for x in range(W)] for y in range(H)]
    return a


img = blur(img)
rows = [bytes(max(0, min(255, int(round(v + rng.gauss(0, 7))))) for v in r) for r in img]


def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)


raw = b"".join(b"\x00" + r for r in rows)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 0, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cells.png")
open(out, "wb").write(png)
print(out)
