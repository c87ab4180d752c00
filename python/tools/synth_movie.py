#!/usr/bin/env python3
"""Synthetic time-lapse movies with exact tracking truth, in the case layout that
score_tracks.py reads (case.json, movie.tif, GT/TRA/man_track.txt + man_trackTTT.tif,
GT/SEG/man_segTTT.tif).

Families:
  bacteria_phase  rod-shaped cells (capsules) growing exponentially on an agar pad and
                  dividing at the middle into two touching daughters that push each other
                  (a microcolony); phase contrast look: dark cells, bright halo, uneven
                  illumination, blur, shot + read noise, 16-bit in a narrow range.  Sisters
                  touch with at most a faint bright line that forms over a few frames.
  nuclei_fluo     nuclei of varied size and brightness moving on a dark background; some
                  divide (condense and elongate, then two daughters a thin gap apart (--gap) that
                  separate over a few frames); some enter or leave at the border.

Truth is exact: every pixel is labelled by the rendered shape that covers it (the nearest
one where two overlap), the same shapes that make the image; tracks are the runs of frames
in which a cell has pixels, parents the mother's track when it ends the frame before.

usage: synth_movie.py FAMILY OUT_DIR [--seed N] [--frames T] [--size PX]
       [--photons P] [--blur S] [--line L] [--widths MIN MAX] [--doubling MIN MAX] [--waist W]
       (bacteria_phase renderings: noisier, blurrier, no line between cells, thinner
       rods, a cell cycle of more or fewer frames, another depth of waist)
       [--drift S]   (either family: a drifting stage, the whole field's random walk of S px a frame)
"""
from __future__ import annotations

import argparse
import json
import os

import numpy as np
import tifffile
from scipy import ndimage as ndi


# bacteria_phase rendering (--photons, --blur, --line, --widths): how hard a movie is.
PHOTONS = 110.0
BLUR = 1.1
LINE = 0.32
WIDTHS = (8.0, 10.0)
# bacteria_phase: a cell cycle lasts between these many frames (--doubling).
DOUBLING = (11.0, 14.0)
# bacteria_phase: how deep the mother's waist gets before she divides (--waist), a share
# of her radius: 0 is a rod that parts with no constriction.
WAIST = 0.45
# Both families: a drifting stage (--drift), px a frame of the whole field's random walk.
DRIFT = 0.0

# ------------------------------------------------------------------------ shapes
def capsule_sd(xx, yy, c, ang, length, width, pinch):
    """Signed distance (px, < 0 inside) of a capsule of total `length` and `width`,
    its waist narrowed by `pinch` (0..1) at the middle (a constricting rod)."""
    dx, dy = xx - c[0], yy - c[1]
    ca, sa = np.cos(ang), np.sin(ang)
    u = dx * ca + dy * sa
    v = -dx * sa + dy * ca
    r = width / 2.0
    a = max(length / 2.0 - r, 0.0)
    uc = np.clip(u, -a, a)
    d = np.hypot(u - uc, v)
    rr = r * (1.0 - pinch * np.exp(-(u / (0.45 * width)) ** 2))
    return d - rr


def blob_sd(xx, yy, c, ang, ax, bx, harm):
    """Approximate signed distance (px) of an ellipse with semi-axes ax, bx at angle ang,
    its radius modulated by Fourier harmonics harm = [(k, amp, phase), ...]."""
    dx, dy = xx - c[0], yy - c[1]
    ca, sa = np.cos(ang), np.sin(ang)
    u = dx * ca + dy * sa
    v = -dx * sa + dy * ca
    phi = np.arctan2(v, u)
    rho = np.hypot(u, v)
    rad = ax * bx / np.sqrt((bx * np.cos(phi)) ** 2 + (ax * np.sin(phi)) ** 2)
    mod = np.ones_like(phi)
    for k, amp, ph in harm:
        mod += amp * np.cos(k * phi + ph)
    return rho - rad * mod


def rasterise(h, w, cells, sd_fn, reach):
    """Labels (nearest covering shape) and coverage (anti-aliased union) of `cells`:
    sd_fn(xx, yy, cell) gives each cell's signed distance in its box of half-size reach(cell)."""
    best = np.full((h, w), np.inf)
    lab = np.zeros((h, w), np.int32)
    cov = np.zeros((h, w))
    for cell in cells:
        cx, cy = cell["pos"]
        r = reach(cell)
        x0, x1 = int(max(0, np.floor(cx - r))), int(min(w, np.ceil(cx + r) + 1))
        y0, y1 = int(max(0, np.floor(cy - r))), int(min(h, np.ceil(cy + r) + 1))
        if x0 >= x1 or y0 >= y1:
            continue
        yy, xx = np.mgrid[y0:y1, x0:x1].astype(float)
        sd = sd_fn(xx, yy, cell)
        sub_b = best[y0:y1, x0:x1]
        inside = (sd < 0) & (sd < sub_b)
        sub_b[inside] = sd[inside]
        lab[y0:y1, x0:x1][inside] = cell["id"]
        cov[y0:y1, x0:x1] = np.maximum(cov[y0:y1, x0:x1], np.clip(0.5 - sd, 0, 1))
    return lab, cov


def smooth_noise(rng, h, w, sigma):
    n = ndi.gaussian_filter(rng.standard_normal((h, w)), sigma)
    return n / (n.std() + 1e-12)


def illumination(rng, h, w, amp):
    yy, xx = np.mgrid[0:h, 0:w] / max(h, w)
    gx, gy = rng.uniform(-1, 1, 2)
    return 1.0 + amp * (gx * (xx - 0.5) + gy * (yy - 0.5)) + 0.5 * amp * smooth_noise(rng, h, w, max(h, w) / 6)


def to_counts(rng, img, photons, read, offset):
    """Shot noise at `photons` per unit, Gaussian read noise, an offset: 16-bit counts."""
    counts = rng.poisson(np.clip(img, 0, None) * photons).astype(float)
    counts += rng.normal(0, read, img.shape) + offset
    return np.clip(np.round(counts), 0, 65535).astype(np.uint16)


# ---------------------------------------------------------------------- bacteria
def seg_closest(p1, q1, p2, q2):
    """Closest points between segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection 5.1.9)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = d1 @ d1, d2 @ d2, d2 @ r
    if a <= 1e-9 and e <= 1e-9:
        return p1, p2
    if a <= 1e-9:
        s, t = 0.0, np.clip(f / e, 0, 1)
    else:
        c = d1 @ r
        if e <= 1e-9:
            t, s = 0.0, np.clip(-c / a, 0, 1)
        else:
            b = d1 @ d2
            den = a * e - b * b
            s = np.clip((b * f - c * e) / den, 0, 1) if den > 1e-9 else 0.0
            t = (b * s + f) / e
            if t < 0:
                t, s = 0.0, np.clip(-c / a, 0, 1)
            elif t > 1:
                t, s = 1.0, np.clip((b - c) / a, 0, 1)
    return p1 + d1 * s, p2 + d2 * t


def rod_ends(c):
    a = max(c["len"] / 2 - c["wid"] / 2, 0.0)
    d = np.array([np.cos(c["ang"]), np.sin(c["ang"])]) * a
    return c["pos"] - d, c["pos"] + d


def relax(cells, rng, iters=12):
    """Pushes overlapping rods apart (translation and a turn about the centre)."""
    for _ in range(iters):
        moved = False
        ends = [rod_ends(c) for c in cells]
        for i in range(len(cells)):
            for j in range(i + 1, len(cells)):
                ci, cj = cells[i], cells[j]
                if np.abs(ci["pos"] - cj["pos"]).max() > (ci["len"] + cj["len"]) / 2 + 2:
                    continue
                pi, pj = seg_closest(*ends[i], *ends[j])
                dvec = pi - pj
                dist = np.hypot(*dvec)
                ov = (ci["wid"] + cj["wid"]) / 2 - dist
                if ov <= 0.05:
                    continue
                n = dvec / dist if dist > 1e-6 else np.array([np.cos(ci["ang"] + 1.57), np.sin(ci["ang"] + 1.57)])
                push = 0.5 * ov * 0.6
                for c, p, sgn in ((ci, pi, 1.0), (cj, pj, -1.0)):
                    c["pos"] = c["pos"] + sgn * push * n
                    arm = p - c["pos"]
                    torque = arm[0] * (sgn * n[1]) - arm[1] * (sgn * n[0])
                    c["ang"] += 0.6 * torque * push / max(c["len"] ** 2 / 12, 1.0)
                moved = True
        if not moved:
            break
    for c in cells:
        c["ang"] += rng.normal(0, 0.004)


def bacteria_phase(seed, frames, size):
    rng = np.random.default_rng(seed)
    h = w = size
    cells, nid = [], 1
    births = {}
    for k in range(3):
        lb = rng.uniform(17, 21)
        cells.append(dict(id=nid, pos=np.array([w / 2, h / 2]) + rng.uniform(-30, 30, 2),
                          ang=rng.uniform(0, np.pi), wid=rng.uniform(*WIDTHS), len=lb * rng.uniform(1.0, 1.9),
                          ldiv=2 * lb * rng.uniform(0.94, 1.06), rate=np.log(2) / rng.uniform(*DOUBLING),
                          parent=0, born=0))
        nid += 1
    relax(cells, rng, 50)
    sub = 4
    labs, covs, sisters = [], [], []
    events = []  # (frame, mother, d1, d2)
    bright_of = []
    for t in range(frames):
        if t > 0:
            for _ in range(sub):
                new = []
                for c in cells:
                    c["len"] *= np.exp(c["rate"] / sub)
                    if c["len"] >= c["ldiv"]:
                        d = np.array([np.cos(c["ang"]), np.sin(c["ang"])])
                        kids = []
                        for sgn in (-1, 1):
                            lb = c["len"] / 2
                            kids.append(dict(id=nid, pos=c["pos"] + sgn * d * c["len"] / 4, ang=c["ang"] + rng.normal(0, 0.03),
                                             wid=float(np.clip(c["wid"] + rng.normal(0, 0.2), *WIDTHS)), len=lb,
                                             ldiv=2 * lb * rng.uniform(0.94, 1.06), rate=np.log(2) / rng.uniform(*DOUBLING),
                                             parent=c["id"], born=t))
                            nid += 1
                        events.append((t, c["id"], kids[0]["id"], kids[1]["id"]))
                        new += kids
                    else:
                        new.append(c)
                cells = new
                relax(cells, rng)
            for c in cells:
                c["pos"] = c["pos"] + rng.normal(0, 0.08, 2)

        def sd(xx, yy, c):
            # The waist narrows over the last part of the cycle (the septum forming).
            prog = np.clip((c["len"] / c["ldiv"] - 0.85) / 0.15, 0, 1)
            return capsule_sd(xx, yy, c["pos"], c["ang"], c["len"], c["wid"], WAIST * prog)

        lab, cov = rasterise(h, w, cells, sd, lambda c: c["len"] / 2 + 3)
        labs.append(lab)
        covs.append(cov)
        by = {c["id"]: c for c in cells}
        bright_of.append(by)
    # Render.
    movie = []
    illum = illumination(rng, h, w, 0.12)
    bg_tex = 1.0 + 0.03 * smooth_noise(rng, h, w, 6)
    for t in range(frames):
        lab, cov, by = labs[t], covs[t], bright_of[t]
        dark = np.zeros((h, w))
        for cid, c in by.items():
            c.setdefault("dark", rng.uniform(0.55, 0.7))
        ids = np.unique(lab[lab > 0])
        dmap = np.zeros(lab.max() + 1)
        for cid in ids:
            dmap[cid] = by[cid]["dark"]
        dark = dmap[lab]
        # Anti-aliased edge: darkness of the nearest cell spread over the coverage.
        dark = ndi.grey_dilation(dark, size=3) * np.where(lab > 0, 1.0, cov)
        dark = np.where(lab > 0, dmap[lab], dark)
        # Bright lines where two cells meet: faint for sisters just born, forming over 8 frames.
        line = np.zeros((h, w))
        for ax in (0, 1):
            a = lab
            b = np.roll(lab, 1, axis=ax)
            m = (a > 0) & (b > 0) & (a != b)
            if not m.any():
                continue
            ys, xs = np.nonzero(m)
            for y, x in zip(ys, xs):
                ca, cb = by[a[y, x]], by[b[y, x]]
                if ca["parent"] and ca["parent"] == cb["parent"]:
                    s = LINE * np.clip((t - ca["born"]) / 8.0, 0, 1) ** 1.5
                else:
                    s = LINE
                line[y, x] = max(line[y, x], s)
        union = np.clip(cov, 0, 1)
        halo = 0.9 * ndi.gaussian_filter(union, 4.0) * (1 - union) + 0.25 * ndi.gaussian_filter(union, 12.0)
        tex = 1.0 + 0.04 * smooth_noise(rng, h, w, 1.5)
        img = bg_tex * (1.0 - dark * tex) + halo + line
        img = ndi.gaussian_filter(img * illum, BLUR)
        movie.append(to_counts(rng, img, photons=PHOTONS, read=2.0, offset=95))
    return movie, labs, events, dict(object="dark", modality="phase-contrast")


# ------------------------------------------------------------------------ nuclei
GAP = 1.5  # px between the daughters' outlines in their first frame (--gap)
def nuclei_fluo(seed, frames, size):
    rng = np.random.default_rng(seed)
    h = w = size
    nid = [1]

    def nucleus(pos, r=None, parent=0, born=0, vel=None):
        r = r if r is not None else rng.uniform(13, 22)
        c = dict(id=nid[0], pos=np.array(pos, float), r=r, r0=r, asp=rng.uniform(1.0, 1.5), ang=rng.uniform(0, np.pi),
                 harm=[(k, rng.uniform(0, 0.06), rng.uniform(0, 6.3)) for k in (2, 3, 4)],
                 bright=rng.uniform(0.25, 1.0), vel=vel if vel is not None else rng.normal(0, 1.0, 2),
                 parent=parent, born=born, tdiv=None, phase=0.0, split=None,
                 tex=[(rng.uniform(0.15, 0.45), rng.uniform(0, 6.3), rng.uniform(0, 6.3)) for _ in range(3)])
        nid[0] += 1
        if rng.random() < 0.45:
            c["tdiv"] = born + int(rng.integers(6, max(frames - 4, 7)))
        return c

    cells = []
    n0 = int(size * size / 6500)
    tries = 0
    while len(cells) < n0 and tries < 5000:
        tries += 1
        p = rng.uniform(10, size - 10, 2)
        if all(np.hypot(*(p - c["pos"])) > 50 for c in cells):
            cells.append(nucleus(p))
    labs, shapes, events = [], [], []
    pre, sep = 4, 4  # frames condensing before division, frames the daughters take to part
    for t in range(frames):
        if t > 0:
            new = []
            for c in cells:
                if c["tdiv"] is not None and t == c["tdiv"]:
                    d = np.array([np.cos(c["ang"]), np.sin(c["ang"])])
                    rd = c["r0"] * 0.55
                    # Anaphase: the two chromatin masses already apart by a thin gap
                    # (blurred, a dip rather than background) along the mother's axis.
                    off = rd * np.sqrt(1.15) + GAP / 2
                    kids = []
                    for sgn in (-1, 1):
                        k = nucleus(c["pos"] + sgn * d * off, r=rd, parent=c["id"], born=t, vel=c["vel"].copy())
                        k.update(ang=c["ang"], asp=1.15, bright=min(1.0, c["bright"] * 1.6), r0=c["r0"] * rng.uniform(0.7, 0.8),
                                 tdiv=None, split=(sgn, d))
                        kids.append(k)
                    events.append((t, c["id"], kids[0]["id"], kids[1]["id"]))
                    new += kids
                    continue
                new.append(c)
            cells = new
            for c in cells:
                c["vel"] = 0.8 * c["vel"] + rng.normal(0, 0.6, 2)
                c["pos"] = c["pos"] + c["vel"]
                if c["split"] is not None:
                    age = t - c["born"]
                    sgn, d = c["split"]
                    if age <= sep:
                        c["pos"] = c["pos"] + sgn * d * 2.5
                    else:
                        c["split"] = None
                    c["r"] = c["r"] + (c["r0"] - c["r"]) * 0.25
                    c["bright"] = c["bright"] * 0.92
                elif c["tdiv"] is not None and c["tdiv"] - pre <= t < c["tdiv"]:
                    c["phase"] = (t - (c["tdiv"] - pre) + 1) / pre
                else:
                    c["r"] = c["r"] + (c["r0"] - c["r"]) * 0.2
            # Neighbours do not overlap (sisters parting are left to their script).
            for _ in range(6):
                for i in range(len(cells)):
                    for j in range(i + 1, len(cells)):
                        a, b = cells[i], cells[j]
                        if a["parent"] and a["parent"] == b["parent"] and (a["split"] is not None):
                            continue
                        dv = a["pos"] - b["pos"]
                        dist = np.hypot(*dv) + 1e-9
                        need = 0.95 * (a["r"] * np.sqrt(a["asp"]) + b["r"] * np.sqrt(b["asp"])) + 2
                        if dist < need:
                            m = 0.5 * (need - dist) * dv / dist
                            a["pos"] = a["pos"] + m
                            b["pos"] = b["pos"] - m
            # New nuclei drift in at the border now and then.
            if rng.random() < 0.25:
                side = rng.integers(4)
                s = rng.uniform(30, size - 30)
                r = rng.uniform(13, 20)
                pos, vel = {0: ([s, -r * 0.9], [0, 2.0]), 1: ([s, size + r * 0.9], [0, -2.0]),
                            2: ([-r * 0.9, s], [2.0, 0]), 3: ([size + r * 0.9, s], [-2.0, 0])}[int(side)]
                c = nucleus(pos, r=r, born=t, vel=np.array(vel, float))
                if all(np.hypot(*(c["pos"] - o["pos"])) > c["r"] + o["r"] + 8 for o in cells):
                    cells.append(c)
            cells = [c for c in cells if -40 < c["pos"][0] < size + 40 and -40 < c["pos"][1] < size + 40]

        def geom(c):
            ph = c["phase"]
            asp = c["asp"] + 0.7 * ph
            r = c["r"] * (1 - 0.2 * ph)
            return r * np.sqrt(asp), r / np.sqrt(asp), 1.0 + 1.0 * ph

        def sd(xx, yy, c):
            ax, bx, _ = geom(c)
            return blob_sd(xx, yy, c["pos"], c["ang"], ax, bx, c["harm"])

        lab, cov = rasterise(h, w, cells, sd, lambda c: geom(c)[0] * 1.3 + 3)
        labs.append(lab)
        shapes.append([(c, geom(c)[2]) for c in cells])
    movie = []
    illum = illumination(rng, h, w, 0.1)
    for t in range(frames):
        lab = labs[t]
        img = np.full((h, w), 0.06)
        yy, xx = np.mgrid[0:h, 0:w].astype(float)
        val = np.zeros((h, w))
        for c, boost in shapes[t]:
            m = lab == c["id"]
            if not m.any():
                continue
            dx, dy = xx[m] - c["pos"][0], yy[m] - c["pos"][1]
            tex = 1.0
            for f, p1, p2 in c["tex"]:
                tex = tex + 0.08 * np.sin(f * dx + p1) * np.cos(f * dy + p2)
            val[m] = c["bright"] * boost * tex
        img = img + val
        img = ndi.gaussian_filter(img * illum, 1.4)
        movie.append(to_counts(rng, img, photons=900, read=4.0, offset=100))
    return movie, labs, events, dict(object="bright", modality="fluorescence")


# ----------------------------------------------------------------------- writing
def tracks_from(labs, events):
    """CTC tracks: each run of frames in which a cell has pixels is one track; a
    daughter's first run has its mother's last run as parent when that ends the frame
    before the daughter starts."""
    frames = len(labs)
    seen = {}
    for t, lab in enumerate(labs):
        for cid in np.unique(lab[lab > 0]):
            seen.setdefault(int(cid), []).append(t)
    mother = {d: m for (_, m, d1, d2) in events for d in (d1, d2)}
    runs = {}
    rows, relabel = [], [dict() for _ in range(frames)]
    nxt = 1
    for cid in sorted(seen):
        fr = seen[cid]
        start = fr[0]
        for i in range(1, len(fr) + 1):
            if i == len(fr) or fr[i] != fr[i - 1] + 1:
                runs.setdefault(cid, []).append((nxt, start, fr[i - 1]))
                for t in range(start, fr[i - 1] + 1):
                    relabel[t][cid] = nxt
                nxt += 1
                if i < len(fr):
                    start = fr[i]
    for cid, rs in runs.items():
        for k, (lab, b, e) in enumerate(rs):
            parent = 0
            if k == 0 and cid in mother and mother[cid] in runs:
                ml, mb, me = runs[mother[cid]][-1]
                if me == b - 1:
                    parent = ml
            rows.append((lab, b, e, parent))
    out = []
    for t, lab in enumerate(labs):
        lut = np.zeros(lab.max() + 1, np.uint16)
        for cid, new in relabel[t].items():
            lut[cid] = new
        out.append(lut[lab])
    return sorted(rows), out


def drifted(movie, labs, seed, sigma, reach=24):
    """The movie and its labels with the whole field moved by a random walk of `sigma` px a
    frame (kept within `reach` px), as a drifting stage moves it: what enters at an edge
    repeats the edge, and cells carried out of the frame are cut by it."""
    rng = np.random.default_rng(seed + 1_000_003)
    off, out_m, out_l = np.zeros(2), [], []
    for t, (img, lab) in enumerate(zip(movie, labs)):
        if t:
            off = np.clip(off + rng.normal(0, sigma, 2), -reach, reach)
        dy, dx = (int(v) for v in np.round(off))
        h, w = img.shape
        ys = np.clip(np.arange(h) - dy, 0, h - 1)
        xs = np.clip(np.arange(w) - dx, 0, w - 1)
        out_m.append(img[np.ix_(ys, xs)])
        inside = np.outer((np.arange(h) - dy >= 0) & (np.arange(h) - dy < h),
                          (np.arange(w) - dx >= 0) & (np.arange(w) - dx < w))
        out_l.append(np.where(inside, lab[np.ix_(ys, xs)], 0))
    return out_m, out_l


def write_case(out_dir, family, seed, frames, size):
    gen = {"bacteria_phase": bacteria_phase, "nuclei_fluo": nuclei_fluo}[family]
    movie, labs, events, kind = gen(seed, frames, size)
    if DRIFT > 0:
        movie, labs = drifted(movie, labs, seed, DRIFT)
    rows, masks = tracks_from(labs, events)
    os.makedirs(os.path.join(out_dir, "GT", "TRA"), exist_ok=True)
    os.makedirs(os.path.join(out_dir, "GT", "SEG"), exist_ok=True)
    tifffile.imwrite(os.path.join(out_dir, "movie.tif"), np.stack(movie))
    for t, m in enumerate(masks):
        tifffile.imwrite(os.path.join(out_dir, "GT", "TRA", f"man_track{t:03d}.tif"), m)
        tifffile.imwrite(os.path.join(out_dir, "GT", "SEG", f"man_seg{t:03d}.tif"), m)
    with open(os.path.join(out_dir, "GT", "TRA", "man_track.txt"), "w") as f:
        f.writelines(f"{a} {b} {c} {d}\n" for a, b, c, d in rows)
    kids = {}
    for r in rows:
        if r[3]:
            kids.setdefault(r[3], []).append(r[0])
    m = np.stack(movie)
    case = dict(name=os.path.basename(os.path.normpath(out_dir)), family=family, seed=seed, **kind,
                frames=frames, height=size, width=size, movie="movie.tif", dtype="uint16", gt="GT",
                tracks=len(rows), divisions=sum(len(k) == 2 for k in kids.values()),
                single_child_links=sum(len(k) == 1 for k in kids.values()),
                cells_first_frame=int(len(np.unique(masks[0])) - 1),
                cells_last_frame=int(len(np.unique(masks[-1])) - 1),
                intensity_range=[int(np.percentile(m, 0.5)), int(np.percentile(m, 99.5))],
                visibility="synthetic", generator="python/tools/synth_movie.py")
    with open(os.path.join(out_dir, "case.json"), "w") as f:
        json.dump(case, f, indent=2)
    return case


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("family", choices=["bacteria_phase", "nuclei_fluo"])
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--frames", type=int, default=None)
    ap.add_argument("--size", type=int, default=None)
    ap.add_argument("--gap", type=float, default=GAP,
                    help="nuclei_fluo: px between sister nuclei in their first frame (0: touching)")
    ap.add_argument("--photons", type=float, default=PHOTONS,
                    help="bacteria_phase: photons per unit of brightness (fewer: noisier)")
    ap.add_argument("--blur", type=float, default=BLUR, help="bacteria_phase: optics' Gaussian sigma, px")
    ap.add_argument("--line", type=float, default=LINE,
                    help="bacteria_phase: brightness of the line where two cells meet (0: none)")
    ap.add_argument("--widths", type=float, nargs=2, default=WIDTHS, metavar=("MIN", "MAX"),
                    help="bacteria_phase: range of rod widths, px")
    ap.add_argument("--doubling", type=float, nargs=2, default=DOUBLING, metavar=("MIN", "MAX"),
                    help="bacteria_phase: frames a cell cycle lasts (fewer: faster growth between frames)")
    ap.add_argument("--waist", type=float, default=WAIST,
                    help="bacteria_phase: depth of the mother's waist before she divides, a share of her radius (0: none)")
    ap.add_argument("--drift", type=float, default=DRIFT,
                    help="both: the whole field moves by a random walk of this many px a frame (0: still)")
    a = ap.parse_args()
    if (a.photons <= 0 or a.blur < 0 or a.line < 0 or a.drift < 0 or not 2 <= a.widths[0] <= a.widths[1]
            or not 2 <= a.doubling[0] <= a.doubling[1] or not 0 <= a.waist < 1):
        ap.error("need --photons > 0, --blur >= 0, --line >= 0, --drift >= 0, and --widths MIN MAX and "
                 "--doubling MIN MAX each with 2 <= MIN <= MAX, and 0 <= --waist < 1")
    globals().update(GAP=a.gap, PHOTONS=a.photons, BLUR=a.blur, LINE=a.line, WIDTHS=tuple(a.widths), DOUBLING=tuple(a.doubling),
                     WAIST=a.waist, DRIFT=a.drift)
    frames = a.frames or (50 if a.family == "bacteria_phase" else 60)
    size = a.size or (256 if a.family == "bacteria_phase" else 420)
    if frames < 2 or size < 64:
        raise SystemExit("synth_movie: need at least 2 frames and a size of 64 px")
    print(json.dumps(write_case(a.out, a.family, a.seed, frames, size)))


if __name__ == "__main__":
    main()
