"""Compare luxel with Blender Cycles on a scene too large to rebuild by hand: luxel writes it as a
glb (`luxel bake SCENE -o FILE.glb`), Cycles renders that file (cycles_cornell.py --glb: its
geometry, camera, Lambertian base colours and one-sided emitters), and luxel renders the scene
itself from the same camera. Both against a converged Cycles reference; time to the same error as
a ratio, as compare_cornell.py does for the Cornell boxes.

Run headless (arguments after "--" belong to this script):

    blender -b --factory-startup --python bench/peers/compare_glb.py -- \
        --scene room-1.5m --glb out/peers/room/room-1.5m.glb \
        --reference out/peers/room/ref_seed1.exr out/peers/room/ref_seed2.exr \
        --outdir out/peers/room --cycles-spp 16,64,256 --markdown out/peers/room/table.md

The error is over every pixel (a closed room shows geometry everywhere; the Cornell boxes' mask of
pixels away from edges would need every polygon cast in Python): the relative RMSE with the
reference's own noise subtracted (from the spread of its renders), the mean bias, and the worst of
4 x 4 regions. Timing: luxel's is the wall time of the whole `luxel render` process (loading the
scene, building the hierarchy or reading it from the cache, solving, rendering, writing the EXR);
Cycles' is its render call (scene sync, BVH, sampling, the EXR), not Blender's start-up or the glb
import.
"""

import argparse
import importlib.util
import json
import math
import os
import statistics
import subprocess
import sys
import time

import numpy as np

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("compare_cornell", os.path.join(HERE, "compare_cornell.py"))
cmp = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(cmp)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="compare_glb.py")
    p.add_argument("--scene", required=True, help="what luxel renders: a built-in name or a scene file")
    p.add_argument("--glb", required=True, help="the same scene as `luxel bake` wrote it, for Cycles")
    p.add_argument("--reference", nargs="+", required=True,
                   help="independent converged Cycles renders of the glb (different seeds, same spp)")
    p.add_argument("--luxel", default="./build/luxel")
    p.add_argument("--blender", default="blender")
    p.add_argument("--outdir", default="out/peers/glb")
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--luxel-spp", default="16")
    p.add_argument("--luxel-extra", default="", help="extra luxel render arguments, ';' between settings")
    p.add_argument("--cycles-spp", default="16,64,256")
    p.add_argument("--cycles-seed", type=int, default=0)
    p.add_argument("--repeat", type=int, default=1, help="luxel runs per setting (median time)")
    p.add_argument("--reuse", action="store_true", help="do not re-render Cycles images that exist")
    p.add_argument("--regions", type=int, default=4)
    p.add_argument("--markdown", help="write the table here")
    return p.parse_args(argv)


def run_cycles(args, spp):
    name = f"cycles_s{spp}_seed{args.cycles_seed}"
    exr = os.path.join(args.outdir, name + ".exr")
    meta = os.path.join(args.outdir, name + ".timing.json")
    if not (args.reuse and os.path.exists(exr) and os.path.exists(meta)):
        subprocess.run([args.blender, "-b", "--factory-startup", "--python", os.path.join(HERE, "cycles_cornell.py"),
                        "--", "--glb", args.glb, "--spp", str(spp), "--seed", str(args.cycles_seed), "--out", exr,
                        "--json", meta, "--threads", str(args.threads), "--size", str(args.size)],
                       check=True, stdout=subprocess.DEVNULL)
    with open(meta) as f:
        return name, exr, json.load(f)["render_seconds"]


def run_luxel(args, spp, extra):
    tag = "".join(c for c in extra if c.isalnum())
    name = f"luxel_s{spp}" + (f"_{tag}" if tag else "")
    exr = os.path.join(args.outdir, name + ".exr")
    stats = os.path.join(args.outdir, name + ".stats.json")
    cmd = [args.luxel, "render", args.scene, "-o", exr, "--size", f"{args.size}x{args.size}", "--spp", str(spp),
           "--threads", str(args.threads), "--stats", stats, "-q"] + extra.split()
    walls = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        walls.append(time.perf_counter() - t0)
    with open(stats) as f:
        info = json.load(f)
    return name, exr, statistics.median(walls), info, " ".join(cmd)


def main():
    args = parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    refs = np.stack([cmp.read_exr(p) for p in args.reference])
    ref = refs.mean(axis=0)
    size = ref.shape[0]
    assert ref.shape[:2] == (args.size, args.size), "reference size differs from --size"
    k = len(refs)
    ref_mean = ref.mean()
    ref_var = (refs.var(axis=0, ddof=1) / k).mean() if k > 1 else 0.0
    lines = []

    def out(s=""):
        print(s, flush=True)
        lines.append(s)

    def measure(img):
        mse = ((img - ref) ** 2).mean()
        raw = math.sqrt(mse) / ref_mean
        corrected = math.sqrt(max(mse - ref_var, 0.0)) / ref_mean
        bias = img.mean() / ref_mean - 1.0
        worst, where, g = 0.0, "", args.regions
        for ry in range(g):
            for rx in range(g):
                sel = (slice(ry * size // g, (ry + 1) * size // g), slice(rx * size // g, (rx + 1) * size // g))
                e = img[sel].sum() / ref[sel].sum() - 1.0
                if abs(e) > abs(worst):
                    worst, where = e, f"row {ry} col {rx}"
        return raw, corrected, bias, worst, where

    out(f"Reference: mean of {k} Cycles renders of {args.glb} ({', '.join(args.reference)}); every pixel; mean "
        f"reference radiance {ref_mean:.5f}; reference noise, relative RMS: {math.sqrt(ref_var) / ref_mean:.5f}")
    out()
    rows = []
    for spp in [int(s) for s in args.cycles_spp.split(",") if s]:
        name, exr, seconds = run_cycles(args, spp)
        rows.append(dict(renderer="cycles", settings=f"{spp} spp", spp=spp, seconds=seconds, err=measure(cmp.read_exr(exr))))
        print(f"  cycles {spp} spp: {seconds:.2f} s", flush=True)
    for extra in [e.strip() for e in args.luxel_extra.split(";")] or [""]:
        for spp in [int(s) for s in args.luxel_spp.split(",") if s]:
            name, exr, seconds, info, cmd = run_luxel(args, spp, extra)
            rows.append(dict(renderer="luxel", settings=f"{info.get('solver', '')}, {info['elements']} elements, "
                             f"{spp} spp{(' ' + extra) if extra else ''}", spp=spp, seconds=seconds,
                             err=measure(cmp.read_exr(exr)), cmd=cmd))
            print(f"  luxel {rows[-1]['settings']}: {seconds:.2f} s", flush=True)

    cyc = [r for r in rows if r["renderer"] == "cycles"]
    b = (np.polyfit([r["spp"] for r in cyc], [r["seconds"] for r in cyc], 1)[0] if len(cyc) >= 2
         else cyc[0]["seconds"] / cyc[0]["spp"])
    pts = sorted((r["err"][1], r["spp"], r["seconds"]) for r in cyc)
    out(f"| renderer | settings | time (s) | rel. RMSE (raw) | rel. RMSE (noise-corrected) | mean bias "
        f"| Cycles spp for same error | Cycles time for same error (s) | Cycles/luxel time | worst region "
        f"({args.regions}x{args.regions}) |")
    out("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        raw, corrected, bias, worst, where = r["err"]
        if r["renderer"] == "luxel":
            spp_eq, t_eq = cmp.matched_cycles(pts, b, corrected)
            extra = f"{spp_eq:.0f} | {t_eq:.2f} | {t_eq / r['seconds']:.2f}"
        else:
            extra = " |  | "
        out(f"| {r['renderer']} | {r['settings']} | {r['seconds']:.2f} | {raw:.4f} | {corrected:.4f} "
            f"| {bias * 100:+.2f}% | {extra} | {worst * 100:+.2f}% ({where}) |")
    out()
    for r in rows:
        if r["renderer"] == "luxel":
            out(f"luxel: `{r['cmd']}`")
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
