"""Scenes built from Python and images in and out."""
import numpy as np
import pytest

import lantern


def test_numbers_are_written_exactly():
    rng = np.random.default_rng(3)
    values = np.concatenate([rng.standard_normal(1000) * 10.0 ** rng.integers(-30, 30, 1000), [0.1, 1e-300, -0.0]])
    text = lantern.format_numbers(values)
    assert np.array_equal(np.array([float(w) for w in text.split()]), values)
    assert lantern.format_numbers(np.array([1, -2, 3], dtype=np.int32)) == "1 -2 3"
    with pytest.raises(ValueError, match="not finite"):
        lantern.format_numbers([1.0, float("nan")])


def test_builder_mesh_equals_the_same_scene_as_text(tmp_path):
    # A NumPy mesh through the builder and the same mesh written by hand in
    # a file: the same scene, so the same image bit for bit.
    points = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float64) * 0.8
    indices = np.array([[0, 1, 2], [0, 2, 3]])
    b = lantern.SceneBuilder()
    b.look_at((0, 0, 3), (0, 0, 0), (0, 1, 0)).camera("perspective", {"fov": 40.0})
    b.film("rgb", {"integer xresolution": 24, "integer yresolution": 24})
    b.world_begin()
    b.light_source("point", {"point3 from": (0, 0, 2), "rgb I": (4, 4, 4)})
    b.attribute_begin().material("diffuse", {"rgb reflectance": (0.2, 0.6, 0.3)})
    b.triangle_mesh(points, indices)
    b.attribute_end()
    path = b.save(tmp_path / "built.pbrt")
    hand = tmp_path / "hand.pbrt"
    hand.write_text(
        'LookAt 0 0 3  0 0 0  0 1 0\nCamera "perspective" "float fov" [ 40 ]\n'
        'Film "rgb" "integer xresolution" [ 24 ] "integer yresolution" [ 24 ]\nWorldBegin\n'
        'LightSource "point" "point3 from" [ 0 0 2 ] "rgb I" [ 4 4 4 ]\n'
        'AttributeBegin\nMaterial "diffuse" "rgb reflectance" [ 0.2 0.6 0.3 ]\n'
        'Shape "trianglemesh" "point3 P" [ -0.8 -0.8 0 0.8 -0.8 0 0.8 0.8 0 -0.8 0.8 0 ] '
        '"integer indices" [ 0 1 2 0 2 3 ]\nAttributeEnd\n'
    )
    a = lantern.render(b.build(), spp=4, seed=2).image
    c = lantern.render(lantern.load_scene(str(hand)), spp=4, seed=2).image
    assert np.array_equal(a, c)
    assert a.max() > 0  # the quad is lit: the comparison is of something
    assert lantern.load_scene(str(path)).info["triangles"] == 2


def test_builder_reports_the_parsers_errors():
    b = lantern.SceneBuilder().world_begin().shape("spheer", {"float radius": 1})
    with pytest.raises(lantern.SceneError, match="<SceneBuilder>:2:.*spheer"):
        b.build()
    with pytest.raises(TypeError, match="float radius.*'big'"):
        lantern.SceneBuilder().shape("sphere", {"float radius": "big"})
    with pytest.raises(TypeError, match="pbrt type"):
        lantern.SceneBuilder().shape("sphere", {"radius": [1, 2]})


def test_scene_settings_and_info(cornell_box):
    s = cornell_box.settings
    assert s["resolution"] == (512, 512) and s["spp"] == 64 and s["maxdepth"] == 10 and s["integrator"] == "path"
    assert cornell_box.info["lights"] >= 1 and cornell_box.info["triangles"] > 0


def test_images_round_trip_and_compare(tmp_path):
    rng = np.random.default_rng(1)
    image = rng.random((5, 7, 3), dtype=np.float32) * 4
    lantern.write_image(str(tmp_path / "a.exr"), image, [("lantern:note", "x")])
    back = lantern.read_image(str(tmp_path / "a.exr"))
    assert np.array_equal(back, image)
    assert dict(lantern.image_metadata(str(tmp_path / "a.exr")))["lantern:note"] == "x"
    m = lantern.compare(image * 1.1, image)
    expected_relmse = np.mean((0.1 * image.astype(np.float64)) ** 2 / (image.astype(np.float64) ** 2 + 1e-2))
    assert m["relmse"] == pytest.approx(expected_relmse, rel=1e-6)
    assert m["ratio"] == pytest.approx((1.1, 1.1, 1.1), rel=1e-5)
    assert m["psnr"] == pytest.approx(10 * np.log10(image.max() ** 2 / np.mean((0.1 * image.astype(np.float64)) ** 2)), rel=1e-5)
    with pytest.raises(ValueError, match="shape"):
        lantern.compare(np.zeros((4, 4)), np.zeros((4, 4)))
    with pytest.raises(ValueError, match="differ in size"):
        lantern.compare(np.zeros((4, 4, 3)), np.zeros((4, 5, 3)))


def test_metrics_closed_forms_and_the_command_lines_json(tmp_path, lantern_binary):
    import json
    import subprocess

    rng = np.random.default_rng(5)
    ref = rng.random((100, 200, 3)).astype(np.float32)
    image = ref * np.float32(1.05)
    image[7, 9] = 1000.0  # two fireflies: 0.01% of 20000 pixels is 2
    image[50, 150] = 500.0
    m = lantern.compare(image, ref)
    r64, i64 = ref.astype(np.float64), image.astype(np.float64)
    rel = (i64 - r64) ** 2 / (r64 ** 2 + 1e-2)
    assert m["relmse"] == pytest.approx(rel.mean(), rel=1e-9)
    # Robust: the two worst pixels left out; what remains is the 5% error.
    per_pixel = rel.mean(axis=2).ravel()
    assert m["robust_excluded_pixels"] == 2
    assert m["relmse_robust"] == pytest.approx(np.sort(per_pixel)[:-2].mean(), rel=1e-9)
    assert m["relmse_robust"] < m["relmse"] / 100
    # pbrt-v4's per-channel MSE and MRSE: (a - r)^2 and (a - r)^2 / (r + 0.01)^2.
    assert m["pbrt_mrse"] == pytest.approx(tuple(((i64 - r64) ** 2 / (r64 + 0.01) ** 2).mean(axis=(0, 1))), rel=1e-9)
    assert m["pbrt_mse"] == pytest.approx(tuple(((i64 - r64) ** 2).mean(axis=(0, 1))), rel=1e-9)
    lantern.write_image(str(tmp_path / "a.exr"), image)
    lantern.write_image(str(tmp_path / "r.exr"), ref)
    out = subprocess.run([lantern_binary, "compare", "--json", str(tmp_path / "a.exr"), str(tmp_path / "r.exr"),
                          "--error-image", str(tmp_path / "err.exr"), "--error-scale", "0.01"],
                         check=True, capture_output=True, text=True).stdout
    j = json.loads(out)
    for key in ("mse", "relmse", "relmse_robust", "mae", "psnr"):
        assert j[key] == pytest.approx(m[key], rel=1e-12), key
    assert tuple(j["pbrt_mrse"]) == pytest.approx(m["pbrt_mrse"], rel=1e-12)
    # The error map has its legend below: 10 rows from blue (0) to red (the scale).
    err = lantern.read_image(str(tmp_path / "err.exr"))
    assert err.shape == (110, 200, 3)
    assert tuple(err[105, 0]) == (0.0, 0.0, 1.0) and tuple(err[105, -1]) == (1.0, 0.0, 0.0)
    assert tuple(err[7, 9]) == (1.0, 0.0, 0.0)  # the firefly: red
    identical = json.loads(subprocess.run([lantern_binary, "compare", "--json", str(tmp_path / "r.exr"),
                                           str(tmp_path / "r.exr")], check=True, capture_output=True,
                                          text=True).stdout)
    assert identical["mse"] == 0 and identical["psnr"] is None
