"""Tests of the Python module `ibl` (python/module.cpp) against the `ibl` command's own files.

Run by CTest as Python.Bindings (python/CMakeLists.txt), with PYTHONPATH holding the built
module, IBL_CLI the command and IBL_TEST_DATA the repository's data/ folder. Every result is
compared bit for bit with what the command writes for the same options.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np

import ibl

CLI = os.environ.get("IBL_CLI", "ibl")
DATA = os.environ.get(
    "IBL_TEST_DATA", os.path.join(os.path.dirname(__file__), "..", "..", "data"))

# Small sizes: the whole suite runs in a few seconds on 2 cores.
BAKE = {"size": 32, "irradiance_size": 8, "dfg_size": 16, "dfg_samples": 64,
        "preview_size": 8}
BAKE_ARGS = ["--size", "32", "--irradiance-size", "8", "--dfg-size", "16", "--dfg-samples",
             "64", "--preview-size", "8"]
# The same without the preview (whose size --no-preview refuses).
BAKE_NO_PREVIEW = {**{k: v for k, v in BAKE.items() if k != "preview_size"}, "no_preview": True}
BAKE_NO_PREVIEW_ARGS = BAKE_ARGS[:-2] + ["--no-preview"]


def run_cli(*args, check=True):
    """Runs the command; returns the CompletedProcess (text stdout and stderr)."""
    result = subprocess.run([CLI, *args], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"ibl {' '.join(args)} failed:\n{result.stderr}")
    return result


def cli_error(*args):
    """The command's error message (its stderr's first line without 'ibl: error: ')."""
    result = run_cli(*args, check=False)
    line = result.stderr.splitlines()[0]
    prefix = "ibl: error: "
    assert line.startswith(prefix), line
    return result.returncode, line[len(prefix):]


def python_spelling(message):
    """The command's message as the module words it: each long option `--input-layout` as the
    keyword `input_layout=` (written here apart from the module's C++)."""
    return re.sub(r"(^|[\s(\[{,;'\"`])--([A-Za-z][A-Za-z0-9-]*)",
                  lambda m: m[1] + m[2].replace("-", "_") + "=", message)


def bits(array):
    """The array's bytes as unsigned integers, for comparing floats bit for bit (NaN too)."""
    a = np.ascontiguousarray(array)
    return a.view({2: np.uint16, 4: np.uint32}[a.dtype.itemsize])


def read_ktx2(path, level=0):
    """A KTX2 file's level as float32 RGB, decoded here with NumPy alone (VK_FORMAT
    R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT, no supercompression): a decoder independent of
    the module's, (height, width, 3) for a 2D texture, (6, size, size, 3) for a cube map."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:12] == b"\xabKTX 20\xbb\r\n\x1a\n", path
    vk_format, _, width, height, _, _, faces, levels, scheme = np.frombuffer(data, "<u4", 9, 12)
    assert scheme == 0 and level < levels, path
    texel = {97: np.float16, 109: np.float32}[int(vk_format)]
    offset = int(np.frombuffer(data, "<u8", 1, 80 + 24 * level)[0])
    w, h = max(1, int(width) >> level), max(1, int(height) >> level)
    pixels = np.frombuffer(data, texel, int(faces) * w * h * 4, offset).astype(np.float32)
    pixels = pixels.reshape(int(faces), h, w, 4)[..., :3]
    return pixels if faces == 6 else pixels[0]


def files_of(folder):
    return sorted(os.path.relpath(os.path.join(d, f), folder)
                  for d, _, names in os.walk(folder) for f in names)


class Case(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def assertBitEqual(self, a, b, msg=None):
        self.assertEqual(a.shape, b.shape, msg)
        self.assertEqual(a.dtype, b.dtype, msg)
        self.assertTrue(np.array_equal(bits(a), bits(b)), msg)

    def assertBakeCubesEqual(self, result, directory, dtype):
        """The bake's specular, source and irradiance arrays against its KTX2 files."""
        for role, levels in (("specular", result["specular"]), ("source", result["source"]),
                             ("irradiance", [result["irradiance"]])):
            self.assertCubeLevelsEqual(levels, os.path.join(directory, role + ".ktx2"), dtype)

    def assertCubeLevelsEqual(self, arrays, ktx2, dtype):
        """Each returned level against the file's, as the file's texel type stores it."""
        for level, array in enumerate(arrays):
            decoded = read_ktx2(ktx2, level)
            self.assertBitEqual(ibl.read_image(ktx2, level=level), decoded)
            self.assertBitEqual(array.astype(dtype), decoded.astype(dtype),
                                f"{ktx2} level {level}")


class TestBake(Case):
    def test_files_and_arrays_equal_the_command(self):
        cmd, py = self.path("cmd"), self.path("py")
        run_cli("bake", *BAKE_ARGS, "-o", cmd, "--quiet")
        result = ibl.bake(**BAKE, output=py, quiet=True)
        self.assertEqual(files_of(cmd), files_of(py))
        for name in files_of(cmd):
            with open(os.path.join(cmd, name), "rb") as f:
                expected = f.read()
            with open(os.path.join(py, name), "rb") as f:
                actual = f.read()
            if name == "manifest.json":
                # Nothing in a manifest differs between runs (no timings): the same bytes.
                self.assertEqual(json.loads(actual), json.loads(expected))
            self.assertEqual(actual, expected, name)
        with open(os.path.join(cmd, "manifest.json")) as f:
            self.assertEqual(result["manifest"], json.load(f))
        # The arrays are the bake's floats; the KTX2 files hold them as half floats.
        self.assertEqual(len(result["specular"]), 3)  # 32, 16, 8
        self.assertEqual(result["specular"][0].shape, (6, 32, 32, 3))
        self.assertBakeCubesEqual(result, cmd, np.float16)
        dfg = read_ktx2(os.path.join(cmd, "dfg.ktx2"))
        self.assertEqual(result["dfg"].shape, (16, 16, 3))
        self.assertBitEqual(result["dfg"].astype(np.float16), dfg.astype(np.float16))
        with open(os.path.join(cmd, "sh.json")) as f:
            sh = np.array(json.load(f)["coefficients"], dtype=np.float32)
        self.assertBitEqual(result["sh"], sh)

    def test_float_files_hold_the_arrays_exactly(self):
        cmd = self.path("cmd")
        run_cli("bake", *BAKE_NO_PREVIEW_ARGS, "--format", "rgba32f", "--sheen", "-o", cmd,
                "--quiet")
        result = ibl.bake(**BAKE_NO_PREVIEW, format="rgba32f", sheen=True, quiet=True)
        self.assertCubeLevelsEqual(result["specular"], os.path.join(cmd, "specular.ktx2"),
                                   np.float32)
        self.assertCubeLevelsEqual(result["sheen"], os.path.join(cmd, "sheen.ktx2"), np.float32)
        self.assertCubeLevelsEqual([result["irradiance"]], os.path.join(cmd, "irradiance.ktx2"),
                                   np.float32)
        sheen_dfg = read_ktx2(os.path.join(cmd, "sheen_dfg.ktx2"))
        self.assertBitEqual(result["sheen_dfg"].astype(np.float16), sheen_dfg.astype(np.float16))
        with open(os.path.join(cmd, "manifest.json")) as f:
            self.assertEqual(result["manifest"], json.load(f))

    def test_array_equals_the_same_pixels_in_a_file(self):
        rng = np.random.default_rng(7)
        pixels = rng.uniform(0.0, 4.0, (32, 64, 3)).astype(np.float32)
        exr = self.path("pixels.exr")
        ibl.write_image(exr, pixels, exr_type="float")
        self.assertBitEqual(ibl.read_image(exr), pixels)
        cmd = self.path("cmd")
        run_cli("bake", exr, *BAKE_ARGS, "--format", "rgba32f", "--rotate", "30", "-o", cmd,
                "--quiet")
        result = ibl.bake(pixels, **BAKE, format="rgba32f", rotate=30, quiet=True)
        self.assertBakeCubesEqual(result, cmd, np.float32)
        with open(os.path.join(cmd, "manifest.json")) as f:
            manifest = json.load(f)
        # The same manifest but for the source's name and format.
        self.assertEqual(result["manifest"]["source"]["path"], "(array)")
        self.assertEqual(result["manifest"]["source"]["format"], "array")
        for m in (manifest, result["manifest"]):
            del m["source"]["path"], m["source"]["format"]
        self.assertEqual(result["manifest"], manifest)
        # A four-channel array: its alpha is left out.
        rgba = np.concatenate([pixels, np.zeros((32, 64, 1), np.float32)], axis=2)
        again = ibl.bake(rgba, **BAKE, format="rgba32f", rotate=30, quiet=True)
        self.assertBitEqual(again["specular"][0], result["specular"][0])


class TestRender(Case):
    @classmethod
    def setUpClass(cls):
        cls.bake_dir = tempfile.TemporaryDirectory()
        run_cli("bake", *BAKE_NO_PREVIEW_ARGS, "-o", cls.bake_dir.name, "--quiet")

    @classmethod
    def tearDownClass(cls):
        cls.bake_dir.cleanup()

    def check_mode(self, cli_args, **options):
        exr = self.path("cmd.exr")
        run_cli("render", "grid", "--size", "48x32", "--bake", self.bake_dir.name, *cli_args,
                "-o", exr, "--quiet")
        py_exr = self.path("py.exr")
        image = ibl.render("grid", size=(48, 32), bake=self.bake_dir.name, output=py_exr,
                           quiet=True, **options)
        self.assertEqual(image.shape, (32, 48, 4))
        self.assertEqual(image.dtype, np.float32)
        # The EXR is 32-bit float: the radiance equals bit for bit; the files (alpha included)
        # byte for byte.
        self.assertBitEqual(image[..., :3], ibl.read_image(exr))
        with open(exr, "rb") as a, open(py_exr, "rb") as b:
            self.assertEqual(a.read(), b.read())
        self.assertGreater(image[..., 3].max(), 0.5)  # the spheres' coverage
        self.assertGreater(image[..., :3].max(), 0.0)
        return image

    def test_split_sum(self):
        self.check_mode(["--spp", "2"], spp=2)

    def test_reference(self):
        image = self.check_mode(["--mode", "reference", "--spp", "4", "--seed", "7",
                                 "--bounces", "2"],
                                mode="reference", spp=4, seed=7, bounces=2)
        other = ibl.render("grid", size=(48, 32), bake=self.bake_dir.name, mode="reference",
                           spp=4, seed=8, bounces=2, quiet=True)
        self.assertFalse(np.array_equal(image, other))  # the seed is used

    def test_environment_array_equals_the_same_pixels_in_a_file(self):
        # As bake() takes one: an (h, w, 3 or 4) array laid out by its shape, here 2:1.
        rng = np.random.default_rng(5)
        pixels = rng.uniform(0.0, 3.0, (16, 32, 3)).astype(np.float32)
        exr = self.path("env.exr")
        ibl.write_image(exr, pixels, exr_type="float")
        cmd = self.path("cmd.exr")
        run_cli("render", "sphere", "--size", "16x16", "--env", exr, "--spp", "1", "-o", cmd,
                "--quiet")
        image = ibl.render("sphere", size=(16, 16), env=pixels, spp=1, quiet=True)
        self.assertBitEqual(image[..., :3], ibl.read_image(cmd))
        rgba = np.concatenate([pixels, np.ones((16, 32, 1), np.float32)], axis=2)
        self.assertBitEqual(ibl.render("sphere", size=(16, 16), env=rgba, spp=1, quiet=True),
                            image)
        # Another environment gives another image: the array is the one used.
        other = ibl.render("sphere", size=(16, 16), env=pixels * 2, spp=1, quiet=True)
        self.assertFalse(np.array_equal(other, image))
        with self.assertRaises(ValueError):
            ibl.render("sphere", env=np.zeros((4, 4), np.float32))
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.render("sphere", env=pixels, bake=self.bake_dir.name)
        self.assertTrue(str(caught.exception).startswith("env=: contradicts bake= "),
                        caught.exception)

    def test_sphere_with_material_options(self):
        exr = self.path("cmd.exr")
        run_cli("render", "sphere", "--size", "24x24", "--bake", self.bake_dir.name,
                "--roughness", "0.3", "--metallic", "1", "--base-color", "0.9,0.5,0.2",
                "--background", "0,0,0", "-o", exr, "--quiet")
        image = ibl.render("sphere", size=(24, 24), bake=self.bake_dir.name, roughness=0.3,
                           metallic=1, base_color=(0.9, 0.5, 0.2), background="0,0,0",
                           quiet=True)
        self.assertBitEqual(image[..., :3], ibl.read_image(exr))


class TestCompareAndSky(Case):
    def test_compare_equals_the_commands_json(self):
        rng = np.random.default_rng(3)
        a = rng.uniform(0.0, 2.0, (16, 24, 3)).astype(np.float32)
        b = (a * rng.uniform(0.8, 1.2, a.shape)).astype(np.float32)
        mask = np.zeros_like(a)
        mask[4:12] = 1.0
        pa, pb, pm = self.path("a.exr"), self.path("b.exr"), self.path("mask.exr")
        for path, array in ((pa, a), (pb, b), (pm, mask)):
            ibl.write_image(path, array, exr_type="float")
        expected = json.loads(run_cli("compare", pa, pb, "--json").stdout)
        self.assertEqual(ibl.compare(pa, pb), expected)
        self.assertEqual(ibl.compare(a, b), expected)
        masked = json.loads(run_cli("compare", pa, pb, "--mask", pm, "--json").stdout)
        self.assertEqual(ibl.compare(pa, pb, mask=pm), masked)
        self.assertEqual(ibl.compare(a, b, mask=mask), masked)
        self.assertEqual(masked["pixels"], 8 * 24)
        png_cmd, png_py = self.path("cmd.png"), self.path("py.png")
        run_cli("compare", pa, pb, "--error-png", png_cmd, "--error-scale", "0.2")
        ibl.compare(a, b, error_png=png_py, error_scale=0.2)
        with open(png_cmd, "rb") as x, open(png_py, "rb") as y:
            self.assertEqual(x.read(), y.read())

    def test_sky_equals_the_commands_file(self):
        exr = self.path("sky.exr")
        run_cli("sky", "--size", "64x32", "--sun-elevation", "20", "--turbidity", "3", "-o", exr,
                "--quiet")
        panorama = ibl.sky(size=(64, 32), sun_elevation=20, turbidity=3)
        self.assertEqual(panorama.shape, (32, 64, 3))
        self.assertBitEqual(panorama, ibl.read_image(exr))  # a 32-bit float EXR


class TestImagesAndErrors(Case):
    def test_write_and_read_round_trip(self):
        rng = np.random.default_rng(1)
        pixels = rng.uniform(0.0, 100.0, (5, 7, 3)).astype(np.float32)
        for name, exr_type, stored in (("f.exr", "float", np.float32), ("h.exr", "half",
                                                                          np.float16)):
            ibl.write_image(self.path(name), pixels, exr_type=exr_type)
            back = ibl.read_image(self.path(name))
            self.assertEqual(back.dtype, np.float32)
            self.assertBitEqual(back.astype(stored), pixels.astype(stored))
        # As `ibl convert` writes it: the same bytes.
        ibl.write_image(self.path("py.hdr"), ibl.read_image(self.path("f.exr")))
        run_cli("convert", self.path("f.exr"), "-o", self.path("cmd.hdr"), "--quiet")
        with open(self.path("py.hdr"), "rb") as a, open(self.path("cmd.hdr"), "rb") as b:
            self.assertEqual(a.read(), b.read())
        sunset = ibl.read_image(os.path.join(DATA, "hdri", "sunset.exr"))
        self.assertEqual((sunset.ndim, sunset.shape[1], sunset.shape[2]),
                         (3, 2 * sunset.shape[0], 3))
        with self.assertRaises(ValueError):
            ibl.write_image(self.path("x.exr"), np.zeros((4, 4), np.float32))

    def test_read_image_equals_an_independent_decoder(self):
        # A rendered frame (3:2, no environment layout) converted by the command into a 2D
        # float KTX2 file, decoded here: the module's reading of the EXR holds the same floats.
        exr, ktx2 = self.path("frame.exr"), self.path("frame.ktx2")
        run_cli("render", "sphere", "--size", "24x16", "--env", "sky:elevation=40,size=64x32",
                "--spp", "1", "-o", exr, "--quiet")
        run_cli("convert", exr, "-o", ktx2, "--format", "rgba32f", "--quiet")
        decoded = read_ktx2(ktx2)
        self.assertEqual(decoded.shape, (16, 24, 3))
        self.assertBitEqual(ibl.read_image(exr), decoded)
        self.assertBitEqual(ibl.read_image(ktx2), decoded)

    def test_errors_carry_the_commands_messages(self):
        missing = self.path("missing.exr")
        status, message = cli_error("bake", missing, "-o", self.path("out"))
        self.assertEqual(status, 1)
        with self.assertRaises(ibl.Error) as caught:
            ibl.bake(missing)
        self.assertNotIsInstance(caught.exception, ibl.UsageError)
        self.assertIsInstance(caught.exception, RuntimeError)
        self.assertEqual(str(caught.exception), message)

        with self.assertRaises(ibl.Error) as caught:
            ibl.read_image(missing)
        self.assertEqual(str(caught.exception), message)

        # Usage errors: the command's message with its options spelled as keywords.
        status, message = cli_error("bake", "--size", "33", "-o", self.path("out"))
        self.assertEqual(status, 2)
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.bake(size=33)
        self.assertEqual(str(caught.exception), python_spelling(message))
        self.assertTrue(str(caught.exception).startswith("size=: "), caught.exception)

        status, message = cli_error("bake", "--input-layout", "diagonal", "-o", self.path("out"))
        self.assertEqual(status, 2)
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.bake(input_layout="diagonal")
        self.assertEqual(str(caught.exception), python_spelling(message))
        self.assertIn("input_layout=", str(caught.exception))
        self.assertNotIn("--", str(caught.exception))

        status, message = cli_error("render", "grid", "--mode", "reference", "--shadows", "map",
                                    "-o", self.path("x.exr"))
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.render("grid", mode="reference", shadows="map")
        self.assertEqual(str(caught.exception), python_spelling(message))
        self.assertNotIn("--", str(caught.exception))

        status, message = cli_error("sky", "--size", "64x32", "--sun-elevation", "100", "-o",
                                    self.path("s.exr"))
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.sky(size=(64, 32), sun_elevation=100)
        self.assertEqual(str(caught.exception), python_spelling(message))
        self.assertTrue(str(caught.exception).startswith("sun_elevation=: "), caught.exception)

        # An unknown keyword is named as given, with the nearest ones, and its value (which
        # the command line would take for a positional argument) is not in the message.
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.bake(sizee=64)
        self.assertEqual(str(caught.exception),
                         "sizee=: not a keyword of ibl.bake(); did you mean size=?")
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.render("sphere", no_such_option=12345)
        self.assertEqual(str(caught.exception), "no_such_option=: not a keyword of ibl.render()")
        with self.assertRaises(ibl.UsageError) as caught:
            ibl.sky(sun_elevatoin=10)
        self.assertIn("; did you mean sun_elevation=?", str(caught.exception))
        # The sun's file is written beside the image: without one, there is nowhere to put it.
        with self.assertRaises(ibl.UsageError):
            ibl.sky(size=(64, 32), sun_json=self.path("sun.json"))
        self.assertFalse(os.path.exists(self.path("sun.json")))
        # An array is no option value (the environment of bake() and render()'s env= are the
        # ones that take pixels).
        with self.assertRaises(TypeError):
            ibl.render("grid", lights=np.zeros((8, 16, 3), np.float32))

    def test_numpy_scalars_are_option_values(self):
        plain = ibl.sky(size=(64, 32), sun_elevation=20, quiet=True)
        numpy = ibl.sky(size=(np.int64(64), np.int32(32)), sun_elevation=np.float32(20),
                        quiet=True)
        self.assertTrue(np.array_equal(plain, numpy))
        self.assertEqual(plain.shape, (32, 64, 3))

    def test_version(self):
        self.assertEqual(f"ibl {ibl.__version__}", run_cli("--version").stdout.strip())

    def test_docs_name_the_interpreter_of_this_build(self):
        # docs/python.md states the Python the module is built for; CMake's (IBL_PYTHON_VERSION)
        # and this interpreter's (the one CMake found runs the tests) must be that one.
        with open(os.path.join(DATA, "..", "docs", "python.md")) as f:
            stated = re.search(r"built for Python (\d+)\.(\d+)", f.read())
        self.assertIsNotNone(stated, "docs/python.md names no Python version")
        version = tuple(int(n) for n in stated.groups())
        self.assertEqual(version, sys.version_info[:2])
        built = os.environ.get("IBL_PYTHON_VERSION", "")
        self.assertEqual(tuple(int(n) for n in built.split(".")[:2]), version, built)
        tag = f"cpython-{version[0]}{version[1]}-"
        self.assertIn(tag, os.path.basename(ibl.__file__))


class TestProgressAndThreads(Case):
    def assertOneBarFollows(self, calls):
        """The callback's contract (docs/python.md): the stages one after another, each from
        0 to 1 with fractions that never decrease; returns the stages in their order."""
        stages = []
        for stage, fraction in calls:
            self.assertIsInstance(stage, str)
            self.assertIsInstance(fraction, float)
            if not stages or stages[-1][0] != stage:
                self.assertNotIn(stage, [s for s, _ in stages], f"{stage} again, in {calls}")
                stages.append((stage, []))
            stages[-1][1].append(fraction)
        for stage, fractions in stages:
            self.assertEqual(fractions[0], 0.0, stage)
            self.assertEqual(fractions[-1], 1.0, stage)
            self.assertEqual(fractions, sorted(fractions), stage)
        return [s for s, _ in stages]

    def test_progress_reports_one_stage_after_another(self):
        # A DFG table no other test integrates (so it runs beside the convolutions), and a
        # sheen chain: stages that run at the same time in the library.
        calls = []
        ibl.bake(size=64, irradiance_size=16, dfg_size=32, dfg_samples=1000, sheen=True,
                 no_preview=True, quiet=True,
                 progress=lambda stage, fraction: calls.append((stage, fraction)))
        stages = self.assertOneBarFollows(calls)
        self.assertTrue(stages[0].startswith("source cube 64x64"), stages)
        for expected in ("irradiance 16x16", "DFG table 32x32 (1000 samples per texel)",
                         "sheen table 32x32 (4000 samples per texel)"):
            self.assertIn(expected, stages)
        levels = [s for s in stages if s.startswith("specular level ")]
        self.assertEqual(len(levels), 4)  # 64, 32, 16, 8: in their order
        self.assertEqual([s.split()[2] for s in levels], ["1/4", "2/4", "3/4", "4/4"])
        self.assertEqual(len([s for s in stages if s.startswith("sheen (Charlie): ")]), 4)
        self.assertGreater(len(calls), 2 * len(stages))  # fractions between 0 and 1 too

        calls = []
        ibl.render("sphere", size=(16, 16), spp=1, env="none",
                   progress=lambda stage, fraction: calls.append((stage, fraction)), quiet=True)
        self.assertEqual(self.assertOneBarFollows(calls), ["rendering"])

    def test_a_raising_callback_propagates(self):
        class Stop(Exception):
            pass

        calls = []

        def callback(stage, fraction):
            calls.append(stage)
            raise Stop(f"stop at {stage}")

        with self.assertRaises(Stop) as caught:
            ibl.bake(**BAKE, progress=callback, quiet=True)
        self.assertEqual(len(calls), 1)  # not called again after it raised
        self.assertEqual(str(caught.exception), f"stop at {calls[0]}")

    def test_the_gil_is_released_during_a_bake(self):
        counter = [0]
        stop = threading.Event()

        def count():
            while not stop.is_set():
                counter[0] += 1

        interval = sys.getswitchinterval()
        sys.setswitchinterval(0.001)
        thread = threading.Thread(target=count)
        thread.start()
        try:
            time.sleep(0.02)
            before = counter[0]
            time.sleep(0.02)
            per_20ms = counter[0] - before
            # A bake of about a quarter of a second: with the GIL held the thread could not
            # count in it at all (the counter is read right after the call returns).
            start = time.perf_counter()
            before = counter[0]
            ibl.bake(size=128, quiet=True)
            during = counter[0] - before
            seconds = time.perf_counter() - start
        finally:
            stop.set()
            thread.join()
            sys.setswitchinterval(interval)
        self.assertGreater(seconds, 0.05)
        self.assertGreater(during, per_20ms, f"{during} counts in a {seconds:.2f} s bake")


if __name__ == "__main__":
    unittest.main()
