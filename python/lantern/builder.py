"""Scenes built from Python, one pbrt-v4 directive per call.

The builder writes the scene's pbrt text and `build()` gives it to the same
parser and scene builder that read scene files, so a scene made here has
exactly the meaning (defaults, errors, warnings) its text has in a file, and
`save()` writes a file the command line renders to the same image (when it
is saved where its relative file names resolve: base_dir, or the working
directory). Numbers
are written as the shortest decimals that read back exactly, in C++
(lantern.format_numbers), so NumPy meshes of millions of vertices cost
seconds, not minutes.

    b = lantern.SceneBuilder()
    b.look_at((0, 0, 5), (0, 0, 0), (0, 1, 0))
    b.camera("perspective", {"float fov": 40})
    b.film("rgb", {"integer xresolution": 64, "integer yresolution": 64})
    b.world_begin()
    b.light_source("infinite", {"rgb L": (1, 1, 1)})
    b.shape("sphere", {"float radius": 1})
    scene = b.build()

Parameters are a dict of pbrt's "type name" keys ("rgb reflectance",
"point3 P", "integer indices", "texture reflectance", ...). A key without a
type takes one from a scalar value: bool, integer, float or string.
"""
import os

from ._lantern import format_numbers, load_scene_from_string

__all__ = ["SceneBuilder"]

_SCALAR_TYPES = ((bool, "bool"), (int, "integer"), (float, "float"), (str, "string"))


def _quoted(s):
    s = str(s)
    if '"' in s or "\n" in s:
        raise ValueError(f"pbrt strings cannot hold a double quote or a line break: {s!r}")
    return '"' + s + '"'


def _values(kind, value):
    """The bracketed value list of one parameter."""
    if kind == "bool":
        items = value if isinstance(value, (list, tuple)) else [value]
        return "[ " + " ".join('"true"' if v else '"false"' for v in items) + " ]"
    if kind in ("string", "texture") or (kind == "spectrum" and isinstance(value, str)):
        items = [value] if isinstance(value, str) else value
        return "[ " + " ".join(_quoted(v) for v in items) + " ]"
    if kind == "integer":
        import numpy as np

        array = np.asarray(value)
        if array.dtype.kind == "f":
            if not np.all(array == np.round(array)):
                raise ValueError(f"integer parameter with non-integer values: {value!r}")
            array = array.astype(np.int64)
        return "[ " + format_numbers(array) + " ]"
    return "[ " + format_numbers(value) + " ]"


def _parameters(params):
    if not params:
        return ""
    words = []
    for key, value in params.items():
        parts = key.split()
        if len(parts) == 2:
            kind, name = parts
        elif len(parts) == 1:
            kind = next((t for cls, t in _SCALAR_TYPES if isinstance(value, cls)), None)
            if kind is None:
                raise TypeError(
                    f"parameter {key!r}: give its pbrt type in the key (\"rgb {key}\", \"point3 {key}\", ...); "
                    f"only a single bool, integer, float or string value implies one"
                )
            name = key
        else:
            raise ValueError(f"parameter key {key!r}: expected \"type name\"")
        try:
            values = _values(kind, value)
        except TypeError:
            raise TypeError(f"parameter \"{kind} {name}\": expected numbers, got {value!r}") from None
        words.append(f"{_quoted(kind + ' ' + name)} {values}")
    return " " + " ".join(words)


def _numbers(*xs):
    return format_numbers([float(x) for x in xs])


class SceneBuilder:
    """A pbrt-v4 scene, directive by directive (the methods are pbrt's
    directives, in snake case)."""

    def __init__(self):
        self._lines = []

    # --- anything ---------------------------------------------------------
    def directive(self, name, *args, params=None):
        """Any directive: its name, its quoted arguments, its parameters."""
        self._lines.append(" ".join([name] + [_quoted(a) for a in args]) + _parameters(params))
        return self

    def text(self):
        return "\n".join(self._lines) + "\n"

    def save(self, path):
        with open(path, "w") as f:
            f.write(self.text())
        return path

    def build(self, base_dir="", name="<SceneBuilder>", **load_options):
        """The scene, loaded as lantern.load_scene_from_string loads text;
        relative file names resolve against base_dir (default: the working
        directory)."""
        return load_scene_from_string(self.text(), name=name, base_dir=base_dir, **load_options)

    # --- transformations ----------------------------------------------------
    def identity(self):
        return self._raw("Identity")

    def translate(self, x, y, z):
        return self._raw("Translate " + _numbers(x, y, z))

    def scale(self, x, y, z):
        return self._raw("Scale " + _numbers(x, y, z))

    def rotate(self, degrees, x, y, z):
        return self._raw("Rotate " + _numbers(degrees, x, y, z))

    def look_at(self, eye, target, up):
        return self._raw("LookAt " + _numbers(*eye, *target, *up))

    def transform(self, m):
        """pbrt's Transform: 16 numbers, column after column as pbrt reads them."""
        return self._raw("Transform [ " + format_numbers(m) + " ]")

    def concat_transform(self, m):
        return self._raw("ConcatTransform [ " + format_numbers(m) + " ]")

    def coordinate_system(self, name):
        return self.directive("CoordinateSystem", name)

    def coord_sys_transform(self, name):
        return self.directive("CoordSysTransform", name)

    def active_transform(self, which):
        """"StartTime", "EndTime" or "All"."""
        return self._raw("ActiveTransform " + which)

    def transform_times(self, start, end):
        return self._raw("TransformTimes " + _numbers(start, end))

    def reverse_orientation(self):
        return self._raw("ReverseOrientation")

    # --- rendering options --------------------------------------------------
    def camera(self, kind, params=None):
        return self.directive("Camera", kind, params=params)

    def film(self, kind, params=None):
        return self.directive("Film", kind, params=params)

    def sampler(self, kind, params=None):
        return self.directive("Sampler", kind, params=params)

    def integrator(self, kind, params=None):
        return self.directive("Integrator", kind, params=params)

    def pixel_filter(self, kind, params=None):
        return self.directive("PixelFilter", kind, params=params)

    def color_space(self, name):
        return self.directive("ColorSpace", name)

    def option(self, params):
        return self.directive("Option", params=params)

    def world_begin(self):
        return self._raw("WorldBegin")

    # --- the world ----------------------------------------------------------
    def attribute_begin(self):
        return self._raw("AttributeBegin")

    def attribute_end(self):
        return self._raw("AttributeEnd")

    def attribute(self, target, params):
        return self.directive("Attribute", target, params=params)

    def material(self, kind, params=None):
        return self.directive("Material", kind, params=params)

    def make_named_material(self, name, params):
        return self.directive("MakeNamedMaterial", name, params=params)

    def named_material(self, name):
        return self.directive("NamedMaterial", name)

    def texture(self, name, value_type, cls, params=None):
        return self.directive("Texture", name, value_type, cls, params=params)

    def light_source(self, kind, params=None):
        return self.directive("LightSource", kind, params=params)

    def area_light_source(self, kind, params=None):
        return self.directive("AreaLightSource", kind, params=params)

    def shape(self, kind, params=None):
        return self.directive("Shape", kind, params=params)

    def triangle_mesh(self, points, indices, params=None):
        """A "trianglemesh" from arrays: points (n, 3), indices (m, 3)."""
        p = {"point3 P": points, "integer indices": indices}
        p.update(params or {})
        return self.shape("trianglemesh", p)

    def make_named_medium(self, name, params):
        return self.directive("MakeNamedMedium", name, params=params)

    def medium_interface(self, inside, outside=None):
        return self.directive("MediumInterface", inside, inside if outside is None else outside)

    def object_begin(self, name):
        return self.directive("ObjectBegin", name)

    def object_end(self):
        return self._raw("ObjectEnd")

    def object_instance(self, name):
        return self.directive("ObjectInstance", name)

    def include(self, path):
        return self.directive("Include", os.fspath(path))

    def _raw(self, line):
        self._lines.append(line)
        return self
