"""Loads a city.obj with its .mtl and textures in trimesh, a third-party loader.

Usage: python load_obj.py path/to/city.obj

Checks that trimesh loads the OBJ into one geometry per (object, material) pair the file
declares, with as many faces as it has `f` lines; that every material the MTL gives a
`map_Kd` names an existing file; and that each geometry of a textured material has its
image loaded and uvs. Prints vertex/face counts. Exits 1 on any failure.
"""

import os
import sys

import trimesh


def declared(obj_path):
    """(object, material) pairs that have faces, and the number of faces, from the text."""
    pairs, faces = set(), 0
    obj, material = None, None
    with open(obj_path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("f "):
                faces += 1
                pairs.add((obj, material))
            elif line.startswith("o "):
                obj = line[2:].strip()
            elif line.startswith("usemtl "):
                material = line[7:].strip()
    return pairs, faces


def textured_materials(mtl_path):
    """Material names the MTL gives a diffuse texture; fails on a missing texture file."""
    names, current = set(), None
    with open(mtl_path, encoding="utf-8") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "newmtl":
                current = words[1]
            elif words[0] == "map_Kd" and current is not None:
                names.add(current)
                texture = os.path.join(os.path.dirname(mtl_path), words[-1])
                if not os.path.isfile(texture):
                    raise SystemExit(f"{mtl_path}: {current} names missing file {words[-1]}")
    return names


def main():
    if len(sys.argv) != 2:
        print("usage: python load_obj.py FILE.obj", file=sys.stderr)
        return 2
    path = sys.argv[1]
    folder = os.path.dirname(os.path.abspath(path))
    # One geometry per (object, material); process=False keeps the vertices as written.
    scene = trimesh.load(path, force="scene", split_objects=True, process=False)
    geometries = scene.geometry
    vertices = sum(len(g.vertices) for g in geometries.values())
    faces = sum(len(g.faces) for g in geometries.values())
    print(f"{path}: {len(geometries)} geometries, {vertices} vertices, {faces} faces")

    failures = []
    pairs, declared_faces = declared(path)
    objects = {obj for obj, _ in pairs}
    print(f"  the file declares {len(objects)} objects with faces, {len(pairs)} (object, material) groups, {declared_faces} faces")
    if len(geometries) != len(pairs):
        failures.append(f"{len(geometries)} geometries loaded, {len(pairs)} groups declared")
    if faces != declared_faces or faces == 0:
        failures.append(f"{faces} faces loaded, {declared_faces} declared")

    textured = textured_materials(os.path.join(folder, "city.mtl"))
    loaded = set()
    for name, geometry in geometries.items():
        material = getattr(geometry.visual, "material", None)
        material_name = getattr(material, "name", None)
        if material_name not in textured:
            continue
        if getattr(material, "image", None) is None:
            failures.append(f"{name}: material {material_name} has no image loaded")
        elif getattr(geometry.visual, "uv", None) is None or len(geometry.visual.uv) != len(geometry.vertices):
            failures.append(f"{name}: textured material {material_name} without uvs")
        else:
            loaded.add(material_name)
    used_textured = {m for _, m in pairs if m in textured}
    print(f"  textured materials: {len(textured)} in the MTL, {len(used_textured)} used, {len(loaded)} loaded with their images")
    if loaded != used_textured:
        failures.append(f"textured materials without a loaded image: {sorted(used_textured - loaded)}")
    for failure in failures:
        print(f"  FAIL {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
