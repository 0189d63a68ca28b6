#!/usr/bin/env python3
"""Check a camera path's LiDAR scans (a camera with `lidar`) against its camera frames.

usage: check_lidar.py <frames/<camera> folder>

Reads the scans as SemanticKITTI's own tools do (numpy: `velodyne/NNNNNN.bin` float32
x, y, z, intensity; `labels/NNNNNN.label` uint32 semantic | instance << 16), and for
every frame checks:

1. the files hold whole records, one label per point, at most beams x columns points;
   every semantic id is one `poses.json` names, intensities lie in [0, 1], ranges within
   the scanner's range (plus noise);
2. the points project into the camera's image the KITTI devkit's way
   (P2 @ R0_rect @ Tr_velo_to_cam @ x, from `calib/NNNNNN.txt`), and there agree with the
   camera's own render, an independent rasterizer: of the points that land on the image,
   at least 97 % carry the semantic id of the object `ids/` shows at their pixel (its
   kind in `instances.json`, mapped by `poses.json`'s `kind_semantic_ids`), at least 97 %
   of the thing points (an instance in the upper 16 bits) the same instance, and the
   median |camera z - depth| is under 5 cm;
3. `velodyne_to_world` in `poses.json` puts the road points (semantic 40) at the
   ground, y = 0, within 5 cm (median).

With PLY files (`lidar.ply`), each PLY holds the same points and labels as the .bin and
.label files.
"""

import json
import sys
from pathlib import Path

import numpy as np
from PIL import Image

from check_kitti import read_calib


def calib_matrices(path):
    """P2 (3 x 4), R0_rect and Tr_velo_to_cam as 4 x 4, read by check_kitti's reader."""
    rows = read_calib(path)
    r0 = np.eye(4)
    r0[:3, :3] = rows["R0_rect"]
    tr = np.eye(4)
    tr[:3, :] = rows["Tr_velo_to_cam"]
    return rows["P2"], r0, tr


def read_ply(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    assert header.startswith("ply\nformat binary_little_endian 1.0\n"), path
    count = int(next(l for l in header.splitlines() if l.startswith("element vertex")).split()[2])
    record = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("i", "<f4"), ("label", "<u4")])
    rows = np.frombuffer(data[end:], dtype=record)
    assert len(rows) == count, f"{path}: {len(rows)} vertices, header says {count}"
    return rows


def main(folder):
    folder = Path(folder)
    poses = json.loads((folder / "poses.json").read_text())
    lidar = poses["lidar"]
    instances = json.loads((folder / "instances.json").read_text())["instances"]
    kind_ids = lidar["kind_semantic_ids"]
    names = {int(k): v for k, v in lidar["semantic_names"].items()}
    # Semantic id of each instance id (0: sky).
    semantic_of = np.zeros(max(i["id"] for i in instances) + 1, dtype=np.int64)
    for inst in instances:
        semantic_of[inst["id"]] = kind_ids[inst["kind"]]
    width, height = poses["intrinsics"]["width"], poses["intrinsics"]["height"]
    scale = poses["depth"]["scale"]
    most = lidar["beams"] * lidar["columns"]
    totals = dict(points=0, seen=0, semantic=0, things=0, thing_match=0)
    dz_all, ground_all = [], []
    for i, frame in enumerate(poses["frames"]):
        stem = f"{i:06d}"
        raw = (folder / "velodyne" / f"{stem}.bin").read_bytes()
        assert len(raw) % 16 == 0, f"{stem}.bin: {len(raw)} bytes, not 16-byte records"
        points = np.frombuffer(raw, dtype="<f4").reshape(-1, 4)
        labels = np.fromfile(folder / "labels" / f"{stem}.label", dtype="<u4")
        assert len(labels) == len(points), f"{stem}: {len(points)} points, {len(labels)} labels"
        assert 0 < len(points) <= most, f"{stem}: {len(points)} points of {most} beams"
        semantic = (labels & 0xFFFF).astype(np.int64)
        instance = (labels >> 16).astype(np.int64)
        unknown = set(np.unique(semantic).tolist()) - set(names)
        assert not unknown, f"{stem}: semantic ids {unknown} not in poses.json"
        assert points[:, 3].min() >= 0 and points[:, 3].max() <= 1, f"{stem}: intensity"
        ranges = np.linalg.norm(points[:, :3], axis=1)
        assert ranges.max() <= lidar["range"] + 6 * lidar["noise"] + 1e-3, f"{stem}: range"
        if lidar.get("ply"):
            ply = read_ply(folder / lidar["ply"] / f"{stem}.ply")
            assert np.array_equal(np.stack([ply["x"], ply["y"], ply["z"], ply["i"]], 1), points)
            assert np.array_equal(ply["label"], labels), f"{stem}.ply: labels"

        # 2. Into the camera, the devkit's way.
        p2, r0, tr = calib_matrices(folder / "calib" / f"{stem}.txt")
        homogeneous = np.hstack([points[:, :3].astype(np.float64), np.ones((len(points), 1))])
        cam = (r0 @ tr @ homogeneous.T)
        pix = p2 @ cam
        z = pix[2]
        front = z > 0.5
        u = np.floor(pix[0, front] / z[front]).astype(np.int64)
        v = np.floor(pix[1, front] / z[front]).astype(np.int64)
        inside = (u >= 0) & (u < width) & (v >= 0) & (v < height)
        idx = np.flatnonzero(front)[inside]
        u, v = u[inside], v[inside]
        rgb = np.asarray(Image.open(folder / "ids" / f"{stem}.png").convert("RGB"), dtype=np.int64)
        ids = rgb[..., 0] + 256 * rgb[..., 1] + 65536 * rgb[..., 2]
        seen_id = ids[v, u]
        agree = semantic_of[seen_id] == semantic[idx]
        thing = instance[idx] > 0
        totals["points"] += len(points)
        totals["seen"] += len(idx)
        totals["semantic"] += int(agree.sum())
        totals["things"] += int(thing.sum())
        totals["thing_match"] += int((seen_id[thing] == instance[idx][thing]).sum())
        depth = np.asarray(Image.open(folder / "depth" / f"{stem}.png"), dtype=np.float64) * scale
        d = depth[v, u]
        # The camera's z of the point: R0_rect's inverse takes rect back to the camera.
        real_z = (tr @ homogeneous.T)[2, idx]
        ok = d > 0
        dz_all.append(np.abs(real_z[ok] - d[ok]))

        # 3. Into the world.
        to_world = np.array(frame["velodyne_to_world"])
        world = (to_world @ homogeneous.T).T
        ground_all.append(np.abs(world[semantic == 40, 1]))

    dz = np.concatenate(dz_all)
    ground = np.concatenate(ground_all)
    semantic_share = totals["semantic"] / totals["seen"]
    thing_share = totals["thing_match"] / max(totals["things"], 1)
    print(
        f"{folder}: {len(poses['frames'])} scans, {totals['points']} points "
        f"({totals['points'] / len(poses['frames']):.0f} a scan of {most}); "
        f"{totals['seen']} in the image: semantic = ids/ {100 * semantic_share:.2f} %, "
        f"thing instance = ids/ {100 * thing_share:.2f} % of {totals['things']}; "
        f"|z - depth| median {100 * np.median(dz):.2f} cm, 95th {100 * np.percentile(dz, 95):.2f} cm; "
        f"road |y| median {100 * np.median(ground):.2f} cm"
    )
    assert totals["seen"] > 0, "no point lands on the image"
    assert semantic_share >= 0.97, f"semantic agreement {semantic_share:.4f} < 0.97"
    assert thing_share >= 0.97, f"thing instance agreement {thing_share:.4f} < 0.97"
    assert np.median(dz) < 0.05, f"median |z - depth| {np.median(dz):.3f} m"
    assert np.median(ground) < 0.05, f"median road |y| {np.median(ground):.3f} m"


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
