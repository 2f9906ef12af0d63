#!/usr/bin/env python3
"""Renders mutated copies of the shipped scenes, small and short, and keeps
every one that crashes, hangs or puts a value that is not finite in its
image. The libFuzzer targets (tests/fuzz/run.sh) stop at the scene and its
acceleration structures; this goes on through the integrators.

A mutation replaces one to three numbers of a scene with an extreme (0,
-1, 1e-30, 3e38, 1e-45, 2^31, ...), so the scenes stay well formed and most
mutants render. An exit code other than 0 (rendered), 1 (a runtime error)
and 2 (an input error) is a failure, as is a timeout or a non-finite pixel.

  python3 tests/fuzz/mutate_renders.py LANTERN SECONDS [SEED] [OUT_DIR]

LANTERN is the lantern binary; failing mutants go to OUT_DIR (default:
./mutants), each with the command that failed at its top.
"""
import glob
import os
import random
import re
import subprocess
import sys
import time

lantern, seconds = sys.argv[1], float(sys.argv[2])
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
out_dir = sys.argv[4] if len(sys.argv) > 4 else "mutants"
src = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
scenes = sorted(glob.glob(os.path.join(src, "scenes", "*.pbrt")))
reals = ["0", "-1", "1e-30", "1e30", "1e-8", "3e38", "-3e38", "1e-45", "0.999999", "1.000001", "-0", "65536",
         "2", "0.5", "1e8", "-1e-8"]
integers = ["0", "-1", "1", "2", "1000000", "2147483647", "-2147483648"]
integrators = ["path", "bdpt", "vcm", "lt", "bpm", "ppm", "path --guide", "path --guide --guide-distribution quadtree", "bdpt --guide-light", "bdpt --spectral",
               "path --sampler independent"]
number = re.compile(r"(?<![\w.])-?\d+\.?\d*(?:e-?\d+)?(?![\w.])")
work = os.path.join(out_dir, "work")
os.makedirs(work, exist_ok=True)


def mutate(text):
    for _ in range(rng.randint(1, 3)):
        found = list(number.finditer(text))
        if not found:
            break
        m = rng.choice(found)
        is_int = not re.search(r"[.e]", m.group(0))
        value = rng.choice(integers if is_int and rng.random() < 0.7 else reals)
        text = text[:m.start()] + value + text[m.end():]
    return text


def finite_image(path):
    """Whether the image reads and every pixel is finite (an image that
    cannot be read after a render that said it wrote one fails too)."""
    r = subprocess.run([lantern, "compare", path, path], capture_output=True, text=True)
    m = re.search(r"nonfinite_pixels (\d+)", r.stdout)
    return r.returncode == 0 and m is not None and m.group(1) == "0"


start, runs, failures = time.time(), 0, 0
while time.time() - start < seconds:
    scene = rng.choice(scenes)
    text = mutate(open(scene).read())
    mutant = os.path.join(work, "mutant.pbrt")
    with open(mutant, "w") as f:
        f.write(text)
    image = os.path.join(work, "image.exr")
    if os.path.exists(image):
        os.remove(image)  # (so that a stale image is never checked)
    cmd = [lantern, "render", mutant, "--resolution", "12", "9", "--spp", "2", "-q", "--integrator"]
    cmd += rng.choice(integrators).split() + ["-o", image]
    try:  # (the shipped scenes read no other files)
        code = subprocess.run(cmd, capture_output=True, timeout=120).returncode
    except subprocess.TimeoutExpired:
        code = "timeout"
    runs += 1
    failed = code not in (0, 1, 2) or (code == 0 and not finite_image(image))
    if failed:
        failures += 1
        keep = os.path.join(out_dir, "%s-%d.pbrt" % (os.path.basename(scene)[:-5], runs))
        with open(keep, "w") as f:
            f.write("# %s (exit %s, from %s)\n" % (" ".join(cmd[2:]), code, os.path.basename(scene)) + text)
        print("failed: exit %s, %s" % (code, keep), flush=True)
print("%d mutants rendered, %d failed" % (runs, failures))
sys.exit(1 if failures else 0)
