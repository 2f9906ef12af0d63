# Builds a shipped pbrt-v4 scene in Blender and renders it with Cycles on the
# CPU, for equal-time comparisons (perf/vs-renderers.sh). Run by Blender:
#   blender -b --factory-startup -P perf/cycles/scene_to_cycles.py -- \
#       SCENE.pbrt OUT.exr --time SECONDS | --samples N [--seed S] [--resolution W H]
#       [--guiding] [--no-adaptive]
#
# It reads the subset of pbrt-v4's format the shipped scenes with area and
# environment lights use: LookAt, Scale, Translate, Rotate, Camera
# "perspective" (fov) and "spherical" (equirectangular), Film resolution,
# Integrator maxdepth, Attribute blocks, ReverseOrientation, named and
# inline materials (diffuse, conductor, coateddiffuse, coatedconductor,
# dielectric, thindielectric, diffusetransmission, hair, interface),
# AreaLightSource "diffuse", LightSource "infinite" (a constant colour) and
# "spot", Shape "trianglemesh", "sphere", "disk", "cylinder" and "curve"
# (pbrt_shapes.py makes the last four meshes; a curve is a tube), and
# media (MakeNamedMedium "homogeneous" and "uniformgrid", MediumInterface;
# below). Anything else stops it with the file's line. Materials are
# approximated by Cycles' closures (a conductor as a GGX glossy of a copper
# or grey colour, a thin dielectric as a Fresnel mix of a mirror and a
# transparent surface, hair as a rough surface of its melanin's colour);
# each renderer's error is measured against its own
# converged image, so what matters is that the light has the same paths to
# find, not that the images match.
#
# Media: the camera's medium fills Blender's world volume; a shape whose
# inside is another medium carries that medium as its material's volume
# (Cycles enters it through the shape's front face, as pbrt does through
# its normal's back side), and a uniformgrid becomes a Volume object read
# from an OpenVDB file written here (Debian's python3-openvdb; the grid's
# samples at its voxels' centres, interpolated linearly as pbrt-v4's
# SampledGrid is). sigma_a and sigma_s are Cycles' absorption and
# scattering densities (Volume Absorption of colour 1 - sigma_a / max,
# Volume Scatter of colour sigma_s / max, Henyey-Greenstein g alike). Where
# a shape's inside is vacuum in the camera's medium (the glass ball of the
# volumetric caustic), Cycles' world volume fills the inside too: its
# volumes add up and none subtracts.
#
# Emission: a surface emission shader of strength 1 and colour L, and a
# background of strength 1 and colour L, appear with value L, as pbrt's
# radiance L does; pbrt's area lights emit on the side of their normal only.
import glob
import math
import os
import re
import sys
import time

import bpy
import mathutils

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pbrt_shapes  # noqa: E402 (found beside this script)


def fail(msg):
    print("scene_to_cycles.py: " + msg, file=sys.stderr)
    sys.exit(2)


def tokens(path):
    text = open(path).read()
    line = 1
    for m in re.finditer(r'"[^"]*"|\[|\]|#[^\n]*|[^\s\[\]"#]+|\n', text):
        t = m.group(0)
        if t == "\n":
            line += 1
        elif not t.startswith("#"):
            yield t, line


def parse(path):
    """(directive, args, params, line): args are the bare values after the
    directive, params a dict of "type name" -> list of values."""
    toks = list(tokens(path))
    out, i = [], 0
    while i < len(toks):
        name, line = toks[i]
        if not re.match(r"[A-Z][A-Za-z]*$", name):
            fail("%s:%d: expected a directive, found %s" % (path, line, name))
        i += 1
        args, params = [], {}
        while i < len(toks) and not re.match(r"[A-Z][A-Za-z]*$", toks[i][0]):
            t = toks[i][0]
            if t.startswith('"') and " " in t.strip('"').strip() and len(t.strip('"').split()) == 2:
                key = t.strip('"')
                i += 1
                vals = []
                if toks[i][0] == "[":
                    i += 1
                    while toks[i][0] != "]":
                        vals.append(toks[i][0])
                        i += 1
                    i += 1
                else:
                    vals.append(toks[i][0])
                    i += 1
                params[key.split()[1]] = (key.split()[0], [v.strip('"') for v in vals])
            elif t in "[]":
                i += 1
            else:
                args.append(t.strip('"'))
                i += 1
        out.append((name, args, params, line))
    return out


def nums(params, name, default=None):
    if name not in params:
        return default
    try:
        return [float(v) for v in params[name][1]]
    except ValueError:
        fail('"%s %s" is not a list of numbers (named spectra are not built)' % (params[name][0], name))


def look_at(e, l, u):
    eye, look, up = mathutils.Vector(e), mathutils.Vector(l), mathutils.Vector(u)
    d = (look - eye).normalized()
    right = up.normalized().cross(d).normalized()
    new_up = d.cross(right)
    world_from_camera = mathutils.Matrix(
        ((right.x, new_up.x, d.x, eye.x), (right.y, new_up.y, d.y, eye.y), (right.z, new_up.z, d.z, eye.z), (0, 0, 0, 1)))
    return world_from_camera.inverted()


def material_node_tree(mat, kind, params):
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    if kind == "diffuse":
        b = nt.nodes.new("ShaderNodeBsdfDiffuse")
        b.inputs["Color"].default_value = nums(params, "reflectance", [0.5] * 3) + [1]
    elif kind == "conductor":
        b = nt.nodes.new("ShaderNodeBsdfGlossy")
        b.distribution = "GGX"
        eta = params.get("eta", ("", [""]))[1][0]
        b.inputs["Color"].default_value = (0.95, 0.64, 0.54, 1) if "Cu" in eta else (0.9, 0.9, 0.9, 1)
        r = nums(params, "roughness", [0.0])[0]
        # pbrt-v4 remaps roughness r to alpha sqrt(r); Cycles' alpha is its roughness squared
        b.inputs["Roughness"].default_value = math.sqrt(math.sqrt(r))
    elif kind == "dielectric":
        b = nt.nodes.new("ShaderNodeBsdfGlass")
        b.inputs["IOR"].default_value = nums(params, "eta", [1.5])[0]
        b.inputs["Roughness"].default_value = 0.0
    elif kind == "thindielectric":
        # a sharp reflection by the Fresnel factor, straight through otherwise
        b = nt.nodes.new("ShaderNodeMixShader")
        fresnel = nt.nodes.new("ShaderNodeFresnel")
        fresnel.inputs["IOR"].default_value = nums(params, "eta", [1.5])[0]
        through = nt.nodes.new("ShaderNodeBsdfTransparent")
        mirror = nt.nodes.new("ShaderNodeBsdfGlossy")
        mirror.inputs["Roughness"].default_value = 0.0
        nt.links.new(fresnel.outputs[0], b.inputs[0])
        nt.links.new(through.outputs[0], b.inputs[1])
        nt.links.new(mirror.outputs[0], b.inputs[2])
    elif kind == "diffusetransmission":
        b = nt.nodes.new("ShaderNodeAddShader")
        for k, (name, node_type) in enumerate((("reflectance", "ShaderNodeBsdfDiffuse"),
                                               ("transmittance", "ShaderNodeBsdfTranslucent"))):
            node = nt.nodes.new(node_type)
            node.inputs["Color"].default_value = nums(params, name, [0.25] * 3) + [1]
            nt.links.new(node.outputs[0], b.inputs[k])
    elif kind == "coatedconductor":
        b = nt.nodes.new("ShaderNodeBsdfPrincipled")
        b.inputs["Base Color"].default_value = (0.95, 0.64, 0.54, 1)  # pbrt-v4's default conductor: copper
        b.inputs["Metallic"].default_value = 1.0
        b.inputs["Roughness"].default_value = math.sqrt(math.sqrt(nums(params, "conductor.roughness", [0.0])[0]))
        b.inputs["Clearcoat"].default_value = 1.0
        b.inputs["Clearcoat Roughness"].default_value = math.sqrt(math.sqrt(nums(params, "interface.roughness", [0.0])[0]))
    elif kind == "hair":
        # Cycles' hair BSDF shades curves only, and the fibres are tubes
        # here: a rough dielectric of the colour a fibre's melanin leaves
        # after two crossings (d'Eon et al. 2011's absorption coefficients)
        eu, pheo = nums(params, "eumelanin", [1.3])[0], nums(params, "pheomelanin", [0.0])[0]
        sigma = [eu * e + pheo * p for e, p in zip((0.419, 0.697, 1.37), (0.187, 0.4, 1.05))]
        b = nt.nodes.new("ShaderNodeBsdfPrincipled")
        b.inputs["Base Color"].default_value = [math.exp(-2 * c) for c in sigma] + [1]
        b.inputs["Roughness"].default_value = min(1.0, nums(params, "beta_m", [0.3])[0] * 2)
    elif kind == "interface":
        b = None  # no surface: the material is its volume alone
    elif kind == "coateddiffuse":
        b = nt.nodes.new("ShaderNodeBsdfPrincipled")
        b.inputs["Base Color"].default_value = nums(params, "reflectance", [0.5] * 3) + [1]
        b.inputs["Roughness"].default_value = 1.0
        b.inputs["Specular"].default_value = 0.5
        b.inputs["Clearcoat"].default_value = 1.0
        b.inputs["Clearcoat Roughness"].default_value = math.sqrt(math.sqrt(nums(params, "roughness", [0.0])[0]))
    else:
        fail("material type %s is not built" % kind)
    return nt, b, out


def volume_shader(nt, params, density_socket=None):
    """pbrt-v4's homogeneous coefficients (times a grid's density, from
    density_socket, if given) as Cycles' absorption plus scattering."""
    scale = nums(params, "scale", [1.0])[0]
    sa = [v * scale for v in nums(params, "sigma_a", [1.0, 1.0, 1.0])]
    ss = [v * scale for v in nums(params, "sigma_s", [1.0, 1.0, 1.0])]
    if "Le" in params or "Lescale" in params:
        fail("emissive media are not built")
    add = nt.nodes.new("ShaderNodeAddShader")
    for k, (sigma, node_type) in enumerate(((sa, "ShaderNodeVolumeAbsorption"), (ss, "ShaderNodeVolumeScatter"))):
        node = nt.nodes.new(node_type)
        top = max(sigma)
        colour = [(1 - c / top) if node_type.endswith("Absorption") else c / top for c in sigma] if top > 0 else [0.0] * 3
        node.inputs["Color"].default_value = colour + [1]
        if node_type.endswith("Scatter"):
            node.inputs["Anisotropy"].default_value = nums(params, "g", [0.0])[0]
        if density_socket is None:
            node.inputs["Density"].default_value = top
        else:
            mul = nt.nodes.new("ShaderNodeMath")
            mul.operation = "MULTIPLY"
            mul.inputs[1].default_value = top
            nt.links.new(density_socket, mul.inputs[0])
            nt.links.new(mul.outputs[0], node.inputs["Density"])
        nt.links.new(node.outputs[0], add.inputs[k])
    return add.outputs[0]


def medium_params(media, name, where):
    if name not in media:
        fail('%s: medium "%s" is not defined' % (where, name))
    kind, params, ctm = media[name]
    if kind != "homogeneous":
        fail('%s: a %s medium as a shape\'s inside or the camera\'s is not built (homogeneous only; a uniformgrid '
             'inside an "interface" shape is)' % (where, kind))
    return params


def grid_volume(name, params, ctm, vdb_path):
    """A uniformgrid medium as a Blender Volume object read from a VDB file."""
    import numpy
    try:
        import pyopenvdb
    except ImportError:
        fail("a uniformgrid medium needs OpenVDB's Python module (Debian: python3-openvdb)")
    n = [int(nums(params, k, [1])[0]) for k in ("nx", "ny", "nz")]
    d = nums(params, "density")
    if d is None or len(d) != n[0] * n[1] * n[2]:
        fail('uniformgrid "%s": "density" needs nx * ny * nz values' % name)
    p0, p1 = [mathutils.Vector(nums(params, k, dflt)) for k, dflt in (("p0", [0.0] * 3), ("p1", [1.0] * 3))]
    # pbrt-v4 stores x fastest, then y, then z: values[(z * ny + y) * nx + x]
    a = numpy.array(d, dtype=numpy.float32).reshape(n[2], n[1], n[0]).transpose(2, 1, 0).copy()
    grid = pyopenvdb.FloatGrid()
    grid.copyFromArray(a)
    grid.name = "density"
    voxel = [(p1[k] - p0[k]) / n[k] for k in range(3)]
    # index (i, j, k) -> p0 + (index + 1/2) * voxel, then the medium's
    # transform; OpenVDB's matrices act on row vectors
    index_to_medium = mathutils.Matrix.Translation(p0 + 0.5 * mathutils.Vector(voxel)) @ mathutils.Matrix.Diagonal(voxel + [1.0])
    m = ctm @ index_to_medium
    grid.transform = pyopenvdb.createLinearTransform([[m[c][r] for c in range(4)] for r in range(4)])
    pyopenvdb.write(vdb_path, grids=[grid])
    vol = bpy.data.volumes.new(name)
    vol.filepath = vdb_path
    ob = bpy.data.objects.new(name, vol)
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    attr = nt.nodes.new("ShaderNodeAttribute")
    attr.attribute_name = "density"
    nt.links.new(volume_shader(nt, params, attr.outputs["Fac"]), out.inputs["Volume"])
    ob.data.materials.append(mat)
    return ob


def make_material(state, name_hint, inside=None):
    kind, params = state["material"]
    mat = bpy.data.materials.new(name_hint)
    mat.use_nodes = True
    nt, bsdf, out = material_node_tree(mat, kind, params)
    if inside is not None:
        nt.links.new(volume_shader(nt, inside), out.inputs["Volume"])
    if bsdf is None:
        if state["area"] is not None:
            fail('an area light with the "interface" material is not built')
        return mat
    shader = bsdf.outputs[0]
    if state["area"] is not None:
        L = state["area"]
        em = nt.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = L + [1]
        em.inputs["Strength"].default_value = 1.0
        # one-sided, as pbrt's: no emission seen from the back
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        black = nt.nodes.new("ShaderNodeEmission")
        black.inputs["Strength"].default_value = 0.0
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geo.outputs["Backfacing"], mix.inputs[0])
        nt.links.new(em.outputs[0], mix.inputs[1])
        nt.links.new(black.outputs[0], mix.inputs[2])
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(shader, add.inputs[0])
        nt.links.new(mix.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    nt.links.new(shader, out.inputs["Surface"])
    return mat


def add_mesh(name, verts, faces, mat):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], faces)
    me.update()
    ob = bpy.data.objects.new(name, me)
    ob.data.materials.append(mat)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def quadric_or_curve(kind, params):
    """pbrt-v4's sphere, disk, cylinder or curve as (vertices, faces) in
    its object space, or None for another shape."""
    one = lambda name, default: nums(params, name, [default])[0]
    if kind == "sphere":
        r = one("radius", 1.0)
        return pbrt_shapes.sphere(r, one("zmin", -r), one("zmax", r), one("phimax", 360.0))
    if kind == "disk":
        return pbrt_shapes.disk(one("radius", 1.0), one("innerradius", 0.0), one("height", 0.0), one("phimax", 360.0))
    if kind == "cylinder":
        return pbrt_shapes.cylinder(one("radius", 1.0), one("zmin", -1.0), one("zmax", 1.0), one("phimax", 360.0))
    if kind == "curve":
        P = nums(params, "P")
        if params.get("basis", ("", ["bezier"]))[1][0] != "bezier" or P is None or len(P) != 12:
            fail("curves other than one cubic Bezier segment (four points) are not built")
        w = one("width", 1.0)
        return pbrt_shapes.curve_tube([P[0:3], P[3:6], P[6:9], P[9:12]], one("width0", w), one("width1", w))
    return None


def spot_light(ctm, params):
    """pbrt-v4's spot light as Cycles' (position, direction, light data).
    pbrt's intensity I (W/sr) on the axis is a Cycles spot of power 4 pi I
    W: Cycles gives a point or spot light of power P the intensity
    P / (4 pi) whatever its cone. pbrt's falloff is a smoothstep from
    cos(coneangle) to cos(coneangle - conedeltaangle), Cycles' from the
    cosine of its half angle c over the fraction blend of 1 - c."""
    I = nums(params, "I", [1.0, 1.0, 1.0])
    scale = nums(params, "scale", [1.0])[0]
    cone = nums(params, "coneangle", [30.0])[0]
    delta = nums(params, "conedeltaangle", [5.0])[0]
    frm = ctm @ mathutils.Vector(nums(params, "from", [0.0, 0.0, 0.0]))
    to = ctm @ mathutils.Vector(nums(params, "to", [0.0, 0.0, 1.0]))
    light = bpy.data.lights.new("spot", type="SPOT")
    peak = max(I) * scale
    light.color = [c * scale / peak for c in I] if peak > 0 else [0.0, 0.0, 0.0]
    light.energy = 4 * math.pi * peak
    light.shadow_soft_size = 0.0  # a point, as pbrt's
    light.spot_size = math.radians(2 * cone)
    c_end, c_start = math.cos(math.radians(cone)), math.cos(math.radians(max(0.0, cone - delta)))
    light.spot_blend = min(1.0, max(0.0, (c_start - c_end) / (1 - c_end))) if c_end < 1 else 0.0
    return frm, (to - frm).normalized(), light


def build(path, opts):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    ctm = mathutils.Matrix.Identity(4)
    camera_from_world, fov, res, maxdepth, panorama = None, 90.0, [640, 480], 5, False
    state = {"material": ("diffuse", {}), "area": None, "reverse": False, "inside": "", "outside": ""}
    stack, named, background, meshes, spots = [], {}, None, [], []
    media, camera_medium, volumes = {}, "", {}
    for name, args, params, line in parse(path):
        where = "%s:%d" % (path, line)
        if name == "LookAt":
            ctm = ctm @ look_at([float(a) for a in args[0:3]], [float(a) for a in args[3:6]], [float(a) for a in args[6:9]])
        elif name == "Scale":
            ctm = ctm @ mathutils.Matrix.Diagonal([float(a) for a in args] + [1.0])
        elif name == "Translate":
            ctm = ctm @ mathutils.Matrix.Translation([float(a) for a in args])
        elif name == "Rotate":
            ctm = ctm @ mathutils.Matrix.Rotation(math.radians(float(args[0])), 4, [float(a) for a in args[1:4]])
        elif name == "Camera":
            if args[0] not in ("perspective", "spherical"):
                fail("%s: camera %s is not built" % (where, args[0]))
            if args[0] == "spherical" and params.get("mapping", ("", ["equalarea"]))[1][0] != "equirectangular":
                fail("%s: a spherical camera's equal-area mapping is not built (equirectangular only)" % where)
            camera_from_world, fov = ctm.copy(), nums(params, "fov", [90.0])[0]
            panorama = args[0] == "spherical"
            camera_medium = state["outside"]  # pbrt-v4: the current outside medium
        elif name == "Film":
            res = [int(nums(params, "xresolution", [1280])[0]), int(nums(params, "yresolution", [720])[0])]
        elif name == "Integrator":
            maxdepth = int(nums(params, "maxdepth", [5])[0])
        elif name in ("Sampler", "PixelFilter", "ColorSpace", "Option"):
            pass
        elif name == "WorldBegin":
            ctm = mathutils.Matrix.Identity(4)
        elif name == "AttributeBegin":
            stack.append((ctm.copy(), dict(state)))
        elif name == "AttributeEnd":
            ctm, state = stack.pop()
        elif name == "MakeNamedMedium":
            media[args[0]] = (params.get("type", ("", [""]))[1][0], params, ctm.copy())
        elif name == "MediumInterface":
            state["inside"] = args[0] if args else ""
            state["outside"] = args[1] if len(args) > 1 else state["inside"]
        elif name == "ReverseOrientation":
            state["reverse"] = not state["reverse"]
        elif name == "MakeNamedMaterial":
            named[args[0]] = (params["type"][1][0], params)
        elif name == "NamedMaterial":
            state["material"] = named[args[0]]
        elif name == "Material":
            state["material"] = (args[0], params)
        elif name == "AreaLightSource":
            L = nums(params, "L", [1.0, 1.0, 1.0])
            s = nums(params, "scale", [1.0])[0]
            state["area"] = [c * s for c in L]
        elif name == "LightSource":
            if args[0] == "spot":
                spots.append(spot_light(ctm, params))
            elif args[0] == "infinite" and "filename" not in params:
                background = nums(params, "L", [1.0, 1.0, 1.0])
            else:
                fail("%s: light %s is not built (area, spot and constant infinite lights only)" % (where, args[0]))
        elif name == "Shape":
            ins = state["inside"]
            inside = None
            if ins != state["outside"] and ins not in ("", camera_medium):
                if ins in media and media[ins][0] == "uniformgrid" and state["material"][0] == "interface":
                    if ins not in volumes:  # the grid bounds itself: its interface shape is not needed
                        volumes[ins] = grid_volume(ins, media[ins][1], media[ins][2], opts["vdb"] % len(volumes))
                    continue
                inside = medium_params(media, ins, where)
            if args[0] == "trianglemesh":
                P = nums(params, "P")
                idx = [int(v) for v in nums(params, "indices")]
                verts = [ctm @ mathutils.Vector(P[3 * k:3 * k + 3]) for k in range(len(P) // 3)]
                flip = state["reverse"] != (ctm.to_3x3().determinant() < 0)
                faces = [(idx[3 * k], idx[3 * k + 2], idx[3 * k + 1]) if flip else tuple(idx[3 * k:3 * k + 3])
                         for k in range(len(idx) // 3)]
                meshes.append((verts, faces, make_material(state, "m%d" % len(meshes), inside)))
            else:
                shape = quadric_or_curve(args[0], params)
                if shape is None:
                    fail("%s: shape %s is not built" % (where, args[0]))
                flip = state["reverse"] != (ctm.to_3x3().determinant() < 0)
                verts = [ctm @ mathutils.Vector(v) for v in shape[0]]
                faces = [tuple(reversed(f)) if flip else f for f in shape[1]]
                meshes.append((verts, faces, make_material(state, "m%d" % len(meshes), inside)))
        else:
            fail("%s: directive %s is not built" % (where, name))
    if camera_from_world is None:
        fail("%s: no Camera" % path)
    # Blender's camera looks down its -z with a right-handed frame; pbrt's
    # down +z, left-handed. Where the camera's frame would be a reflection,
    # the world is mirrored in x instead (the same image).
    cam_world = camera_from_world.inverted() @ mathutils.Matrix.Diagonal((1, 1, -1, 1))
    mirror = mathutils.Matrix.Diagonal((-1, 1, 1, 1)) if cam_world.to_3x3().determinant() < 0 else None
    if mirror is not None:
        cam_world = mirror @ cam_world
    for n, (verts, faces, mat) in enumerate(meshes):
        if mirror is not None:
            verts = [mirror @ v for v in verts]
            faces = [tuple(reversed(f)) for f in faces]  # the normals stay on their side
        add_mesh("shape%d" % n, verts, faces, mat)
    for n, (position, direction, light) in enumerate(spots):
        if mirror is not None:
            position, direction = mirror @ position, mirror.to_3x3() @ direction
        ob = bpy.data.objects.new("spot%d" % n, light)
        # a Blender spot shines down its local -z
        ob.matrix_world = mathutils.Matrix.Translation(position) @ direction.to_track_quat("-Z", "Y").to_matrix().to_4x4()
        scene.collection.objects.link(ob)
    for ob in volumes.values():
        if mirror is not None:
            ob.matrix_world = mirror
        scene.collection.objects.link(ob)
    cam = bpy.data.cameras.new("camera")
    w, h = opts.get("resolution") or res
    cam.sensor_fit = "VERTICAL" if w >= h else "HORIZONTAL"
    if panorama:
        # pbrt-v4's equirectangular image looks along the camera's +x at
        # its left edge, forward at a quarter of its width and left at
        # its centre, turning left as it goes right; Cycles' looks forward
        # at its centre and turns right, unless its longitudes run
        # backwards. So they run backwards, and the camera turns left by
        # a quarter turn (below).
        cam.type = "PANO"
        cam.cycles.panorama_type = "EQUIRECTANGULAR"
        cam.cycles.longitude_min, cam.cycles.longitude_max = math.pi, -math.pi
        cam_world = cam_world @ mathutils.Matrix.Rotation(math.pi / 2, 4, "Y")
    elif w >= h:
        cam.angle_y = math.radians(fov)
    else:
        cam.angle_x = math.radians(fov)
    cam.clip_start, cam.clip_end = 1e-3, 1e6
    ob = bpy.data.objects.new("camera", cam)
    ob.matrix_world = cam_world
    scene.collection.objects.link(ob)
    scene.camera = ob
    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (background or [0.0, 0.0, 0.0]) + [1]
    bg.inputs["Strength"].default_value = 1.0
    if camera_medium:
        out = world.node_tree.nodes["World Output"]
        world.node_tree.links.new(volume_shader(world.node_tree, medium_params(media, camera_medium, path)), out.inputs["Volume"])
    scene.world = world
    return w, h, maxdepth


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) < 2:
        fail("usage: -- SCENE.pbrt OUT.exr --time SECONDS | --samples N [--seed S] [--resolution W H] [--guiding] [--no-adaptive]")
    path, out = argv[0], argv[1]
    opts, i = {}, 2
    while i < len(argv):
        a = argv[i]
        if a in ("--time", "--samples", "--seed"):
            opts[a[2:]] = float(argv[i + 1])
            i += 2
        elif a == "--resolution":
            opts["resolution"] = [int(argv[i + 1]), int(argv[i + 2])]
            i += 3
        elif a in ("--guiding", "--no-adaptive"):
            opts[a[2:]] = True
            i += 1
        else:
            fail("unknown option " + a)
    opts["vdb"] = out + ".grid%d.vdb"  # a uniformgrid's file, removed after the render
    w, h, maxdepth = build(path, opts)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.use_denoising = False
    c.seed = int(opts.get("seed", 0))
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.volume_bounces = maxdepth
    c.transparent_max_bounces = maxdepth  # (a shape of the "interface" material is a transparent one to Cycles)
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.use_adaptive_sampling = not opts.get("no-adaptive", False)
    if "time" in opts:
        # Under a time limit the render must use its time: at the default
        # noise threshold (0.01) Cycles stops early on these scenes (the
        # Cornell box before 30 s), so its adaptive sampling aims lower.
        c.samples = 1 << 20
        c.time_limit = opts["time"]
        c.adaptive_threshold = 0.001
    else:
        c.samples = int(opts.get("samples", 64))
        c.time_limit = 0
    if opts.get("guiding"):
        import _cycles
        if not getattr(_cycles, "with_path_guiding", False):
            fail("this Cycles was built without path guiding (Open PGL)")
        c.use_guiding = True
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = out
    t0 = time.time()
    try:
        bpy.ops.render.render(write_still=True)
    finally:
        for f in glob.glob(glob.escape(out) + ".grid*.vdb"):
            os.remove(f)
    print("scene_to_cycles.py: %s: %dx%d, %.2f s render" % (out, w, h, time.time() - t0))


try:
    main()
except SystemExit:
    raise
except Exception as e:  # Blender itself would exit 0 after a script's exception
    fail("%s: %s" % (type(e).__name__, e))
