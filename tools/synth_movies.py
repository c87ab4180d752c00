#!/usr/bin/env python3
"""Small synthetic time-lapse cases with Cell Tracking Challenge truth, to check that the
tracking defaults are not fitted to one public movie.

usage: python3 synth_movies.py OUT [--seed N]

Writes two case folders under OUT, each with case.json, movie.tif (16-bit) and GT/TRA
(man_track.txt, man_trackTTT.tif) + GT/SEG (man_segTTT.tif), the layout score_tracks.py
reads:
  nuclei_fluo    bright nuclei (radius 9-13 px) that drift, condense before mitosis (smaller,
                 brighter, elongated) and split into two daughters that move apart; cells
                 enter and leave at the border.
  rods_phase     phase-contrast bacteria: dark rods with a bright halo that grow in length,
                 constrict in the middle and divide end to end into two touching daughters.
Needs numpy, scipy and tifffile (shared/tools/requirements-tracks.txt).
"""
from __future__ import annotations

import argparse
import json
import math
import os

import numpy as np
import tifffile
from scipy import ndimage as ndi


class Cell:
    def __init__(self, label, parent, born, x, y, angle, length, radius):
        self.label, self.parent, self.born = label, parent, born
        self.x, self.y, self.angle = x, y, angle
        self.length, self.radius = length, radius
        self.vx = self.vy = 0.0
        self.phase = 0  # frames into the pinch before division (0: none)


def capsule_mask(shape, c, neck=0.0):
    """Pixels within c.radius of the segment of length c.length through (x, y) at c.angle;
    neck in [0, 1) narrows the middle (a constriction)."""
    h, w = shape
    half = c.length / 2 + c.radius + 2
    x0, x1 = max(0, int(c.x - half)), min(w, int(c.x + half) + 1)
    y0, y1 = max(0, int(c.y - half)), min(h, int(c.y + half) + 1)
    m = np.zeros(shape, bool)
    if x0 >= x1 or y0 >= y1:
        return m
    yy, xx = np.mgrid[y0:y1, x0:x1]
    px, py = xx + 0.5 - c.x, yy + 0.5 - c.y
    ux, uy = math.cos(c.angle), math.sin(c.angle)
    s = np.clip(px * ux + py * uy, -c.length / 2, c.length / 2)
    d = np.hypot(px - s * ux, py - s * uy)
    s_raw = px * ux + py * uy
    r = c.radius * (1 - neck * np.exp(-((s_raw / (0.6 * c.radius)) ** 2)))
    m[y0:y1, x0:x1] = d <= r
    return m


def simulate(kind, rng, size, frames, n0):
    h = w = size
    cells, tracks, nxt = [], {}, 1

    def new(parent, born, x, y, angle, length, radius):
        nonlocal nxt
        c = Cell(nxt, parent, born, x, y, angle, length, radius)
        tracks[nxt] = [born, born, parent]
        nxt += 1
        return c

    margin = 20
    for _ in range(n0 * 20):
        if len(cells) >= n0:
            break
        x, y = rng.uniform(margin, w - margin, 2)
        if all(math.hypot(x - c.x, y - c.y) > 34 for c in cells):
            if kind == "nuclei":
                cells.append(new(0, 0, x, y, rng.uniform(0, math.pi), rng.uniform(0, 6), rng.uniform(9, 13)))
            else:
                cells.append(new(0, 0, x, y, rng.uniform(0, math.pi), rng.uniform(10, 22), rng.uniform(4, 5.5)))
    labels_t, neck_t = [], []
    for t in range(frames):
        if t > 0:
            born = []
            for c in list(cells):
                if kind == "nuclei":
                    ready = c.phase == 0 and t - c.born > 12 and rng.random() < 0.1
                else:
                    ready = c.phase == 0 and c.length > 30 and rng.random() < 0.35
                if ready:
                    c.phase = 1
                elif c.phase:
                    c.phase += 1
                if c.phase == 4:  # divides: two daughters along the axis
                    cells.remove(c)
                    ux, uy = math.cos(c.angle), math.sin(c.angle)
                    if kind == "nuclei":
                        off, ln, rad = c.radius * 1.1, 2.0, c.radius * 0.72
                    else:
                        off, ln, rad = c.length / 4 + c.radius / 2 + 0.5, c.length / 2 - c.radius, c.radius
                    for sgn in (-1, 1):
                        d = new(c.label, t, c.x + sgn * off * ux, c.y + sgn * off * uy,
                                c.angle + rng.normal(0, 0.05), max(ln, 1.0), rad)
                        d.vx, d.vy = sgn * 0.8 * ux, sgn * 0.8 * uy
                        born.append(d)
                    continue
                if kind == "nuclei":
                    if c.phase:  # condensing: smaller, elongated
                        c.radius *= 0.93
                        c.length += 3.0
                    else:
                        c.radius = min(c.radius + 0.25, 12.0)
                        c.length = max(c.length - 0.3, 0.0)
                    c.vx = 0.7 * c.vx + rng.normal(0, 0.6)
                    c.vy = 0.7 * c.vy + rng.normal(0, 0.6)
                else:
                    c.length += 1.3
                    c.vx = 0.5 * c.vx + rng.normal(0, 0.25)
                    c.vy = 0.5 * c.vy + rng.normal(0, 0.25)
                    c.angle += rng.normal(0, 0.01)
            cells += born
            # push apart what would overlap (centres closer than their sizes)
            for a in cells:
                for b in cells:
                    if a is b:
                        continue
                    dx, dy = a.x - b.x, a.y - b.y
                    dist = math.hypot(dx, dy) + 1e-6
                    reach = (a.radius + b.radius) + 0.25 * (a.length + b.length) + 2
                    if dist < reach and kind == "nuclei":
                        a.vx += 0.3 * dx / dist
                        a.vy += 0.3 * dy / dist
            for c in cells:
                c.x += c.vx
                c.y += c.vy
            if kind == "nuclei" and t in (frames // 3, 2 * frames // 3):
                # one cell enters at the left border, drifting in
                e = new(0, t, -8.0, rng.uniform(40, h - 40), 0.0, 0.0, 11.0)
                e.vx = 2.5
                cells.append(e)
                tracks[e.label][0] = t
        lab = np.zeros((h, w), np.uint16)
        neck = np.zeros((h, w), np.float32)
        keep = []
        for c in cells:
            m = capsule_mask((h, w), c, neck=(0.25 * c.phase if kind == "rods" else 0.0))
            m &= lab == 0
            if m.sum() < 20:
                if m.sum() == 0 and t > tracks[c.label][0]:
                    continue  # left the field
                if m.sum() == 0:
                    keep.append(c)
                    continue
            lab[m] = c.label
            neck[m] = 1.0 + (0.25 * c.phase if kind == "nuclei" else 0.0)
            keep.append(c)
        cells = keep
        labels_t.append(lab)
        neck_t.append(neck)
    # tracks from the label images themselves (first/last frame a label shows)
    present = {}
    for t, lab in enumerate(labels_t):
        for L in np.unique(lab):
            if L:
                present.setdefault(int(L), []).append(t)
    out_tracks = {}
    for L, ts in present.items():
        b, e, p = ts[0], ts[-1], tracks[L][2]
        if p and p not in present:
            p = 0
        out_tracks[L] = [b, e, p]
    return labels_t, neck_t, out_tracks


def render(kind, labels_t, bright_t, rng):
    frames = []
    for lab, bright in zip(labels_t, bright_t):
        fg = lab > 0
        if kind == "nuclei":
            img = 0.12 + 0.55 * bright * (0.85 + 0.15 * ndi.gaussian_filter(rng.random(fg.shape), 2) * 2)
            img = np.where(fg, img, 0.12)
            img = ndi.gaussian_filter(img, 1.5)
            img = rng.poisson(img * 300) / 300.0 + rng.normal(0, 0.02, img.shape)
            scale, base = 400, 300
        else:
            dist_out = ndi.distance_transform_edt(~fg)
            halo = np.where(fg, 0, 0.35 * np.exp(-dist_out / 2.0))
            # the boundary between touching cells is bright too (as in phase contrast)
            edge = np.zeros(fg.shape, bool)
            for dy, dx in ((0, 1), (1, 0)):
                a, b = lab, np.roll(lab, (dy, dx), (0, 1))
                edge |= (a != b) & (a > 0) & (b > 0)
            img = np.where(fg, 0.22, 0.5) + halo + 0.25 * edge
            img = ndi.gaussian_filter(img, 1.0) + rng.normal(0, 0.03, img.shape)
            scale, base = 600, 200
        frames.append(np.clip(base + scale * img, 0, 65535).astype(np.uint16))
    return frames


def write_case(root, name, kind, obj, modality, labels_t, tracks, frames):
    d = os.path.join(root, name)
    for sub in ("GT/TRA", "GT/SEG"):
        os.makedirs(os.path.join(d, sub), exist_ok=True)
    tifffile.imwrite(os.path.join(d, "movie.tif"), np.stack(frames))
    for t, lab in enumerate(labels_t):
        tifffile.imwrite(os.path.join(d, "GT/TRA", f"man_track{t:03d}.tif"), lab)
        tifffile.imwrite(os.path.join(d, "GT/SEG", f"man_seg{t:03d}.tif"), lab)
    with open(os.path.join(d, "GT/TRA/man_track.txt"), "w") as f:
        for L in sorted(tracks):
            b, e, p = tracks[L]
            f.write(f"{L} {b} {e} {p}\n")
    divisions = len({p for _, _, p in tracks.values() if p})
    with open(os.path.join(d, "case.json"), "w") as f:
        json.dump({"name": name, "object": obj, "modality": modality, "frames": len(frames),
                   "movie": "movie.tif", "gt": "GT", "tracks": len(tracks),
                   "divisions": divisions, "generator": "synth_movies.py"}, f, indent=1)
    print(f"{name}: {len(frames)} frames, {len(tracks)} tracks, {divisions} divisions")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    lab, bright, tr = simulate("nuclei", rng, 256, 40, 14)
    write_case(a.out, "nuclei_fluo", "nuclei", "bright", "fluorescence", lab, tr, render("nuclei", lab, bright, rng))
    lab, neck, tr = simulate("rods", rng, 256, 30, 10)
    write_case(a.out, "rods_phase", "rods", "dark", "phase-contrast", lab, tr, render("rods", lab, neck, rng))


if __name__ == "__main__":
    main()
