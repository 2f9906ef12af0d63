"""Lantern from Python: load or build pbrt-v4 scenes, render them with the
command line's options, and get the image as a NumPy array (docs/python.md).

    import lantern
    scene = lantern.load_scene("scenes/cornell-box.pbrt")
    result = lantern.render(scene, integrator="bdpt", spp=64)
    result.image        # (height, width, 3) float32, linear
    result.stats        # what `lantern render --stats` writes, as a dict
"""
from ._lantern import (  # noqa: F401
    Progress,
    RenderResult,
    RenderSession,
    Scene,
    SceneError,
    SceneWarning,
    compare,
    format_numbers,
    image_metadata,
    load_scene,
    load_scene_from_string,
    read_image,
    relative_error_image,
    render,
    version,
    write_image,
)
from .builder import SceneBuilder  # noqa: F401

__version__ = version().split()[1]
