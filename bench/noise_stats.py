"""Noise and agreement statistics of ibl and Cycles renders of the same scene (bench/cycles.sh).
Blender's Python reads the EXR files (no numpy needed); run it as

    blender -b --factory-startup -P bench/noise_stats.py -- noise --spp N \
        --ibl A.exr B.exr --ibl-seconds SA SB --blender C.exr D.exr --blender-seconds SC SD \
        [--blender-sampling-seconds TC TD]
    blender -b --factory-startup -P bench/noise_stats.py -- compare X.exr Y.exr [Z.exr ...]

Statistics are over the pixels the sphere covers fully in every image (alpha > 0.999), on the
luminance Y = 0.2126 R + 0.7152 G + 0.0722 B. `--region NAME` names those pixels in the output
(default "sphere"; bench/cycles.sh's room passes "room": there the pixels of the rect light,
alpha 0 in Cycles, are left out).

`noise`: for each renderer, two renders with different seeds a and b give per pixel the noise
of one render, |a - b| / sqrt(2), relative to the pixel's mean m = (a + b) / 2; the table shows
its RMS over the sphere ("rel RMS"), its median, and the efficiency 1 / (rel RMS^2 * seconds)
(seconds: the mean render time of the two), then the ratio ibl / Cycles of the efficiencies,
the ratio of the mean radiance over the sphere (ibl / Cycles; ~1 when the scenes match) and
the mean relative difference of the two-seed means, with the part of it that noise alone
explains (sqrt(2/pi) times the standard deviation of the difference).

`compare`: mean relative difference |X - Y| / Y of each further image against the first,
and the ratio of their means.
"""

import math
import statistics
import sys
from array import array

import bpy


def load_luminance(path):
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"  # the raw linear floats, no conversion
    w, h = img.size
    px = array("f", bytes(4 * 4 * w * h))
    img.pixels.foreach_get(px)
    y = [0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2] for i in range(0, len(px), 4)]
    alpha = px[3::4]
    rgb = (px[0::4], px[1::4], px[2::4])
    bpy.data.images.remove(img)
    return (w, h), y, alpha, rgb


def load_all(paths):
    data = [load_luminance(p) for p in paths]
    sizes = {d[0] for d in data}
    if len(sizes) != 1:
        sys.exit(f"noise_stats: images differ in size: {sizes}")
    n = len(data[0][1])
    mask = [i for i in range(n) if all(d[2][i] > 0.999 for d in data)]
    if not mask:
        sys.exit("noise_stats: no pixel is covered by the sphere in every image")
    return data, mask


def two_seed(a, b, mask):
    rel = []
    for i in mask:
        m = 0.5 * (a[i] + b[i])
        rel.append(abs(a[i] - b[i]) / math.sqrt(2.0) / m if m > 0 else 0.0)
    rms = math.sqrt(sum(r * r for r in rel) / len(rel))
    return rms, statistics.median(rel), rel


def noise(args):
    def take(flag, k):
        i = args.index(flag)
        return args[i + 1:i + 1 + k]

    spp = int(take("--spp", 1)[0])
    ibl = take("--ibl", 2)
    cyc = take("--blender", 2)
    ibl_s = [float(v) for v in take("--ibl-seconds", 2)]
    cyc_s = [float(v) for v in take("--blender-seconds", 2)]
    region = take("--region", 1)[0] if "--region" in args else "sphere"
    data, mask = load_all(ibl + cyc)
    (w, h) = data[0][0]
    ya, yb, yc, yd = (d[1] for d in data)
    rows = []
    for name, a, b, secs in (("ibl", ya, yb, ibl_s), ("cycles", yc, yd, cyc_s)):
        rms, med, rel = two_seed(a, b, mask)
        t = 0.5 * (secs[0] + secs[1])
        rows.append((name, rms, med, t, 1.0 / (rms * rms * t), rel))
    print(f"{w}x{h}, {spp} spp, {len(mask)} {region} pixels (alpha > 0.999 in all four images)")
    print(f"{'renderer':<9} {'spp':>6} {'seconds':>8} {'rel RMS':>9} {'median':>9} {'1/(noise^2 s)':>14}")
    for name, rms, med, t, eff, _ in rows:
        print(f"{name:<9} {spp:>6} {t:>8.3f} {rms:>9.5f} {med:>9.5f} {eff:>14.1f}")
    (_, rms_i, med_i, t_i, eff_i, rel_i), (_, rms_c, med_c, t_c, eff_c, rel_c) = rows
    print(f"efficiency ibl/cycles: {eff_i / eff_c:.3f} (noise ratio {rms_i / rms_c:.3f}, "
          f"median {med_i / med_c:.3f}; time ratio {t_i / t_c:.3f})")
    if "--blender-sampling-seconds" in args:
        ts = sum(float(v) for v in take("--blender-sampling-seconds", 2)) / 2
        if ts > 0:
            print(f"  against Cycles' path tracing alone ({ts:.2f} s, without its sync and "
                  f"importance map): {eff_i / (1.0 / (rms_c * rms_c * ts)):.3f}")
    mi = [0.5 * (ya[i] + yb[i]) for i in mask]
    mc = [0.5 * (yc[i] + yd[i]) for i in mask]
    ratio = sum(mi) / sum(mc)
    chans = []
    for c in range(3):
        si = sum(data[0][3][c][i] + data[1][3][c][i] for i in mask)
        sc = sum(data[2][3][c][i] + data[3][3][c][i] for i in mask)
        chans.append(si / sc)
    print(f"mean radiance ibl/cycles over the {region}: {ratio:.4f} "
          f"(R {chans[0]:.4f}, G {chans[1]:.4f}, B {chans[2]:.4f})")
    diff = [abs(x - y) / y for x, y in zip(mi, mc) if y > 0]
    floor = [math.sqrt(2.0 / math.pi) * math.sqrt(0.5 * (ri * ri + rc * rc))
             for ri, rc in zip(rel_i, rel_c)]
    print(f"mean relative difference of the two-seed means: {sum(diff) / len(diff):.4f} "
          f"(noise alone: ~{sum(floor) / len(floor):.4f})")


def compare(paths):
    data, mask = load_all(paths)
    ref = data[0][1]
    print(f"{data[0][0][0]}x{data[0][0][1]}, {len(mask)} sphere pixels; against {paths[0]}:")
    for p, d in zip(paths[1:], data[1:]):
        y = d[1]
        rel = [abs(y[i] - ref[i]) / ref[i] for i in mask if ref[i] > 0]
        ratio = sum(y[i] for i in mask) / sum(ref[i] for i in mask)
        print(f"  {p}: mean relative difference {sum(rel) / len(rel):.4f}, "
              f"median {statistics.median(rel):.4f}, mean ratio {ratio:.4f}")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not args or args[0] not in ("noise", "compare"):
        sys.exit(__doc__)
    if args[0] == "noise":
        noise(args[1:])
    else:
        compare(args[1:])


main()
