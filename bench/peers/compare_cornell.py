"""Time-to-error comparison of luxel and Blender Cycles on the Cornell box.

Runs inside Blender's Python (for numpy and OpenEXR reading), from the repository root:

    blender -b --factory-startup --python bench/peers/compare_cornell.py -- \
        --reference out/peers/ref_seed1.exr out/peers/ref_seed2.exr \
                    out/peers/ref_seed3.exr out/peers/ref_seed4.exr \
        --markdown out/peers/table.md

It renders luxel (built-in `cornell`; --luxel-modes hq and/or radiosity) at several
element budgets and sample counts and Cycles (bench/peers/cycles_cornell.py) at several sample counts, all at
256x256 with 2 threads, and measures each image's error against a converged reference
(the average of independent high-spp Cycles renders with different seeds).

Error metric: RMSE over the masked pixels and the three channels, divided by the mean
reference radiance over the same pixels and channels ("relative RMSE").  The reference
still has Monte Carlo noise; because it is independent of the image being measured,
E[MSE(image, ref)] = MSE(image, truth) + var(ref), and var(ref) is estimated from the
spread of the K independent reference renders (per-pixel sample variance / K).  The
table gives both the raw RMSE and the noise-corrected one, sqrt(MSE - var(ref)), which
is what the matched-error analysis uses.

Mask: the pixels whose footprint lies inside a single planar face, at least 2 px away
from any depth or normal discontinuity.  The scene geometry (cycles_cornell.CORNELL_MESHES)
is ray cast with 8x8 sub-pixel rays per pixel through the same pinhole camera; a pixel
whose sub-pixel rays hit more than one face (or the background) straddles an edge, and
every pixel within 2 px (Chebyshev distance) of such a pixel is excluded.  The four
coplanar ceiling quads count as one face.  The light's own pixels (emission 17,12,4,
exact in both renderers, and 100x brighter than anything else) and background pixels
are excluded too.  Shadow boundaries are *not* excluded: they are radiance features that
a renderer has to get right.  --border sets the 2 px; the table also gives the error
with border 0 (every pixel whose footprint lies on one face), which adds the pixels
right next to creases, where a radiosity solution's discretisation error is largest.

Timing: luxel's is the wall time of the whole `luxel render` process (scene setup,
form factors, solve, render, EXR write), the median of --repeat runs; Cycles' is the time
of bpy.ops.render.render inside Blender (scene sync, BVH, path tracing, EXR write),
without Blender's own start-up and the scene building (~0.8 s).
"""

import argparse
import re
import importlib.util
import itertools
import json
import math
import os
import statistics
import subprocess
import sys
import time

import bpy
import numpy as np

sys.dont_write_bytecode = True  # importing cycles_cornell must leave no __pycache__ behind
HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("cycles_cornell", os.path.join(HERE, "cycles_cornell.py"))
cc = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cc)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="compare_cornell.py")
    p.add_argument("--reference", nargs="+", required=True,
                   help="independent converged Cycles renders (different seeds, same spp)")
    p.add_argument("--obj", help="compare on this OBJ (McGuire's Cornell box) from "
                                 "obj_scene.MCGUIRE_CAMERA instead of the built-in box")
    p.add_argument("--luxel", default="./build/luxel")
    p.add_argument("--blender", default="blender")
    p.add_argument("--outdir", default="out/peers")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--luxel-elements", default="2500,10000,40000")
    p.add_argument("--luxel-spp", default="4,16,64")
    p.add_argument("--luxel-solver", default="progressive")
    p.add_argument("--luxel-modes", default="hq", help="comma-separated: hq, radiosity")
    p.add_argument("--luxel-extra", default="", help="extra luxel render arguments")
    p.add_argument("--cycles-spp", default="16,64,256,1024")
    p.add_argument("--cycles-seed", type=int, default=0)
    p.add_argument("--repeat", type=int, default=3,
                   help="luxel runs per setting (median time); runs over 5 s are not repeated")
    p.add_argument("--reuse", action="store_true",
                   help="do not re-render images whose EXR and timing JSON exist")
    p.add_argument("--regions", type=int, default=4,
                   help="the worst-region error is over a grid of this many regions a side")
    p.add_argument("--border", type=int, default=2,
                   help="exclude pixels within this many pixels of an edge-straddling pixel")
    p.add_argument("--markdown", help="write the tables here")
    p.add_argument("--images", action="store_true",
                   help="write PNG comparisons (reference | image | signed error) to --outdir")
    return p.parse_args(argv)


# ---------------------------------------------------------------------------- images

def read_exr(path):
    """Linear RGB as float64 (H, W, 3), first row at the top."""
    img = bpy.data.images.load(os.path.abspath(path), check_existing=False)
    try:
        img.colorspace_settings.name = "Non-Color"
        w, h = img.size
        buf = np.empty(w * h * 4, np.float32)
        img.pixels.foreach_get(buf)
    finally:
        bpy.data.images.remove(img)
    return buf.reshape(h, w, 4)[::-1, :, :3].astype(np.float64)


def write_png(path, rgb):
    """rgb: (H, W, 3) display values in [0, 1] (already tone mapped), first row at the top."""
    h, w, _ = rgb.shape
    img = bpy.data.images.new("png", w, h, alpha=False)
    rgba = np.ones((h, w, 4), np.float32)
    rgba[..., :3] = np.clip(rgb, 0.0, 1.0)
    img.pixels.foreach_set(rgba[::-1].ravel())
    img.filepath_raw = os.path.abspath(path)
    img.file_format = "PNG"
    img.save()
    bpy.data.images.remove(img)


def display(x, scale):
    return np.clip(x / scale, 0, 1) ** (1 / 2.2)


def error_map(d, scale):
    """Signed error: red = too bright, blue = too dark, full at |d| = scale."""
    t = np.clip(np.abs(d).mean(axis=2) / scale, 0, 1)
    s = np.sign(d.mean(axis=2))
    out = np.zeros(d.shape)
    out[..., 0] = np.where(s > 0, t, 0)
    out[..., 2] = np.where(s < 0, t, 0)
    return out


# ---------------------------------------------------------------------------- mask

def scene_geometry(obj):
    """(polygons in metres with their face ids, faces as (mesh, material), camera, emitting
    materials): the built-in box from cycles_cornell (its four coplanar ceiling quads one face),
    or an OBJ from obj_scene (each polygon a face, named by its material: McGuire's files give
    the boxes' faces under the previous `g`)."""
    polys, faces = [], []
    if obj:
        meshes, materials = cc.obj_scene.load_obj(obj)
        for _, mat, polygons in meshes:
            for poly in polygons:
                polys.append((np.array(poly, np.float64), len(faces)))
                faces.append((mat, mat))
        lights = {m for m, v in materials.items() if cc.obj_scene.emits(v)}
        return polys, faces, cc.obj_scene.MCGUIRE_CAMERA, lights
    for mesh, mat, quads in cc.CORNELL_MESHES:
        for qi, q in enumerate(quads):
            if mesh == "ceiling" and qi > 0:
                fid = next(i for i, f in enumerate(faces) if f[0] == "ceiling")
            else:
                fid = len(faces)
                faces.append((mesh, mat))
            polys.append((np.array(q, np.float64) * cc.MM, fid))
    return polys, faces, cc.CORNELL_CAMERA, {"light"}


def face_ids(size, obj=None, sub=8):
    """Per pixel, the face id hit by each of sub x sub sub-pixel rays: (H, W, sub*sub), -1 = miss.

    Also returns the id -> (mesh, material) table and the emitting materials."""
    polys, faces, cam, lights = scene_geometry(obj)
    tris, tri_face = [], []
    for v, fid in polys:
        for i in range(1, len(v) - 1):
            tris.append((v[0], v[i], v[i + 1]))
            tri_face.append(fid)
    eye = np.array(cam["eye"])
    fwd = np.array(cam["target"]) - eye
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    th = math.tan(math.radians(cam["fov_deg"]) / 2)
    o = (np.arange(sub) + 0.5) / sub
    px = (np.arange(size)[:, None] + o[None, :]).ravel() / size  # (size*sub,)
    ids = np.empty((size, size, sub * sub), np.int64)
    rows_per_chunk = 16
    for r0 in range(0, size, rows_per_chunk):
        r1 = min(r0 + rows_per_chunk, size)
        sx, sy = np.meshgrid(px, px[r0 * sub: r1 * sub])  # sy: rows (down), sx: columns
        d = fwd + right * ((2 * sx - 1) * th)[..., None] + up * ((1 - 2 * sy) * th)[..., None]
        d = d.reshape(-1, 3)
        best_t = np.full(len(d), np.inf)
        best_f = np.full(len(d), -1)
        for (a, b, c), fid in zip(tris, tri_face):  # Moller-Trumbore, both faces
            e1, e2 = b - a, c - a
            pv = np.cross(d, e2)
            det = pv @ e1
            ok = np.abs(det) > 1e-12
            inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
            tv = eye - a
            u = (pv @ tv) * inv
            qv = np.cross(tv, e1)
            v = (d @ qv) * inv
            t = (qv @ e2) * inv
            hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-6) & (t < best_t)
            best_t[hit] = t[hit]
            best_f[hit] = fid
        ids[r0:r1] = best_f.reshape(r1 - r0, sub, size, sub).transpose(0, 2, 1, 3).reshape(
            r1 - r0, size, sub * sub)
    return ids, faces, lights


def build_mask(size, border=2, obj=None):
    ids, faces, lights = face_ids(size, obj)
    first = ids[..., 0]
    straddles = (ids != first[..., None]).any(axis=2) | (first < 0)
    near = np.zeros_like(straddles)
    padded = np.pad(straddles, border, constant_values=False)
    for dy in range(-border, border + 1):
        for dx in range(-border, border + 1):
            near |= padded[border + dy: border + dy + size, border + dx: border + dx + size]
    light = np.array([m in lights for _, m in faces])
    mask = ~near & (first >= 0) & ~light[np.maximum(first, 0)]
    return mask, np.where(straddles, -1, first), faces


# ---------------------------------------------------------------------------- renders

def run_luxel(args, mode, elements, spp):
    name = f"luxel_{mode}_e{elements}_s{spp}_{args.luxel_solver}"
    if args.luxel_extra.strip():  # different extra arguments must not reuse each other's renders
        name += "_" + re.sub(r"[^A-Za-z0-9]+", "", args.luxel_extra)
    exr = os.path.join(args.outdir, name + ".exr")
    meta = os.path.join(args.outdir, name + ".timing.json")
    if args.reuse and os.path.exists(exr) and os.path.exists(meta):
        with open(meta) as f:
            return name, exr, json.load(f)
    stats_path = os.path.join(args.outdir, name + ".stats.json")
    scene = ["cornell"]
    if args.obj:
        cam = cc.obj_scene.MCGUIRE_CAMERA
        scene = [args.obj, "--eye", ",".join(map(str, cam["eye"])), "--target", ",".join(map(str, cam["target"])),
                 "--fov", str(cam["fov_deg"])]
    cmd = [args.luxel, "render", *scene, "-o", exr, "--size", f"{args.size}x{args.size}",
           "--spp", str(spp), "--elements", str(elements), "--solver", args.luxel_solver,
           "--mode", mode, "--stats", stats_path, "--threads", str(args.threads), "-q"]
    cmd += args.luxel_extra.split()
    walls, totals = [], []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        walls.append(time.perf_counter() - t0)
        with open(stats_path) as f:
            stats = json.load(f)
        totals.append(stats["seconds"]["total"])
        if walls[-1] > 5.0:
            break
    info = {"command": " ".join(cmd), "wall_seconds": walls, "stats_total_seconds": totals,
            "seconds": statistics.median(walls), "elements": stats["elements"],
            "stats": stats["seconds"]}
    with open(meta, "w") as f:
        json.dump(info, f, indent=2)
    return name, exr, info


def run_cycles(args, spp):
    name = f"cycles_s{spp}_seed{args.cycles_seed}"
    exr = os.path.join(args.outdir, name + ".exr")
    meta = os.path.join(args.outdir, name + ".timing.json")
    if not (args.reuse and os.path.exists(exr) and os.path.exists(meta)):
        cmd = [args.blender, "-b", "--factory-startup", "--python",
               os.path.join(HERE, "cycles_cornell.py"), "--", "--spp", str(spp),
               "--seed", str(args.cycles_seed), "--out", exr, "--json", meta,
               "--threads", str(args.threads), "--size", str(args.size)]
        if args.obj:
            cmd += ["--obj", args.obj]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(meta) as f:
        info = json.load(f)
    info["seconds"] = info["render_seconds"]
    return name, exr, info


# ---------------------------------------------------------------------------- analysis

def fit_inverse_sqrt(spps, errors):
    """error = c / sqrt(spp), least squares in log space."""
    logc = np.mean(np.log(errors) + 0.5 * np.log(spps))
    return math.exp(logc)


def matched_cycles(pts, b, err):
    """Cycles' spp and time for the error `err`, from its measured (error, spp, seconds) `pts`
    (error ascending) and its seconds per sample `b`: interpolated log-log and piecewise linear
    between the measured sample counts; beyond them, extrapolated from the nearest measured point
    with error ~ 1/sqrt(spp) and time ~ a + b * spp."""
    if err <= pts[0][0] or err >= pts[-1][0] or len(pts) == 1:
        e0, s0, t0 = pts[0] if err <= pts[0][0] else pts[-1]
        spp = s0 * (e0 / err) ** 2
        return spp, max(t0 + b * (spp - s0), 0.0)
    for (e0, s0, t0), (e1, s1, t1) in zip(pts, pts[1:]):
        if e0 <= err <= e1:
            w = math.log(err / e0) / math.log(e1 / e0)
            return (math.exp(math.log(s0) + w * (math.log(s1) - math.log(s0))),
                    math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0))))


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    refs = np.stack([read_exr(p) for p in args.reference])
    ref = refs.mean(axis=0)
    size = ref.shape[0]
    assert ref.shape[:2] == (args.size, args.size), "reference size differs from --size"
    mask, face_of_pixel, faces = build_mask(size, args.border, args.obj)
    mask0 = build_mask(size, 0, args.obj)[0]  # also every single-face pixel, right up to the edges
    m0 = mask0[..., None].repeat(3, axis=2)
    ref_mean0 = ref[m0].mean()
    ref_var0 = (refs.var(axis=0, ddof=1) / len(refs))[m0].mean() if len(refs) > 1 else 0.0
    m = mask[..., None].repeat(3, axis=2)
    ref_mean = ref[m].mean()
    k = len(refs)
    ref_var = (refs.var(axis=0, ddof=1) / k)[m].mean() if k > 1 else 0.0
    lines = []

    def out(s=""):
        print(s, flush=True)
        lines.append(s)

    out(f"Reference: mean of {k} Cycles renders ({', '.join(args.reference)}); "
        f"mask (border {args.border} px): {mask.sum()} of {size * size} pixels (border 0: "
        f"{mask0.sum()}); mean reference radiance over the mask "
        f"{ref_mean:.5f}; reference noise, relative RMS: {math.sqrt(ref_var) / ref_mean:.5f}")
    out()

    def measure(img):
        d = img - ref
        mse = (d[m] ** 2).mean()
        raw = math.sqrt(mse) / ref_mean
        corr = math.sqrt(max(mse - ref_var, 0.0)) / ref_mean
        bias = img[m].mean() / ref_mean - 1.0
        corr0 = math.sqrt(max((d[m0] ** 2).mean() - ref_var0, 0.0)) / ref_mean0
        # The worst region: the image cut into regions x regions squares, each one's mean over its
        # masked pixels against the reference's (regions under a tenth masked are left out).
        worst, where = 0.0, ""
        g = args.regions
        for ry in range(g):
            for rx in range(g):
                sel = np.zeros(mask.shape, bool)
                sel[ry * size // g:(ry + 1) * size // g, rx * size // g:(rx + 1) * size // g] = True
                sel &= mask
                if sel.sum() < 0.1 * size * size / (g * g):
                    continue
                e = img[sel].sum() / ref[sel].sum() - 1.0
                if abs(e) > abs(worst):
                    worst, where = e, f"row {ry} col {rx}"
        return raw, corr, bias, corr0, worst, where

    rows = []
    for spp in [int(s) for s in args.cycles_spp.split(",") if s]:
        name, exr, info = run_cycles(args, spp)
        img = read_exr(exr)
        rows.append(dict(renderer="cycles", settings=f"{spp} spp", spp=spp,
                         seconds=info["seconds"], img=img, name=name,
                         err=measure(img)))
        print(f"  {rows[-1]['renderer']} {rows[-1]['settings']}: {info['seconds']:.3f} s", flush=True)
    for mode, elements, spp in itertools.product(
            [m for m in args.luxel_modes.split(",") if m],
            [int(e) for e in args.luxel_elements.split(",") if e],
            [int(s) for s in args.luxel_spp.split(",") if s]):
        name, exr, info = run_luxel(args, mode, elements, spp)
        img = read_exr(exr)
        rows.append(dict(renderer="luxel", settings=f"{mode}, {args.luxel_solver}, "
                         f"{info['elements']} elements, {spp} spp", spp=spp,
                         seconds=info["seconds"], img=img, name=name, info=info,
                         err=measure(img)))
        print(f"  {rows[-1]['renderer']} {rows[-1]['settings']}: {info['seconds']:.3f} s", flush=True)

    cyc = [r for r in rows if r["renderer"] == "cycles"]
    c = fit_inverse_sqrt(np.array([r["spp"] for r in cyc], float),
                         np.array([r["err"][1] for r in cyc]))
    # time = a + b * spp
    if len(cyc) >= 2:
        b, a = np.polyfit([r["spp"] for r in cyc], [r["seconds"] for r in cyc], 1)
    else:
        a, b = 0.0, cyc[0]["seconds"] / cyc[0]["spp"]

    pts = sorted((r["err"][1], r["spp"], r["seconds"]) for r in cyc)  # error ascending

    def cycles_time_for(err):
        return matched_cycles(pts, b, err)

    out(f"| renderer | settings | time (s) | rel. RMSE (raw) | rel. RMSE (noise-corrected) "
        f"| mean bias | Cycles spp for same error | Cycles time for same error (s) "
        f"| Cycles/luxel time | rel. RMSE, border 0 (noise-corrected) | worst region "
        f"({args.regions}x{args.regions}) |")
    out("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        raw, corr, bias, corr0, worst, where = r["err"]
        if r["renderer"] == "luxel":
            spp_eq, t_eq = cycles_time_for(corr)
            extra = f"{spp_eq:.0f} | {t_eq:.2f} | {t_eq / r['seconds']:.1f}"
        else:
            extra = " |  | "
        out(f"| {r['renderer']} | {r['settings']} | {r['seconds']:.3f} | {raw:.4f} | {corr:.4f} "
            f"| {bias * 100:+.2f}% | {extra} | {corr0:.4f} | {worst * 100:+.2f}% ({where}) |")
    out()
    out(f"Cycles fit: rel. RMSE = {c:.4f} / sqrt(spp); time = {a:.3f} s + {b * 1000:.2f} ms * spp "
        f"(at 256 spp: fit error {c / 16:.4f}, fit time {a + 256 * b:.2f} s)")
    for r in cyc:
        out(f"  cycles {r['spp']:>6} spp: measured {r['err'][1]:.4f}, fit {c / math.sqrt(r['spp']):.4f}")
    out()

    # Per-surface brightness: mean image / mean reference over each face's masked pixels.
    out("Per-surface mean radiance ratio (image / reference, R G B) over masked pixels:")
    out()
    lights = scene_geometry(args.obj)[3]
    names = sorted({f[0] for f in faces if f[1] not in lights},
                   key=lambda n: [f[0] for f in faces].index(n))
    out("| image | " + " | ".join(names) + " |")
    out("|---|" + "---|" * len(names))
    for r in rows:
        cells = []
        for n in names:
            sel = mask & np.isin(face_of_pixel, [i for i, f in enumerate(faces) if f[0] == n])
            if sel.sum() == 0:
                cells.append("-")
                continue
            ratio = r["img"][sel].mean(axis=0) / ref[sel].mean(axis=0)
            cells.append(" ".join(f"{x:.3f}" for x in ratio))
        out(f"| {r['renderer']} {r['settings']} | " + " | ".join(cells) + " |")
    out()

    # Where the squared error comes from: each surface's share of the sum over the mask.
    out("Share of the squared error (noise-corrected for the reference) by surface, and "
        "the surface's share of the masked pixels:")
    out()
    out("| image | " + " | ".join(names) + " |")
    out("|---|" + "---|" * len(names))
    sels = {n: mask & np.isin(face_of_pixel, [i for i, f in enumerate(faces) if f[0] == n])
            for n in names}
    out("| (pixels) | " + " | ".join(f"{sels[n].sum() / mask.sum() * 100:.1f}%" for n in names) + " |")
    refvar_px = (refs.var(axis=0, ddof=1) / k).sum(axis=2) if k > 1 else np.zeros(mask.shape)
    for r in rows:
        se = ((r["img"] - ref) ** 2).sum(axis=2) - refvar_px
        total = se[mask].sum()
        out(f"| {r['renderer']} {r['settings']} | "
            + " | ".join(f"{se[sels[n]].sum() / total * 100:.1f}%" for n in names) + " |")
    out()

    if args.images:
        scale = np.percentile(ref[mask], 99) * 1.2
        for r in rows:
            d = r["img"] - ref
            strip = np.concatenate([display(ref, scale), display(r["img"], scale),
                                    error_map(d, 0.1 * ref_mean)], axis=1)
            write_png(os.path.join(args.outdir, r["name"] + "_cmp.png"), strip)
        mimg = np.where(mask[..., None], display(ref, scale), display(ref, scale) * 0.25)
        write_png(os.path.join(args.outdir, "mask.png"), mimg)

    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
