#!/usr/bin/env python3
"""Check a timed drive's optical flow (a camera with `flow = true`) against its frames.

usage: check_flow.py <frames/<camera> folder>

Reads `flow/NNNNNN.png` as the KITTI 2015 devkit does (16-bit RGB read with pypng, so no
bit is lost: u = (R - 2^15) / 64, v = (G - 2^15) / 64, valid = B), and checks:

1. every frame but the last has a flow file of the image's size, B is 0 or 1, R and G are
   0 where B is 0, the sky (id 0 in ids/) is never valid, and most pixels are valid;
2. the geometry, recomputed here from poses.json alone (the camera basis from eye,
   target and up, the intrinsics; with moving traffic, each frame's `traffic.objects`
   offsets) and the frame's depth/ and ids/: every valid pixel's centre, unprojected at
   its depth, moved with its object (the next frame's offset less this one's) and
   projected by the next pose, lands where the flow says: at least 99.9 % of valid pixels
   within 1/64 px (the PNG's step) of the landings at either end of the depth file's
   rounding step. With traffic, the pixels of objects that moved must be there, and most
   of them must be off the camera-only landing (the flow holds the objects' motion);
3. warping: of the valid pixels, at least 95 % land on the same instance in the next
   frame's ids/, and the next frame's RGB sampled (bilinearly) where the flow points
   matches this frame's far better than without the flow: the mean absolute error on
   valid pixels is under half of the same pixels' error against the next frame unwarped.
"""

import json
import sys
from pathlib import Path

import numpy as np
import png
from PIL import Image


def read_flow(path):
    width, height, rows, info = png.Reader(filename=str(path)).read()
    assert info["bitdepth"] == 16 and info["planes"] == 3 and not info.get("alpha"), path
    data = np.vstack([np.asarray(r, dtype=np.int64) for r in rows]).reshape(height, width, 3)
    valid = data[..., 2]
    assert set(np.unique(valid).tolist()) <= {0, 1}, f"{path}: B is not 0 or 1"
    assert not data[valid == 0, :2].any(), f"{path}: R, G not 0 where B is 0"
    uv = (data[..., :2] - 32768) / 64.0
    return uv, valid == 1


def basis(frame):
    eye, target, up = (np.array(frame[k], dtype=np.float64) for k in ("eye", "target", "up"))
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    return eye, right, np.cross(right, forward), forward


def ids_of(path):
    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.int64)
    return rgb[..., 0] + 256 * rgb[..., 1] + 65536 * rgb[..., 2]


def bilinear(image, x, y):
    """image (h, w, 3) sampled at pixel-index coordinates x, y (edges clamped)."""
    h, w = image.shape[:2]
    x0 = np.clip(np.floor(x).astype(np.int64), 0, w - 1)
    y0 = np.clip(np.floor(y).astype(np.int64), 0, h - 1)
    x1, y1 = np.minimum(x0 + 1, w - 1), np.minimum(y0 + 1, h - 1)
    fx, fy = np.clip(x - x0, 0, 1)[:, None], np.clip(y - y0, 0, 1)[:, None]
    top = image[y0, x0] * (1 - fx) + image[y0, x1] * fx
    bottom = image[y1, x0] * (1 - fx) + image[y1, x1] * fx
    return top * (1 - fy) + bottom * fy


def motion(frame, next_frame, ids):
    """Per pixel of `ids`, how far its object moves to the next frame (world metres), from
    poses.json's traffic offsets; zero for what stands still."""
    now = frame.get("traffic", {}).get("objects", {})
    later = next_frame.get("traffic", {}).get("objects", {})
    moved = np.zeros(ids.shape + (3,))
    for key, offset in now.items():
        delta = np.array(later.get(key, offset), dtype=np.float64) - np.array(offset)
        if np.abs(delta).max() > 0:
            moved[ids == int(key)] = delta
    return moved


def main(folder):
    folder = Path(folder)
    poses = json.loads((folder / "poses.json").read_text())
    k = poses["intrinsics"]
    width, height = k["width"], k["height"]
    scale = poses["depth"]["scale"]
    frames = poses["frames"]
    assert poses.get("flow", {}).get("folder") == "flow", "poses.json has no flow section"
    assert not (folder / "flow" / f"{len(frames) - 1:06d}.png").exists(), "the last frame has flow"
    xs, ys = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    totals = dict(pixels=0, valid=0, same_id=0)
    geometry, warped_err, plain_err = [], [], []
    movers = dict(pixels=0, off_camera=0)
    for i in range(len(frames) - 1):
        stem, next_stem = f"{i:06d}", f"{i + 1:06d}"
        uv, valid = read_flow(folder / "flow" / f"{stem}.png")
        assert uv.shape == (height, width, 2), f"{stem}: flow of shape {uv.shape}"
        ids = ids_of(folder / "ids" / f"{stem}.png")
        assert not valid[ids == 0].any(), f"{stem}: sky pixels with flow"
        totals["pixels"] += width * height
        totals["valid"] += int(valid.sum())

        # 2. The geometry from poses.json alone.
        depth = np.asarray(Image.open(folder / "depth" / f"{stem}.png"), dtype=np.float64) * scale
        eye, right, up, forward = basis(frames[i])
        eye2, right2, up2, forward2 = basis(frames[i + 1])
        x, y, d = xs[valid], ys[valid], depth[valid]
        a, b = (x - k["cx"]) / k["fx"], (y - k["cy"]) / k["fy"]
        moved = motion(frames[i], frames[i + 1], ids)[valid]

        def landing(d, moved=moved):
            world = eye + d[:, None] * (forward + a[:, None] * right - b[:, None] * up) + moved
            rel = world - eye2
            cz = rel @ forward2
            u2 = k["cx"] + k["fx"] * (rel @ right2) / cz
            v2 = k["cy"] - k["fy"] * (rel @ up2) / cz
            return np.stack([u2 - x, v2 - y], 1)

        # The depth file rounds to its unit: the true depth lies within half a unit, so
        # the flow lies between the landings at either end (and is rounded to 1/64 px).
        low, high = landing(d - scale / 2), landing(d + scale / 2)
        lo, hi = np.minimum(low, high), np.maximum(low, high)
        f = uv[valid]
        geometry.append(np.maximum(np.maximum(lo - f, f - hi), 0).max(1))
        # The objects' own motion is in the flow: camera-only landings miss it.
        is_mover = np.abs(moved).max(1) > 0.01
        if is_mover.any():
            still = np.zeros_like(moved)
            camera_only = landing(d, still)[is_mover]
            movers["pixels"] += int(is_mover.sum())
            movers["off_camera"] += int((np.abs(camera_only - f[is_mover]).max(1) > 0.5).sum())

        # 3. Warping.
        tx, ty = x + uv[valid][:, 0], y + uv[valid][:, 1]
        next_ids = ids_of(folder / "ids" / f"{next_stem}.png")
        landed = next_ids[np.clip(ty.astype(np.int64), 0, height - 1), np.clip(tx.astype(np.int64), 0, width - 1)]
        totals["same_id"] += int((landed == ids[valid]).sum())
        rgb = np.asarray(Image.open(folder / "rgb" / f"{stem}.png").convert("RGB"), dtype=np.float64)
        rgb2 = np.asarray(Image.open(folder / "rgb" / f"{next_stem}.png").convert("RGB"), dtype=np.float64)
        warped = bilinear(rgb2, tx - 0.5, ty - 0.5)
        warped_err.append(np.abs(warped - rgb[valid]).mean(1))
        plain_err.append(np.abs(rgb2[valid] - rgb[valid]).mean(1))

    geometry = np.concatenate(geometry)
    warped = np.concatenate(warped_err).mean()
    plain = np.concatenate(plain_err).mean()
    valid_share = totals["valid"] / totals["pixels"]
    same = totals["same_id"] / totals["valid"]
    print(
        f"{folder}: {len(frames) - 1} flow frames, {100 * valid_share:.1f} % of pixels valid; "
        f"flow off the geometry from poses.json by more than 1/64 px: "
        f"{100 * (geometry > 1 / 64 + 1e-6).mean():.3f} % (worst {geometry.max():.3f} px); same instance after warping {100 * same:.2f} %; "
        f"RGB mean abs error warped {warped:.2f} vs unwarped {plain:.2f} (of 255)"
    )
    traffic = any("traffic" in frame for frame in frames)
    if traffic:
        print(
            f"  moving traffic: {movers['pixels']} valid pixels of objects that moved, "
            f"{100 * movers['off_camera'] / max(movers['pixels'], 1):.1f} % of them more than "
            f"half a pixel off the camera-only flow"
        )
        assert movers["pixels"] > 1000, "no valid pixel of a moving object"
        assert movers["off_camera"] > 0.5 * movers["pixels"], "the flow misses the objects' motion"
    assert valid_share > 0.5, f"only {valid_share:.3f} of pixels valid"
    assert (geometry > 1 / 64 + 1e-6).mean() <= 0.001, "flow off the geometry from poses.json"
    assert same >= 0.95, f"only {same:.4f} of valid pixels land on their instance"
    assert warped < 0.5 * plain, f"warping does not help: {warped:.2f} vs {plain:.2f}"


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
