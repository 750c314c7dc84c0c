"""A Wavefront OBJ scene for the peer comparisons: polygons grouped by group and material, and
each material's diffuse reflectance and emitted radiance from its MTL (Kd, Ke), as luxel reads
them. Enough for McGuire's Cornell boxes (quads, `g` groups, negative indices); plain Python, so
that both Blender's side (cycles_cornell.py) and the mask (compare_cornell.py) read the same
geometry.
"""

import os

# A view of McGuire's boxes (x in [-1, 1], y in [0, 2], z in [-1, 1] metres, open towards +z).
MCGUIRE_CAMERA = dict(eye=(0.0, 1.0, 3.6), target=(0.0, 1.0, 0.0), fov_deg=40.0)


def load_obj(path):
    """Returns (meshes, materials): meshes as (name, material, polygons) with polygons lists of
    (x, y, z) in the file's units (metres), in the file's order; materials as
    {name: {"kd": (r, g, b), "ke": (r, g, b)}}.

    A copy of a polygon already read (same corners in the same cyclic order) is dropped, as luxel
    drops coincident faces at load (src/scene/coincident_faces.h): McGuire's original box repeats
    a face of each block, which a path tracer renders black (each copy shadows the other)."""
    verts, meshes, materials = [], [], {}
    seen = set()
    group, material = "default", "default"
    by_key = {}
    with open(path) as f:
        for line in f:
            parts = line.split("#", 1)[0].split()
            if not parts:
                continue
            tag = parts[0]
            if tag == "v":
                verts.append(tuple(float(x) for x in parts[1:4]))
            elif tag in ("g", "o"):
                group = " ".join(parts[1:]) or "default"
            elif tag == "usemtl":
                material = parts[1]
            elif tag == "mtllib":
                materials.update(load_mtl(os.path.join(os.path.dirname(path), " ".join(parts[1:]))))
            elif tag == "f":
                poly = []
                for ref in parts[1:]:
                    i = int(ref.split("/")[0])
                    poly.append(verts[i - 1] if i > 0 else verts[len(verts) + i])
                k = min(range(len(poly)), key=lambda j: poly[j])
                canonical = tuple(poly[k:] + poly[:k])
                if canonical in seen:
                    continue
                seen.add(canonical)
                key = (group, material)
                if key not in by_key:
                    by_key[key] = len(meshes)
                    meshes.append((group, material, []))
                meshes[by_key[key]][2].append(poly)
    for _, m, _ in meshes:
        materials.setdefault(m, {"kd": (0.8, 0.8, 0.8), "ke": (0.0, 0.0, 0.0)})
    return meshes, materials


def load_mtl(path):
    materials, current = {}, None
    with open(path) as f:
        for line in f:
            parts = line.split("#", 1)[0].split()
            if not parts:
                continue
            if parts[0] == "newmtl":
                current = parts[1]
                materials[current] = {"kd": (0.8, 0.8, 0.8), "ke": (0.0, 0.0, 0.0)}
            elif current and parts[0] in ("Kd", "Ke"):
                materials[current][parts[0].lower()] = tuple(float(x) for x in parts[1:4])
    return materials


def emits(material):
    return any(c > 0.0 for c in material["ke"])
