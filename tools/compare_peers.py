#!/usr/bin/env python3
"""topocontour against the level-set tools users would otherwise pick, in one run.

usage: python3 tools/compare_peers.py [CASES_DIR] [--bin PATH] [--mode adaptive|preserve|implicit]

For every case folder (image.png, truth.png, case.json) it runs
  * our CLI as a whole process (load, evolve, write the mask): wall time of the process,
    the median of five runs (a single run is at the mercy of a cold binary or of a peer's
    worker threads still winding down on a small machine);
  * four peers, each configured once for all cases as a fair user would:
      skimage.morph_chan_vese, skimage.morph_gac, sitk.geodesic_active_contour,
      sitk.threshold_level_set
    timed on segmentation only (image loading excluded: generous to the peers);
and prints per case: seconds, Dice and topology (components, holes; 4-connected, as the
truth is counted) for each, then our speed ratio against the fastest peer that got the
topology right ("-" when none did).

The peers need numpy, scipy, scikit-image and SimpleITK. When they are missing the script
makes a virtual environment under target/peers-venv, installs them there with pip and
re-runs itself inside it.

Fair configuration (the same rules for every peer):
  * the user's initialisation: seed disks (grow) or a rectangle inside the border (shrink);
  * one parameter set per method for all cases; only what a user knows varies per case:
    grow or shrink, dark or bright objects;
  * thresholds and edge constants from the image itself (Otsu);
  * convergence as a user would judge it: evolve in chunks, stop when fewer than 0.1 % of
    the pixels change between chunks (with a cap), built-in stopping rules off;
  * region peers that end up labelling the background are flipped to the object class.
"""
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, "target", "peers-venv")
NEEDED = ["numpy", "scipy", "scikit-image", "SimpleITK"]


def ensure_packages():
    try:
        import numpy, scipy, skimage, SimpleITK  # noqa: F401
        return
    except ImportError:
        pass
    if os.environ.get("TOPO_PEERS_VENV"):
        sys.exit("compare_peers: the peer packages did not install: " + ", ".join(NEEDED))
    py = os.path.join(VENV, "bin", "python")
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
    subprocess.check_call([py, "-m", "pip", "install", "--quiet"] + NEEDED)
    env = dict(os.environ, TOPO_PEERS_VENV="1")
    os.execve(py, [py] + sys.argv, env)


ensure_packages()

import numpy as np  # noqa: E402
from scipy import ndimage as ndi  # noqa: E402
from skimage import io, segmentation as seg, draw, filters  # noqa: E402
import SimpleITK as sitk  # noqa: E402

TOL = 0.001
RUNS = 5


def init_mask(meta):
    h, w = meta["height"], meta["width"]
    m = np.zeros((h, w), bool)
    ini = meta["init"]
    if "seeds" in ini:
        for x, y, r in ini["seeds"]:
            rr, cc = draw.disk((y, x), max(r, 3), shape=m.shape)
            m[rr, cc] = True
    else:
        k = ini["border_margin"]
        m[k:h - k, k:w - k] = True
    return m


def growing(meta):
    return "seeds" in meta["init"]


def dark(meta):
    return meta["init"].get("object", "dark") == "dark"


def topo(mask):
    lab, n = ndi.label(mask)
    holes = 0
    for i in range(1, n + 1):
        comp = lab == i
        holes += ndi.label(ndi.binary_fill_holes(comp) & ~comp)[1]
    return n, holes


def dice(a, b):
    s = a.sum() + b.sum()
    return 2.0 * (a & b).sum() / s if s else 1.0


def to_object(mask, img, meta):
    if mask.all() or not mask.any():
        return mask
    inside, outside = img[mask].mean(), img[~mask].mean()
    if (dark(meta) and inside > outside) or (not dark(meta) and inside < outside):
        return ~mask
    return mask


def chunks(step, state, to_mask, chunk, cap):
    prev, it = to_mask(state), 0
    while it < cap:
        n = min(chunk, cap - it)
        state = step(state, n)
        it += n
        m = to_mask(state)
        if np.count_nonzero(m ^ prev) < TOL * m.size:
            break
        prev = m
    return state


def signed(mask):
    return (ndi.distance_transform_edt(~mask) - ndi.distance_transform_edt(mask)).astype(np.float32)


def edge_potential(img, sigma):
    """~1 on flat ground, ~0 on edges: gradient magnitude through a sigmoid whose midpoint is the
    Otsu split of the gradient magnitudes and whose width is set by their median."""
    g = sitk.GetArrayFromImage(sitk.GradientMagnitudeRecursiveGaussian(
        sitk.GetImageFromArray(img.astype(np.float32)), sigma))
    k2, beta = float(np.median(g)), float(filters.threshold_otsu(g))
    alpha = -(beta - k2) / 3.0
    return (1.0 / (1.0 + np.exp(-(g - beta) / alpha))).astype(np.float32)


def itk_run(f, meta, feat, chunk, cap):
    def step(ls, n):
        f.SetNumberOfIterations(n)
        return f.Execute(ls, feat)
    ls = chunks(step, sitk.GetImageFromArray(signed(init_mask(meta))),
                lambda ls: sitk.GetArrayViewFromImage(ls) < 0, chunk, cap)
    return sitk.GetArrayFromImage(ls) < 0


def morph_chan_vese(img, meta):
    step = lambda u, n: seg.morphological_chan_vese(img, n, init_level_set=u, smoothing=1)
    u = chunks(step, init_mask(meta).astype(np.int8), lambda u: u.astype(bool), 20, 3000)
    return to_object(u.astype(bool), img, meta)


def morph_gac(img, meta):
    g = edge_potential(img, 2.0)
    balloon = 1 if growing(meta) else -1
    step = lambda u, n: seg.morphological_geodesic_active_contour(
        g, n, init_level_set=u, smoothing=1, threshold=0.5, balloon=balloon)
    u = chunks(step, init_mask(meta).astype(np.int8), lambda u: u.astype(bool), 20, 3000)
    return u.astype(bool)


def sitk_gac(img, meta):
    f = sitk.GeodesicActiveContourLevelSetImageFilter()
    f.SetPropagationScaling(1.0 if growing(meta) else -1.0)
    f.SetCurvatureScaling(1.0)
    f.SetAdvectionScaling(1.0)
    f.SetMaximumRMSError(1e-6)
    return itk_run(f, meta, sitk.GetImageFromArray(edge_potential(img, 1.5)), 100, 6000)


def sitk_threshold(img, meta):
    s = ndi.gaussian_filter(img, 1.0)
    t = float(filters.threshold_otsu(s))
    f = sitk.ThresholdSegmentationLevelSetImageFilter()
    if dark(meta):
        f.SetLowerThreshold(t - 10.0)
        f.SetUpperThreshold(t)
    else:
        f.SetLowerThreshold(t)
        f.SetUpperThreshold(t + 10.0)
    f.SetCurvatureScaling(0.2)
    f.SetPropagationScaling(1.0)
    f.SetMaximumRMSError(1e-6)
    return itk_run(f, meta, sitk.GetImageFromArray(s.astype(np.float32)), 100, 6000)


PEERS = [("skimage.morph_chan_vese", morph_chan_vese), ("skimage.morph_gac", morph_gac),
         ("sitk.geodesic_ac", sitk_gac), ("sitk.threshold_ls", sitk_threshold)]


def ours(binary, d, meta, mode, out):
    ini = meta["init"]
    args = [binary, "segment", os.path.join(d, "image.png"), "--object", ini.get("object", "dark"),
            "--mode", mode, "--mask", out]
    if "seeds" in ini:
        for x, y, r in ini["seeds"]:
            args += ["--seed", f"{x},{y},{r}"]
    else:
        args += ["--wrap", str(ini["border_margin"])]
    times = []
    for _ in range(RUNS):
        t = time.perf_counter()
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - t)
    return sorted(times)[RUNS // 2], io.imread(out) > 127


def main():
    argv = sys.argv[1:]
    binary = os.path.join(ROOT, "target", "release", "topocontour")
    mode = "adaptive"
    if "--bin" in argv:
        i = argv.index("--bin")
        binary = argv[i + 1]
        del argv[i:i + 2]
    if "--mode" in argv:
        i = argv.index("--mode")
        mode = argv[i + 1]
        del argv[i:i + 2]
    cases = argv[0] if argv else os.path.join(ROOT, "tests", "cases")
    if not os.path.exists(binary):
        sys.exit(f"compare_peers: build first (cargo build --release): no {binary}")
    out = os.path.join(ROOT, "target", "compare_mask.png")
    names = [n for n in sorted(os.listdir(cases)) if os.path.exists(os.path.join(cases, n, "case.json"))]
    head = f"{'case':<16} {'method':<24} {'seconds':>9} {'dice':>7} {'comp':>5} {'holes':>5} {'topo':>5}"
    print(head)
    totals = {}
    ratios = []
    ours_total, best_total = 0.0, 0.0
    for name in names:
        d = os.path.join(cases, name)
        meta = json.load(open(os.path.join(d, "case.json")))
        img = io.imread(os.path.join(d, "image.png")).astype(float)
        if img.ndim == 3:
            img = img[..., :3].mean(axis=2)
        img /= 255.0
        truth = io.imread(os.path.join(d, "truth.png")) > 127
        want = (meta["expect"]["components"], meta["expect"]["holes"])
        rows = []
        secs, m = ours(binary, d, meta, mode, out)
        rows.append((f"topocontour ({mode})", secs, m))
        for pname, fn in PEERS:
            t = time.perf_counter()
            pm = np.asarray(fn(img, meta)).astype(bool)
            rows.append((pname, time.perf_counter() - t, pm))
        best = None
        for label, secs, m in rows:
            c, h = topo(m)
            ok = (c, h) == want
            print(f"{name:<16} {label:<24} {secs:>9.4f} {dice(m, truth):>7.4f} {c:>5} {h:>5} {'ok' if ok else 'NO':>5}")
            totals[label] = totals.get(label, 0.0) + secs
            if not label.startswith("topocontour") and ok and (best is None or secs < best[1]):
                best = (label, secs)
        if best:
            r = best[1] / rows[0][1]
            ratios.append(r)
            ours_total += rows[0][1]
            best_total += best[1]
            print(f"{name:<16} → {r:.0f}× faster than the fastest topology-right peer ({best[0]}, {best[1]:.3f} s)")
        else:
            print(f"{name:<16} → no peer got the topology right")
        print()
    print("total seconds: " + ", ".join(f"{k} {v:.3f}" for k, v in totals.items()))
    if ratios:
        print(f"speed ratio against the fastest topology-right peer: min {min(ratios):.0f}×, "
              f"median {sorted(ratios)[len(ratios) // 2]:.0f}× over {len(ratios)} cases")
        print(f"in total over those cases: topocontour {ours_total:.3f} s, the fastest topology-right "
              f"peer of each case {best_total:.3f} s: {best_total / ours_total:.0f}× less time")


if __name__ == "__main__":
    main()
