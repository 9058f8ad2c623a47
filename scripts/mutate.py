#!/usr/bin/env python3
"""Mutation testing of the shading rules: plants one deliberate error at a time in the code
(each rule exists once, in include/ibl/shared/ or the library, so one edit changes it for the
CPU and the GPU alike), rebuilds, and runs the CPU test suite; a mutant is killed when a test
fails. Prints one line per mutant and the count; exits 1 if any survives.

    python3 scripts/mutate.py [--build DIR] [--only SUBSTRING]

Run it when shading code changes (about 2 minutes per mutant on 2 cores). The tree is restored
after each mutant, also on Ctrl-C.
"""
import argparse
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent

# (name, [(file, original, replacement), ...]): every original must occur exactly once.
MUTANTS = [
    ("roughness-to-level mapping (linear read as Frostbite's)",
     [("include/ibl/shared/split_sum.h",
       "float t = frostbiteMapping ? sqrt(max(roughness, 0.0f)) : roughness;",
       "float t = frostbiteMapping ? roughness : sqrt(max(roughness, 0.0f));")]),
    ("SH band-2 cosine-lobe weight pi/4 -> pi/3",
     [("include/ibl/shared/sh.h", "return 0.78539816f;", "return 1.04719755f;")]),
    ("SH basis: the x^2 - y^2 constant",
     [("include/ibl/shared/sh.h", "return 0.546274f * (x * x - y * y);",
       "return 0.5f * (x * x - y * y);")]),
    ("specular dominant direction: sqrt(smoothness) -> smoothness",
     [("include/ibl/shared/split_sum.h", "smoothness * (sqrt(smoothness) + alpha)",
       "smoothness * (smoothness + alpha)")]),
    ("diffuse dominant direction: a constant of listing 23",
     [("include/ibl/shared/split_sum.h", "1.02341f * alpha - 1.51174f",
       "1.2341f * alpha - 1.51174f")]),
    ("specular-occlusion exponent -16 a -> -8 a",
     [("include/ibl/shared/split_sum.h", "exp2(-16.0f * alpha - 1.0f)",
       "exp2(-8.0f * alpha - 1.0f)")]),
    ("multiple-scattering compensation without the -1",
     [("include/ibl/shared/split_sum.h", "f0 * (1.0f / (dfg.x + dfg.y) - 1.0f)",
       "f0 * (1.0f / (dfg.x + dfg.y) - 0.9f)")]),
    ("normal map: bitangent sign flipped",
     [("include/ibl/shared/material.h", "(tangent.w < 0.0f ? -1.0f : 1.0f)",
       "(tangent.w < 0.0f ? 1.0f : -1.0f)")]),
    ("metallic-roughness channels swapped",
     [("include/ibl/shared/material.h", "vec2(metallic * texel.z, roughness * texel.y)",
       "vec2(metallic * texel.y, roughness * texel.z)")]),
    ("base color texture not sRGB-decoded (CPU and GPU)",
     [("src/render/renderer.cpp", "return srgbToLinear(glm::vec3(t));", "return glm::vec3(t);"),
      ("shaders/view/scene.frag",
       "baseColor *= srgbToLinear(texture(baseColorTexture, texCoord).rgb);",
       "baseColor *= texture(baseColorTexture, texCoord).rgb;")]),
    ("split sum: no emission",
     [("include/ibl/shared/split_sum.h", "vec3 color = m.emissive;", "vec3 color = vec3(0.0f);")]),
    ("reference: no emission",
     [("src/render/renderer.cpp", "return sum + p.emissive;", "return sum;")]),
    ("Fresnel power of the F0 = 0 lobe 5 -> 4",
     [("include/ibl/shared/brdf.h", "return ggxVisibilityLobe(c, a2) * (m2 * m2 * m);",
       "return ggxVisibilityLobe(c, a2) * (m2 * m2);")]),
    ("prefilter lobe: n.h^2 = (1 + c) / 2 -> (1 + c^2) / 2",
     [("include/ibl/shared/brdf.h", "float d = 0.5f * (1.0f + c) * (a2 - 1.0f) + 1.0f;",
       "float d = 0.5f * (1.0f + c * c) * (a2 - 1.0f) + 1.0f;")]),
    ("GGX D: one power of the denominator",
     [("include/ibl/shared/brdf.h", "return a2 / (kPi * d * d);", "return a2 / (kPi * d);")]),
    ("Smith visibility: 0.5 -> 0.25",
     [("include/ibl/shared/brdf.h", "return 0.5f / (lambdaV + lambdaL);",
       "return 0.25f / (lambdaV + lambdaL);")]),
    ("Schlick weight (1 - VoH)^5 -> ^4",
     [("include/ibl/shared/brdf.h", "  float m2 = m * m;\n  return m2 * m2 * m;",
       "  float m2 = m * m;\n  return m2 * m2;")]),
    ("Disney diffuse energy factor 1/1.51 -> 1/1.41",
     [("include/ibl/shared/brdf.h", "(1.0f / 1.51f - 1.0f)", "(1.0f / 1.41f - 1.0f)")]),
    ("DFG integrand: A without (1 - Fc)",
     [("include/ibl/shared/brdf.h", "return vec3((1.0f - fc) * g, fc * g,",
       "return vec3(g, fc * g,")]),
    ("face table: +Y face's t axis flipped (both directions)",
     [("include/ibl/shared/cube.h", "if (face == 2) return vec3(sc, 1.0f, tc);",
       "if (face == 2) return vec3(sc, 1.0f, -tc);"),
      ("include/ibl/shared/cube.h", "tc = d.y >= 0.0f ? d.z : -d.z;",
       "tc = d.y >= 0.0f ? -d.z : -d.z;")]),
    ("sRGB encode exponent 1/2.4 -> 1/2.2",
     [("include/ibl/shared/color.h", "pow(l, 1.0f / 2.4f)", "pow(l, 1.0f / 2.2f)")]),
    ("ACES tone curve constant",
     [("include/ibl/shared/color.h", "(c * (2.51f * c + 0.03f))", "(c * (2.41f * c + 0.03f))")]),
    ("adaptive stop on the deviation, not the standard error",
     [("src/render/renderer.cpp", "std::sqrt(variance / taken) <=", "std::sqrt(variance) <=")]),
    ("camera: no other up when up is parallel to the view",
     [("src/render/camera.cpp", "if (!(glm::length(side) > 1e-4f * glm::length(up))) {",
       "if (false) {")]),
    ("range: values encoded without clamping",
     [("src/io/ktx2.cpp", "const glm::vec3 c = representable(f, value);",
       "const glm::vec3 c = value;")]),
    ("visible-normal sampling: the warp's s",
     [("include/ibl/shared/sampling.h", "f.s = 0.5f * (1.0f + f.vh.z);", "f.s = 0.5f * (1.0f + 0.5f * f.vh.z);")]),
    ("GTAO: the slice integral's 2 h sin n -> h sin n",
     [("include/ibl/shared/ambient_occlusion.h", "cos(n) + 2.0f * h * sin(n))",
       "cos(n) + h * sin(n))")]),
    ("GTAO: visibility not weighted by the projected normal's length",
     [("include/ibl/shared/ambient_occlusion.h", "visibility += projectedLength * (",
       "visibility += (")]),
    ("GTAO: bent normal's in-plane moments added, not mirrored",
     [("include/ibl/shared/ambient_occlusion.h", "ortho * (plus.y - minus.y)",
       "ortho * (plus.y + minus.y)")]),
    ("specular micro-occlusion ignored in the split sum",
     [("include/ibl/shared/split_sum.h", "fresnelF90(f0, s.specularMicroOcclusion) * dfg.y",
       "dfg.y")]),
    ("bloom: the threshold without the -3 of EV to luminance",
     [("include/ibl/shared/bloom.h", "exp2(ev100 + compensation - 3.0f)",
       "exp2(ev100 + compensation)")]),
    ("bloom: a box instead of the tent in the halvings",
     [("src/render/bloom.cpp", "kTaps[4] = {0.125f, 0.375f, 0.375f, 0.125f};",
       "kTaps[4] = {0.0f, 0.5f, 0.5f, 0.0f};")]),
    ("SSR: the reflection about the half vector with the view's sign flipped",
     [("include/ibl/shared/screen_space_reflections.h", "2.0f * dot(v, h) * h - v",
       "2.0f * dot(v, h) * h + v")]),
    ("SSR: the ray's depth interpolated linearly on the screen",
     [("include/ibl/shared/screen_space_reflections.h",
       "return mix(z0 * k0, z1 * k1, t) / mix(k0, k1, t);",
       "return mix(z0, z1, t + 0.0f * k0 * k1);")]),
    ("SSR: the probes not weighted by the share the reflection leaves",
     [("include/ibl/shared/screen_space_reflections.h",
       "(1.0f - reflection.w) * probeOcclusion * probes", "probeOcclusion * probes")]),
    ("SSR: no roughness fade",
     [("include/ibl/shared/screen_space_reflections.h",
       "float fade = roughnessFade(roughness, r);", "float fade = 1.0f;")]),
    ("probes: the capture's alpha left out of the coverage",
     [("include/ibl/shared/probes.h", "coverage + share * clamp(alpha, 0.0f, 1.0f)",
       "coverage + share")]),
    ("captures: metals left black",
     [("src/render/path_tracer.cpp", "p.baseColor * (1.0f - p.metallic) + p.metallic * f0",
       "p.baseColor * (1.0f - p.metallic) + 0.0f * f0")]),
    ("emissive triangles: no MIS weight on the light sample",
     [("src/render/path_tracer.cpp",
       "visibility ? powerHeuristic(es.pdf, brdf.pdf(v, l)) / es.pdf : 1.0f / es.pdf",
       "1.0f / es.pdf")]),
    ("emissive triangles: the area density without the cosine at the light",
     [("src/render/emissive_triangles.cpp",
       "s.pdf = static_cast<float>(pTriangle) / tri.area * dist2 / cosLight;",
       "s.pdf = static_cast<float>(pTriangle) / tri.area * dist2;")]),
]


def run(cmd, **kw):
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, **kw)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build-mutate")
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    build = ROOT / args.build
    if run(["cmake", "-S", ".", "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
            "-DIBL_LTO=OFF", "-DIBL_BUILD_BENCH=OFF"]).returncode != 0:
        sys.exit("mutate: cmake failed")
    if run(["ninja", "-C", str(build)]).returncode != 0:
        sys.exit("mutate: the unmutated tree does not build")
    killed, survived = 0, []
    for name, edits in MUTANTS:
        if args.only not in name:
            continue
        originals = {}
        try:
            for path, old, new in edits:
                f = ROOT / path
                text = originals.setdefault(path, f.read_text())
                current = f.read_text()
                if current.count(old) != 1:
                    sys.exit(f"mutate: '{old}' is not in {path} exactly once; update the mutant")
                f.write_text(current.replace(old, new))
            start = time.time()
            built = run(["ninja", "-C", str(build)]).returncode == 0
            if built:
                tests = run(["ctest", "--test-dir", str(build), "-j2", "--stop-on-failure",
                             "-E", "^(Gpu|Viewer)\\."])
                dead = tests.returncode != 0
                failed = re.findall(r"Test +#\d+: (\S+) \.*\*\*\*", tests.stdout)
                why = ("killed by " + ", ".join(failed[:2])) if dead else "no test failed"
            else:
                dead, why = True, "killed by the compiler"
            print(f"{'killed  ' if dead else 'SURVIVED'}  {name}  ({why}, {time.time() - start:.0f} s)",
                  flush=True)
            if dead:
                killed += 1
            else:
                survived.append(name)
        finally:
            for path, text in originals.items():
                (ROOT / path).write_text(text)
    total = killed + len(survived)
    print(f"{killed} of {total} mutants killed")
    run(["ninja", "-C", str(build)])
    sys.exit(1 if survived else 0)


if __name__ == "__main__":
    main()
