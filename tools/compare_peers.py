#!/usr/bin/env python3
"""topocontour against the level-set tools users would otherwise pick, in one run.

usage: python3 tools/compare_peers.py [CASES_DIR] [--bin PATH] [--mode adaptive|preserve|implicit]
                                     [--auto-seeds]

For every case folder (image.png, truth.png, case.json) it runs
  * our CLI as a whole process (load, evolve, write the mask): wall time of the process,
    the median of five runs (a single run is at the mercy of a cold binary or of a peer's
    worker threads still winding down on a small machine);
  * four peers, each configured once for all cases as a fair user would:
      skimage.morph_chan_vese, skimage.morph_gac, sitk.geodesic_active_contour,
      sitk.threshold_level_set
    timed on segmentation only (image loading excluded: generous to the peers);
and prints per case: seconds, CPU seconds, Dice, SEG (the Cell Tracking Challenge
instance measure: mean Jaccard of each reference object with the predicted object that
covers more than half of it; instances from truth_labels.png, else the truth's
components; ours from the JSON polygons, a peer's from its mask's components) and
topology (components, holes; 4-connected, as the truth is counted) for each, then our
speed ratio against the fastest peer that got the topology right ("-" when none did).
Cases without truth.png (images to look at) report time and components only. A case
that names a modality passes it to our CLI (`--modality`), as score_cases.py does;
`--auto-seeds` replaces our initialisation by found seeds (the instance run).

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
import resource
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


def seg_score(ref, pred):
    """SEG of a predicted label image against a reference label image (0 = background)."""
    nr, npred = int(ref.max()) + 1, int(pred.max()) + 1
    both = np.bincount(ref.ravel() * npred + pred.ravel(), minlength=nr * npred).reshape(nr, npred)
    rsize, psize = both.sum(1), both.sum(0)
    scores = []
    for r in range(1, nr):
        if rsize[r] == 0:
            continue
        p = int(np.argmax(both[r, 1:])) + 1 if npred > 1 else 0
        inter = both[r, p] if p else 0
        ok = p and inter > 0.5 * rsize[r]
        scores.append(inter / (rsize[r] + psize[p] - inter) if ok else 0.0)
    return float(np.mean(scores)) if scores else float("nan")


def json_labels(doc, shape):
    """One label per outer contour of our JSON, its holes cut out (as score_cases.py)."""
    lab = np.zeros(shape, np.int64)
    ids = {}
    for c in doc["contours"]:
        if not c["hole"]:
            ids[c["id"]] = len(ids) + 1
            xy = np.asarray(c["points"], float)
            rr, cc = draw.polygon(xy[:, 1] - 0.5, xy[:, 0] - 0.5, shape)
            lab[rr, cc] = ids[c["id"]]
    for c in doc["contours"]:
        if c["hole"] and c["parent"] in ids:
            xy = np.asarray(c["points"], float)
            rr, cc = draw.polygon(xy[:, 1] - 0.5, xy[:, 0] - 0.5, shape)
            sel = lab[rr, cc] == ids[c["parent"]]
            lab[rr[sel], cc[sel]] = 0
    return lab


def ours(binary, d, meta, mode, auto, out):
    ini = meta["init"]
    js = out + ".json"
    args = [binary, "segment", os.path.join(d, "image.png"), "--object", ini.get("object", "dark"),
            "--mode", mode, "--mask", out, "--json", js]
    if "modality" in ini:
        args += ["--modality", ini["modality"]]
    if auto:
        args += ["--auto-seeds"]
    elif "seeds" in ini:
        for x, y, r in ini["seeds"]:
            args += ["--seed", f"{x},{y},{r}"]
    else:
        args += ["--wrap", str(ini["border_margin"])]
    times, cpus = [], []
    for _ in range(RUNS):
        t = time.perf_counter()
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        times.append(time.perf_counter() - t)
        cpus.append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    mask = io.imread(out) > 127
    return sorted(times)[RUNS // 2], sorted(cpus)[RUNS // 2], mask, json_labels(json.load(open(js)), mask.shape)


def main():
    argv = sys.argv[1:]
    binary = os.path.join(ROOT, "target", "release", "topocontour")
    mode = "adaptive"
    auto = "--auto-seeds" in argv
    if auto:
        argv.remove("--auto-seeds")
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
    head = (f"{'case':<18} {'method':<24} {'seconds':>9} {'cpu s':>9} {'dice':>7} {'seg':>7} "
            f"{'comp':>5} {'holes':>5} {'topo':>5}")
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
        tp = os.path.join(d, "truth.png")
        truth = io.imread(tp) > 127 if os.path.exists(tp) else None
        lp = os.path.join(d, "truth_labels.png")
        if os.path.exists(lp):
            ref = io.imread(lp).astype(np.int64)
        elif truth is not None:
            ref = ndi.label(truth, np.ones((3, 3), bool))[0]
        else:
            ref = None
        want = (meta["expect"]["components"], meta["expect"]["holes"])
        rows = []
        secs, cpu, m, lab = ours(binary, d, meta, mode, auto, out)
        label = f"topocontour ({mode}{', auto' if auto else ''})"
        rows.append((label, secs, cpu, m, lab))
        for pname, fn in PEERS:
            t, c0 = time.perf_counter(), time.process_time()
            pm = np.asarray(fn(img, meta)).astype(bool)
            secs, cpu = time.perf_counter() - t, time.process_time() - c0
            rows.append((pname, secs, cpu, pm, ndi.label(pm, np.ones((3, 3), bool))[0]))
        best = None
        for label, secs, cpu, m, lab in rows:
            c, h = topo(m)
            ok = truth is not None and (c, h) == want
            dc = f"{dice(m, truth):>7.4f}" if truth is not None else f"{'-':>7}"
            sg = f"{seg_score(ref, lab):>7.4f}" if ref is not None else f"{'-':>7}"
            verdict = ("ok" if ok else "NO") if truth is not None else "-"
            print(f"{name:<18} {label:<24} {secs:>9.4f} {cpu:>9.4f} {dc} {sg} {c:>5} {h:>5} {verdict:>5}")
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
