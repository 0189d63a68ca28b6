#!/usr/bin/env python3
"""Check a camera path's KITTI object files (`kitti = true`) against its COCO file.

usage: check_kitti.py <frames/<camera> folder>

Reads `label_2/NNNNNN.txt` and `calib/NNNNNN.txt` as the KITTI object devkit's readme
describes them, with numpy only (no third-party reader: pykitti reads the raw and
odometry sets, not object labels, and the readers that do, lingvo's kitti_data or d3d,
come with TensorFlow or a 3D framework), and checks for every frame:

1. the calib file has P0-P3 and Tr_velo_to_cam, Tr_imu_to_velo (12 numbers each) and
   R0_rect (9), R0_rect a rotation, and P2 = K @ [R0_rect.T | 0] with K the COCO image's
   intrinsics (so P2 is K itself for a level camera);
2. every label line has the 15 fields (type, truncated in [0, 1], occluded in 0-3, alpha
   and rotation_y in [-pi, pi], the 2D box, h w l >= 0, x y z), one per COCO annotation of
   the frame that has `attributes.box3d` and is not an ignore region, in order; its 2D box
   is that annotation's bbox (edges);
3. the 8 corners, made as the devkit's computeBox3D makes them and projected through P2,
   contain the annotation's full_bbox (the pixels the object would cover unoccluded;
   within 0.6 px, for the labels' 2 decimals), where every corner is in front of the
   camera; and the COCO `box3d` agrees with the label (size, rotation_y).
"""

import json
import math
import sys
from pathlib import Path

import numpy as np


def read_calib(path):
    rows = {}
    for line in path.read_text().splitlines():
        if line.strip():
            name, values = line.split(":", 1)
            rows[name] = np.array([float(v) for v in values.split()])
    for name in ["P0", "P1", "P2", "P3", "Tr_velo_to_cam", "Tr_imu_to_velo"]:
        assert rows[name].shape == (12,), f"{path}: {name}"
    assert rows["R0_rect"].shape == (9,), f"{path}: R0_rect"
    return {k: v.reshape(3, 4) if v.size == 12 else v.reshape(3, 3) for k, v in rows.items()}


def corners(h, w, l, x, y, z, ry):
    """The devkit's computeBox3D: 3 x 8 corners in the camera."""
    xs = [l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2]
    ys = [0, 0, 0, 0, -h, -h, -h, -h]
    zs = [w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2]
    r = np.array([[math.cos(ry), 0, math.sin(ry)], [0, 1, 0], [-math.sin(ry), 0, math.cos(ry)]])
    return r @ np.array([xs, ys, zs]) + np.array([[x], [y], [z]])


def main(folder):
    folder = Path(folder)
    coco = json.loads((folder / "coco.json").read_text())
    by_image = {}
    for ann in coco["annotations"]:
        if ann["iscrowd"] == 0 and "box3d" in ann.get("attributes", {}):
            by_image.setdefault(ann["image_id"], []).append(ann)
    boxes = 0
    for image in coco["images"]:
        stem = Path(image["file_name"]).stem
        calib = read_calib(folder / "calib" / f"{stem}.txt")
        r0 = calib["R0_rect"]
        assert np.allclose(r0 @ r0.T, np.eye(3), atol=1e-9), f"{stem}: R0_rect"
        k = image["intrinsics"]
        kmat = np.array([[k["fx"], 0, k["cx"]], [0, k["fy"], k["cy"]], [0, 0, 1]])
        p2 = calib["P2"]
        assert np.allclose(p2, kmat @ np.hstack([r0.T, np.zeros((3, 1))]), atol=1e-6), stem
        lines = (folder / "label_2" / f"{stem}.txt").read_text().splitlines()
        anns = by_image.get(image["id"], [])
        assert len(lines) == len(anns), f"{stem}: {len(lines)} lines, {len(anns)} annotations"
        for line, ann in zip(lines, anns):
            f = line.split()
            assert len(f) == 15, line
            truncated, occluded, alpha = float(f[1]), int(f[2]), float(f[3])
            left, top, right, bottom, h, w, l, x, y, z, ry = map(float, f[4:])
            assert 0 <= truncated <= 1 and occluded in (0, 1, 2, 3), line
            assert abs(alpha) <= math.pi + 0.01 and abs(ry) <= math.pi + 0.01, line
            assert min(h, w, l) >= 0, line
            bx, by, bw, bh = ann["bbox"]
            assert [left, top, right, bottom] == [bx, by, bx + bw, by + bh], (line, ann["bbox"])
            b3 = ann["attributes"]["box3d"]
            assert np.allclose([l, w, h], b3["size"], atol=0.006), (line, b3)
            assert abs(math.remainder(ry - b3["rotation_y"], 2 * math.pi)) < 0.006, (line, b3)
            c = corners(h, w, l, x, y, z, ry)
            if (c[2] <= 0.1).any() or ann.get("full_bbox") is None:
                continue
            p = p2 @ np.vstack([c, np.ones(8)])
            u, v = p[0] / p[2], p[1] / p[2]
            fx, fy, fw, fh = ann["full_bbox"]
            s = 0.6
            assert u.min() <= fx + 0.5 + s and u.max() >= fx + fw - 0.5 - s, (stem, line, fx, fw)
            assert v.min() <= fy + 0.5 + s and v.max() >= fy + fh - 0.5 - s, (stem, line, fy, fh)
            boxes += 1
    assert boxes > 0, "no box checked"
    print(f"{folder}: {len(coco['images'])} frames, {boxes} 3D boxes contain their full 2D boxes")


if __name__ == "__main__":
    main(sys.argv[1])
