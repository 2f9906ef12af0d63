"""Rendering from Python: the same image as the command line for the same
options, a closed-form value, the image handed over without a copy,
progress, cancelling and Ctrl-C."""
import json
import os
import signal
import subprocess
import threading

import numpy as np
import pytest

import lantern


def test_render_equals_the_command_line_bit_for_bit(cornell_box, lantern_binary, tmp_path):
    # The keyword arguments mean what the command line's options mean: the
    # same settings give the same image, bit for bit (renders are
    # deterministic for a seed, whatever the thread count).
    options = dict(integrator="bdpt", spp=4, maxdepth=4, seed=7, resolution=(48, 40), sampler="halton")
    result = lantern.render(cornell_box, **options)
    exr = tmp_path / "cli.exr"
    subprocess.run([lantern_binary, "render", cornell_box.path, "-q", "-o", str(exr), "--integrator", "bdpt",
                    "--spp", "4", "--maxdepth", "4", "--seed", "7", "--resolution", "48", "40", "--sampler",
                    "halton"], check=True)
    cli = lantern.read_image(str(exr))
    assert result.image.shape == (40, 48, 3)
    assert np.array_equal(result.image, cli)
    # ... and a different seed gives a different image (the comparison can fail).
    other = lantern.render(cornell_box, **dict(options, seed=8))
    assert not np.array_equal(other.image, cli)


def test_guide_distribution_means_the_flag_of_that_name(cornell_box, lantern_binary, tmp_path):
    # guide_distribution="vmm" (the default) renders what
    # --guide-distribution vmm renders, bit for bit, and another image than
    # the quadtree's; a word that is neither is refused.
    options = dict(integrator="path", spp=8, seed=3, resolution=(32, 32), guide=True)
    lobes = lantern.render(cornell_box, guide_distribution="vmm", **options)
    exr = tmp_path / "lobes.exr"
    subprocess.run([lantern_binary, "render", cornell_box.path, "-q", "-o", str(exr), "--integrator", "path",
                    "--spp", "8", "--seed", "3", "--resolution", "32", "32", "--guide", "--guide-distribution",
                    "vmm"], check=True)
    assert np.array_equal(lobes.image, lantern.read_image(str(exr)))
    assert np.array_equal(lobes.image, lantern.render(cornell_box, **options).image)
    assert not np.array_equal(lobes.image, lantern.render(cornell_box, guide_distribution="quadtree", **options).image)
    with pytest.raises(ValueError, match="guide distribution"):
        lantern.render(cornell_box, guide_distribution="lobes", **options)


def test_guide_stop_means_the_flag_of_that_name(cornell_box, lantern_binary, tmp_path):
    # guide_stop="never" renders what --guide-stop never renders, bit for
    # bit; on the Cornell box, where the guide does not pay, the default
    # stops it after the third iteration and renders another image; a word
    # that is neither is refused.
    options = dict(integrator="path", spp=32, seed=1, resolution=(64, 48), guide=True)
    kept = lantern.render(cornell_box, guide_stop="never", collect_stats=True, **options)
    exr = tmp_path / "kept.exr"
    subprocess.run([lantern_binary, "render", cornell_box.path, "-q", "-o", str(exr), "--integrator", "path",
                    "--spp", "32", "--seed", "1", "--resolution", "64", "48", "--guide", "--guide-stop", "never"],
                   check=True)
    assert np.array_equal(kept.image, lantern.read_image(str(exr)))
    assert kept.stats["guiding"]["stopped_after"] == -1
    stopped = lantern.render(cornell_box, collect_stats=True, **options)
    assert stopped.stats["guiding"]["stopped_after"] == 2
    assert not np.array_equal(stopped.image, kept.image)
    with pytest.raises(ValueError, match="guide_stop"):
        lantern.render(cornell_box, guide_stop="sometimes", **options)


def test_a_render_region_is_the_films_own_crop(cornell_box):
    # cropwindow, pixelbounds and pixel render what the Film's "cropwindow"
    # and "pixelbounds" render, bit for bit, as the command line's flags of
    # those names do (a crop is the whole image's part in distribution:
    # tests/film_crop_test.cpp).
    text = open(cornell_box.path).read()
    assert 'Film "rgb"' in text

    def film_with(extra):
        return lantern.load_scene_from_string(text.replace('Film "rgb"', 'Film "rgb" ' + extra),
                                              base_dir=os.path.dirname(cornell_box.path))

    options = dict(spp=4, resolution=(48, 40), seed=3)
    bounds = lantern.render(cornell_box, pixelbounds=(10, 20, 30, 38), **options).image
    assert bounds.shape == (8, 10, 3)
    assert np.array_equal(bounds, lantern.render(film_with('"integer pixelbounds" [10 20 30 38]'), **options).image)
    crop = lantern.render(cornell_box, cropwindow=(0.5, 1.0, 0.25, 0.5), **options).image
    assert crop.shape == (10, 24, 3)
    assert np.array_equal(crop, lantern.render(film_with('"float cropwindow" [0.5 1 0.25 0.5]'), **options).image)
    pixel = lantern.render(cornell_box, pixel=(7, 9), **options).image
    assert np.array_equal(pixel, lantern.render(film_with('"integer pixelbounds" [7 8 9 10]'), **options).image)
    assert not np.array_equal(pixel, lantern.render(film_with('"integer pixelbounds" [8 9 9 10]'), **options).image)
    with pytest.raises(ValueError, match="cropwindow"):
        lantern.render(cornell_box, cropwindow=(0.5, 0.2, 0, 1), **options)


def test_lit_sphere_has_its_albedo():
    # A convex diffuse sphere under a uniform sky of radiance 1 sees only the
    # sky: its outgoing radiance is its albedo, 0.5, everywhere (closed form);
    # the sky itself is 1.
    b = lantern.SceneBuilder()
    b.look_at((0, 0, 4), (0, 0, 0), (0, 1, 0))
    b.camera("perspective", {"float fov": 30})
    b.film("rgb", {"integer xresolution": 32, "integer yresolution": 32})
    b.world_begin()
    b.light_source("infinite", {"rgb L": (1, 1, 1)})
    b.material("diffuse", {"rgb reflectance": (0.5, 0.5, 0.5)})
    b.shape("sphere", {"float radius": 1})
    result = lantern.render(b.build(), spp=64, maxdepth=2, seed=1)
    centre = result.image[12:20, 12:20]
    corner = result.image[:3, :3]
    assert centre.mean() == pytest.approx(0.5, rel=0.02)
    assert corner.mean() == pytest.approx(1.0, rel=1e-3)


def test_image_is_handed_over_without_a_copy(cornell_box):
    result = lantern.render(cornell_box, spp=1, resolution=(16, 8))
    image = result.image
    assert image.dtype == np.float32 and image.shape == (8, 16, 3)
    assert not image.flags.owndata  # the renderer's buffer, owned through a capsule
    assert image.flags.c_contiguous and image.flags.writeable
    view = result.image
    view[0, 0, 0] = 123.0  # the same memory
    assert image[0, 0, 0] == 123.0


def test_adaptive_budget_is_the_command_lines(cornell_box, lantern_binary, tmp_path):
    # adaptive=True is --adaptive: the mean budget spent to a block, not
    # evenly, and the same image as the command line's.
    result = lantern.render(cornell_box, adaptive=True, spp=48, resolution=(32, 32), seed=3)
    assert 48 * 32 * 32 - 16 * 16 < result.samples <= 48 * 32 * 32
    assert result.stats["max_spp"] > result.stats["min_spp"]
    exr = tmp_path / "adaptive.exr"
    subprocess.run([lantern_binary, "render", cornell_box.path, "-q", "-o", str(exr), "--adaptive", "--spp", "48",
                    "--resolution", "32", "32", "--seed", "3"], check=True)
    assert np.array_equal(result.image, lantern.read_image(str(exr)))


def test_stats_are_the_command_lines(cornell_box, lantern_binary, tmp_path):
    stats_file = tmp_path / "py.json"
    result = lantern.render(cornell_box, spp=2, resolution=(16, 16), stats=str(stats_file), output=str(tmp_path / "py.exr"))
    cli_stats = tmp_path / "cli.json"
    subprocess.run([lantern_binary, "render", cornell_box.path, "-q", "-o", str(tmp_path / "cli.exr"), "--spp", "2",
                    "--resolution", "16", "16", "--stats", str(cli_stats)], check=True)
    cli = json.loads(cli_stats.read_text())
    assert set(result.stats) == set(cli)
    assert json.loads(stats_file.read_text())["samples"] == result.samples == cli["samples"] == 16 * 16 * 2
    assert result.stats["settings"] == cli["settings"]
    header = dict(lantern.image_metadata(str(tmp_path / "py.exr")))
    assert header["lantern:samples"] == str(16 * 16 * 2)
    assert header["lantern:command"].startswith("python3")


def test_progress_reports_and_a_false_return_cancels(cornell_box):
    seen = []

    def progress(p):
        seen.append(p.fraction)
        return len(seen) < 3

    result = lantern.render(cornell_box, time=60, resolution=(64, 64), progress=progress)
    assert result.interrupted
    assert result.seconds < 30
    assert len(seen) >= 3 and seen == sorted(seen)


def test_a_callback_that_returns_nothing_lets_the_render_finish(cornell_box):
    calls = []
    result = lantern.render(cornell_box, spp=16, resolution=(64, 64), progress=lambda p: calls.append(p.spp))
    assert not result.interrupted and result.spp == 16
    assert calls and calls[-1] == pytest.approx(16.0)


def test_an_exception_in_progress_cancels_and_is_raised(cornell_box):
    def progress(p):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        lantern.render(cornell_box, time=60, resolution=(64, 64), progress=progress)


def test_ctrl_c_writes_the_image_so_far_then_raises(cornell_box, tmp_path):
    out = tmp_path / "interrupted.exr"
    # Ctrl-C once the render has samples (before, the pilot that chooses
    # the split may still run: the image so far would have none).
    rendering = threading.Event()

    def interrupt():
        rendering.wait(30)
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Thread(target=interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        lantern.render(cornell_box, time=60, resolution=(64, 64), output=str(out),
                       progress=lambda p: rendering.set() if p.spp > 0 else None)
    timer.join()
    header = dict(lantern.image_metadata(str(out)))
    assert header["lantern:interrupted"] == "true"
    assert int(header["lantern:samples"]) > 0


def test_session_snapshots_grow_and_cancel_stops(cornell_box):
    session = lantern.RenderSession(cornell_box, time=60, resolution=(32, 32))
    assert session.settings["integrator"] == "path"
    session.start()
    assert session.wait(timeout=0.3) is None  # still rendering
    first = session.progress.samples_done
    snapshot = session.snapshot()
    assert snapshot.shape == (32, 32, 3)
    session.cancel()
    result = session.wait()
    assert result.interrupted and session.done
    assert result.samples >= first
    assert session.wait().samples == result.samples


def test_leaving_a_with_block_stops_the_render(cornell_box):
    with lantern.RenderSession(cornell_box, time=60, resolution=(32, 32)) as session:
        session.start()
    assert session.done


def test_bad_input_raises_clear_errors(tmp_path, cornell_box):
    bad = tmp_path / "bad.pbrt"
    bad.write_text('WorldBegin\nShape "sphere" "float radius" [ one ]\n')
    with pytest.raises(lantern.SceneError, match=r"bad\.pbrt:2:"):
        lantern.load_scene(str(bad))
    with pytest.raises(TypeError, match="unknown render option 'sp'"):
        lantern.render(cornell_box, sp=4)
    with pytest.raises(ValueError, match="integrator"):
        lantern.render(cornell_box, integrator="pathh")
    with pytest.raises(ValueError, match="spp"):
        lantern.render(cornell_box, spp=0)
    with pytest.raises(ValueError, match="one budget"):
        lantern.render(cornell_box, spp=4, time=1)
    with pytest.raises(ValueError, match="roulette"):
        lantern.render(cornell_box, spp=1, roulette=0)
    with pytest.raises(ValueError, match="light_subpaths"):
        lantern.render(cornell_box, spp=1, integrator="bdpt", light_subpaths=0.005)
    with pytest.raises(ValueError, match="light_subpaths"):
        lantern.render(cornell_box, spp=1, integrator="bdpt", light_subpaths="sometimes")
    with pytest.raises(ValueError, match="light_subpaths"):
        lantern.render(cornell_box, spp=1, integrator="bdpt", light_subpaths=0.0099999)
    with pytest.raises(ValueError, match="light_subpaths"):
        lantern.render(cornell_box, spp=1, integrator="bdpt", light_subpaths=True)
    with pytest.raises(ValueError, match="light choice"):
        lantern.render(cornell_box, spp=1, integrator="bdpt", light_choice="bvh")
    with pytest.raises(ValueError, match="merging"):
        lantern.render(cornell_box, spp=1, integrator="vcm", merging="off")
    for bad_split in (3, 4.0, "four", True, 32):
        with pytest.raises(ValueError, match="split"):
            lantern.render(cornell_box, spp=1, split=bad_split)
    with pytest.raises(RuntimeError, match="no-such-folder"):
        lantern.render(cornell_box, spp=1, output=str(tmp_path / "no-such-folder" / "x.exr"))


def test_light_choice(source_dir):
    # How light subpaths choose their light: given, or (auto) the pilot's
    # choice on a scene of several lights (the prism's sky and spot), under
    # a time budget (a render of a few samples is too small for the pilot).
    prism = lantern.load_scene(str(source_dir / "scenes" / "prism.pbrt"))
    chosen = lantern.render(prism, time=0.1, resolution=(48, 36), integrator="bdpt", collect_stats=True)
    choice = chosen.stats["light_subpaths"]["light_choice"]
    assert choice["chosen"] != "power" and len(choice["probabilities"]) == 2
    given = lantern.render(prism, spp=1, resolution=(48, 36), integrator="bdpt", light_choice="power",
                           collect_stats=True)
    assert "light_choice" not in given.stats["light_subpaths"]


def test_merging(cornell_box):
    # vcm merges with merging="on"; with "auto" too where the render is too
    # small for the merge pilot, which then reports nothing.
    for merging in ("on", "auto"):
        r = lantern.render(cornell_box, spp=4, resolution=(16, 16), integrator="vcm", merging=merging,
                           collect_stats=True)
        assert r.stats["vcm"]["merges"] > 0
        assert "merging" not in r.stats


def test_split_camera_samples(cornell_box):
    # Paths per camera sample: a count, or the pilot's choice; --stats says which.
    four = lantern.render(cornell_box, spp=8, resolution=(16, 16), split=4, collect_stats=True)
    assert four.stats["split"]["paths_per_camera_sample"] == 4
    chosen = lantern.render(cornell_box, spp=8, resolution=(16, 16), split="auto", collect_stats=True)
    assert chosen.stats["split"]["paths_per_camera_sample"] == 1  # (too small a render for the pilot)


def test_warnings_reach_python(tmp_path):
    # A Film parameter pbrt knows (the spectral film's) and Lantern's RGB film does not use.
    text = 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "integer nbuckets" [ 16 ]\nWorldBegin\n'
    with pytest.warns(lantern.SceneWarning, match="nbuckets"):
        scene = lantern.load_scene_from_string(text)
    assert any("nbuckets" in w for w in scene.warnings)


def test_unknown_parameters_are_errors_unless_lenient(tmp_path):
    text = 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "float unknownthing" [ 1 ]\nWorldBegin\n'
    with pytest.raises(lantern.SceneError, match=r"<string>:1:68: .*unknownthing"):
        lantern.load_scene_from_string(text)
    with pytest.warns(lantern.SceneWarning, match="unknownthing"):
        scene = lantern.load_scene_from_string(text, lenient=True)
    assert any("unknownthing" in w for w in scene.warnings)


def test_memory_layouts_load_the_same_instances_and_bad_words_raise():
    text = ('Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ]\nWorldBegin\n'
            'LightSource "infinite" "rgb L" [ 1 1 1 ]\nObjectBegin "s"\nShape "sphere" "float radius" 0.3\nObjectEnd\n'
            'Translate 0 0 3\nObjectInstance "s"\nTranslate 0.4 0 0\nObjectInstance "s"\n')
    fast = lantern.load_scene_from_string(text, memory_layout="fast")
    compact = lantern.load_scene_from_string(text, memory_layout="compact")
    a = lantern.render(fast, spp=4, resolution=(8, 8))
    b = lantern.render(compact, spp=4, resolution=(8, 8))
    assert abs(float(a.image.mean()) - float(b.image.mean())) < 1e-3 * float(a.image.mean())
    assert float(a.image.min()) < 0.9  # the spheres are in view
    with pytest.raises(ValueError, match="memory layout"):
        lantern.load_scene_from_string(text, memory_layout="tiny")


def test_a_kept_checkpoint_extends_to_a_larger_budget_and_info_reads_it(cornell_box, lantern_binary, tmp_path):
    ckpt = str(tmp_path / "r.ckpt")
    options = dict(integrator="path", sampler="halton", resolution=(24, 16), seed=4)
    first = lantern.render(cornell_box, spp=16, checkpoint_file=ckpt, keep_checkpoint=True, **options)
    assert not first.interrupted
    info = subprocess.run([lantern_binary, "info", ckpt], check=True, capture_output=True, text=True).stdout
    assert f"samples {24 * 16 * 16}\n" in info and "integrator path\n" in info and "budget spp 16\n" in info
    extended = lantern.render(cornell_box, spp=48, checkpoint_file=ckpt, resume=True, **options)
    straight = lantern.render(cornell_box, spp=48, **options)
    assert extended.resumed_samples == 24 * 16 * 16
    assert np.array_equal(extended.image, straight.image)
