#!/usr/bin/env python3
"""Writes the pbrt-v4 versions of the interior benchmark's rooms (README.md in this folder) from their JSON files, so
that the two stay the same scene: daylit_room_open, daylit_room_glazed, door_ajar and night_room_downlights .pbrt,
and downlight_equal_area.pfm, the downlights' IES distribution as the equal-area image pbrt-v4's `goniometric`
light reads.

Run from anywhere:  python3 data/scenes/interiors/write_pbrt_versions.py
The outputs are committed; this script is how they were made (standard library only). With --check it writes
nothing and exits 1 if a committed file differs from what it would write (a ctest runs that). It converts only what these
rooms use (quads, triangle meshes, spheres; diffuse, thin and solid dielectrics, conductors; a distant sun, a
uniform sky with a portal, IES downlights) and stops on anything else.

Units. pbrt-v4's light unit is "1 nit": a light of luminance 1 makes a pixel Y of 1. Rimu's importer reads a pbrt
amount A as A·K in its photometric keys, K = 683 lm/W · ∫ȳ dλ = 72 983.26 nt (docs/pbrt-import.md), so every
photometric amount of the JSON is written divided by K: the same room in both files.
Exposure. Film "iso" scales pbrt's pixels by iso/100, and Rimu imports it as the same scale; it is chosen per
room so that the lit walls are of order 1, because the relMSE of the benchmark (rimu-pbrt-image-compare) adds 0.01
to each reference pixel's square and would otherwise measure absolute error in the dark rooms.
"""
import json
import sys
import math
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent
K_NT = 683.0 * 106.856895  # Rimu's luminance per film unit Y (CIE 1931 ȳ integrated over 360-830 nm)
PFM_NAME = "downlight_equal_area.pfm"
PFM_SIZE = 64
SCENES = {  # JSON file -> Film iso (pixel scale iso/100), chosen so the walls are of order 1
    "daylit_room_open.json": 3000,
    "daylit_room_glazed.json": 3000,
    "door_ajar.json": 300000,
    "night_room_downlights.json": 3000,
}
# pbrt-v4's portal light gives radiance only to rays whose origin sees the portal in front of it
# (PortalImageInfiniteLight::Le checks the ray origin's view of the portal). A ray leaving the glazed room starts
# on the outer pane (x = 4.01), beyond a portal in the window's plane (x = 4), and would see no sky. So in the glazed
# room the portal is moved 1 mm outside the outer pane and grown by 0.1 m on every side, so that no direction
# through the window misses it (a ray would have to cross the 11 mm at more than 83.7 degrees from the normal).
# Rimu does not need this (its sky is seen outside portals too); it reads the same larger portal.
PORTAL_MOVES = {"daylit_room_glazed.json": (4.011, 0.1)}  # JSON file -> (portal plane x, margin m)


def fmt(values):
    return " ".join("%.9g" % v for v in values)


def spectrum(value, what):
    """A Rimu spectrum of a light as a pbrt spectrum parameter's type suffix and value."""
    if "illuminant" in value and value["illuminant"] == "D65":
        return '"spectrum %s" "stdillum-D65"' % what
    if "blackbody" in value:
        return '"blackbody %s" %s' % (what, fmt([value["blackbody"]]))
    raise ValueError("spectrum %r not converted" % value)


def reflectance(value):
    if isinstance(value, (int, float)):
        return '"spectrum reflectance" [ 300 %s 800 %s ]' % (fmt([value]), fmt([value]))
    if "rgb" in value:
        return '"rgb reflectance" [ %s ]' % fmt(value["rgb"])
    raise ValueError("reflectance %r not converted" % value)


def material(name, m):
    t = m["type"]
    if t == "diffuse":
        body = '"diffuse" %s' % reflectance(m["reflectance"])
    elif t == "thin_dielectric":
        body = '"thindielectric" "float eta" %s' % fmt([m["ior"]])
    elif t == "dielectric" and m.get("glass") == "bk7":
        body = '"dielectric" "spectrum eta" "glass-BK7"'
    elif t == "conductor" and m.get("metal") == "copper":
        # Rimu's roughness r is perceptual: GGX alpha = r^2; pbrt's without remapping is alpha itself.
        alpha = m.get("roughness", 0.0) ** 2
        body = ('"conductor" "spectrum eta" "metal-Cu-eta" "spectrum k" "metal-Cu-k" '
                '"bool remaproughness" false "float roughness" %s' % fmt([alpha]))
    else:
        raise ValueError("material %s: %r not converted" % (name, m))
    return 'MakeNamedMaterial "%s" "string type" %s' % (name, body)


def shape(s):
    lines = ['# %s' % s["name"]] if "name" in s else []
    lines.append('NamedMaterial "%s"' % s["material"])
    if s["type"] == "quad":
        p, idx = s["vertices"], [0, 1, 2, 0, 2, 3]
    elif s["type"] == "triangles":
        p, idx = s["positions"], s["indices"]
    elif s["type"] == "sphere":
        lines += ["AttributeBegin", "  Translate %s" % fmt(s["center"]),
                  '  Shape "sphere" "float radius" %s' % fmt([s["radius"]]), "AttributeEnd"]
        return lines
    else:
        raise ValueError("shape %r not converted" % s["type"])
    # Rimu's front is the counter-clockwise side, and so is pbrt-v4's for a mesh without normals.
    flat = [c for v in p for c in v]
    lines.append('Shape "trianglemesh" "integer indices" [ %s ]\n  "point3 P" [ %s ]'
                 % (" ".join(str(i) for i in idx), fmt(flat)))
    return lines


def ies_candela(path):
    """(vertical angles in degrees, candela) of a single-plane LM-63 file such as data/examples/downlight.ies."""
    tokens = path.read_text().split("TILT=NONE", 1)[1].split()
    n_vertical, n_horizontal = int(tokens[3]), int(tokens[4])
    numbers = [float(t) for t in tokens[13:]]  # after the 10 + 3 header numbers
    angles = numbers[:n_vertical]
    candela = numbers[n_vertical + n_horizontal:n_vertical + n_horizontal + n_vertical]
    if n_horizontal != 1:
        raise ValueError("%s: only rotationally symmetric IES files are converted" % path)
    return angles, candela


def equal_area_square_to_sphere(u, v):
    """Clarberg's equal-area octahedral map of [0,1]^2 to the sphere, as pbrt-v4 uses it for its light images."""
    u, v = 2 * u - 1, 2 * v - 1
    up, vp = abs(u), abs(v)
    signed_distance = 1 - (up + vp)
    r = 1 - abs(signed_distance)
    phi = ((vp - up) / r + 1 if r != 0 else 1) * math.pi / 4
    z = math.copysign(1 - r * r, signed_distance)
    s = r * math.sqrt(max(0.0, 2 - r * r))
    return math.copysign(math.cos(phi), u) * s, math.copysign(math.sin(phi), v) * s, z


def write(name, data, check):
    """Writes HERE/name, or with check only compares it; returns False when a committed file differs."""
    path = HERE / name
    if not check:
        path.write_bytes(data)
        return True
    if not path.exists() or path.read_bytes() != data:
        print("%s differs from what write_pbrt_versions.py writes from the JSON scenes: rerun it" % path)
        return False
    return True


def goniometric_image(ies_path):
    """The IES distribution of a downlight pointing along its light space's -y, as pbrt-v4's goniometric image.
    pbrt looks a light-space direction (x, y, z) up at the image's direction (x, z, y), so the downlight's axis is
    the image's -z, and the angle from it is acos(-z). Nearest pixel in pbrt (and Rimu's import), so 64 x 64 pixels
    (0.003 sr each) resolve the 5-degree table. The scale is irrelevant: `power` sets the flux."""
    angles, candela = ies_candela(ies_path)
    rows = []
    for y in range(PFM_SIZE):
        row = []
        for x in range(PFM_SIZE):
            _, _, z = equal_area_square_to_sphere((x + 0.5) / PFM_SIZE, (y + 0.5) / PFM_SIZE)
            gamma = math.degrees(math.acos(max(-1.0, min(1.0, -z))))
            value = 0.0
            for i in range(len(angles) - 1):
                if angles[i] <= gamma <= angles[i + 1]:
                    f = (gamma - angles[i]) / (angles[i + 1] - angles[i])
                    value = candela[i] * (1 - f) + candela[i + 1] * f
                    break
            row.append(value)
        rows.append(row)
    # PFM: bottom row first; the map is symmetric under the row flip, so the order does not matter here.
    data = b"".join(struct.pack("<fff", v, v, v) for row in reversed(rows) for v in row)
    return b"PF\n%d %d\n-1.0\n" % (PFM_SIZE, PFM_SIZE) + data


def moved_portal(portal, move):
    """The portal rectangle (in an x = const plane) moved to x = move[0] and grown by move[1] on every side."""
    x, margin = move
    ys, zs = [p[1] for p in portal], [p[2] for p in portal]
    if len({p[0] for p in portal}) != 1:
        raise ValueError("only portals in an x = const plane are moved")
    y0, y1, z0, z1 = min(ys) - margin, max(ys) + margin, min(zs) - margin, max(zs) + margin
    return [[x, y0, z0], [x, y0, z1], [x, y1, z1], [x, y1, z0]]  # the JSON's winding: normal +x, out of the room


def light(l, move):
    if l["type"] == "distant":
        return ['# %s: a delta direction in pbrt (Rimu\'s JSON gives it a %s-degree disc)'
                % (l.get("name", "distant"), l.get("angular_diameter_deg", 0)),
                'LightSource "distant" "point3 from" [ %s ] "point3 to" [ 0 0 0 ] %s "float illuminance" %s'
                % (fmt(l["direction"]), spectrum(l["spectrum"], "L"), fmt([l["illuminance_lx"] / K_NT]))]
    if l["type"] == "environment":
        portals = l.get("portals", [])
        if len(portals) > 1:
            raise ValueError("pbrt-v4 takes one portal")
        if portals and move:
            portals = [moved_portal(portals[0], move)]
        portal = ' "point3 portal" [ %s ]' % fmt([c for p in portals[0] for c in p]) if portals else ""
        return ['# %s: uniform, %g nt; pbrt-v4 makes L with a portal a 1x1 image in sRGB' % (l.get("name", "sky"),
                                                                                           l["luminance_nt"]),
                'LightSource "infinite" %s "float scale" %s%s' % (spectrum(l["spectrum"], "L"),
                                                                  fmt([l["luminance_nt"] / K_NT]), portal)]
    if l["type"] == "ies":
        d = l["direction"]
        if d != [0, -1, 0]:
            raise ValueError("only downward IES lights are converted")
        return ["AttributeBegin", "  Translate %s" % fmt(l["position"]),
                '  LightSource "goniometric" "string filename" "%s" %s "float power" %s'
                % (PFM_NAME, spectrum(l["spectrum"], "I"), fmt([l["luminous_power_lm"] / K_NT])),
                "AttributeEnd"]
    raise ValueError("light %r not converted" % l["type"])


def convert(json_name, iso):
    """The pbrt-v4 file of one JSON room, as bytes."""
    scene = json.loads((HERE / json_name).read_text())
    cam, film, integ = scene["camera"], scene["film"], scene.get("integrator", {})
    width, height = film["resolution"]
    if width < height:
        raise ValueError("pbrt's fov is the shorter axis': only landscape images are converted")
    if film.get("filter", {}).get("type", "box") != "box" and "filter" in film:
        raise ValueError("only the box filter is converted")
    out = ["# %s in pbrt-v4's format, written by write_pbrt_versions.py from %s (README.md in this folder)."
           % (json_name[:-5], json_name),
           "# " + scene.get("description", "").split(". data/")[0],
           "# Lights in pbrt's unit (1 nit = film Y 1): the JSON's photometric amounts / %.2f." % K_NT,
           "# pbrt's camera space is left-handed: the mirror makes the image the JSON's.",
           "Scale -1 1 1",
           "LookAt %s  %s  0 1 0" % (fmt(cam["from"]), fmt(cam["to"])),
           'Camera "perspective" "float fov" %s' % fmt([cam["vertical_fov_deg"]]),
           'Film "rgb" "integer xresolution" %d "integer yresolution" %d "float iso" %s "bool savefp16" false'
           % (width, height, fmt([iso])),
           'PixelFilter "box"',
           # No "seed": a Sampler's seed overrides pbrt's --seed, which the benchmark sets per render.
           'Sampler "zsobol" "integer pixelsamples" %d' % integ.get("spp", 16),
           'Integrator "path" "integer maxdepth" %d' % integ.get("max_depth", 5),
           "WorldBegin", ""]
    for l in scene["lights"]:
        out += light(l, PORTAL_MOVES.get(json_name))
    out.append("")
    for name, m in scene["materials"].items():
        out.append(material(name, m))
    out.append("")
    for s in scene["shapes"]:
        out += shape(s)
    return ("\n".join(out) + "\n").encode()


def main():
    check = sys.argv[1:] == ["--check"]
    same = write(PFM_NAME, goniometric_image(HERE / "../../examples/downlight.ies"), check)
    for name, iso in SCENES.items():
        same = write(name[:-5] + ".pbrt", convert(name, iso), check) and same
    sys.exit(0 if same else 1)


if __name__ == "__main__":
    main()
