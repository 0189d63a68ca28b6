"""Reads a build's WebDataset tars with the `webdataset` package and checks them against
the same frames built with the files layout (same cache, so the same frames):

- the sample keys are distinct over every camera's shards together;
- per camera, one sample per COCO image, in order, keyed `<camera>_<NNNNNN>`; its JSON
  holds that image entry and exactly its annotations, every box inside the image; its
  members are the same in every sample of every camera;
- with the default decoders (`.decode("rgb")`) the depth is float32 metres equal to the
  camera's own depth file × its scale, and the RGB image equals its `rgb/` file; the ids
  image read raw equals its `ids/` file, and so do the Cityscapes images (with
  `[annotations] cityscapes = true`) their `semantic/` files;
- `to_tuple("png;jpg", "json")` finds every sample of every camera;
- with `[splits]`: each split's shards `wds/<split>/` hold its frames in the order of
  `coco/<split>.json`'s images, whose `file_name` is the sample's `<key>.png`, each sample
  the camera's own, member for member.

    python check_wds.py out/day-wds out/day
"""

import hashlib
import io
import json
import sys
from pathlib import Path

import numpy as np
import webdataset as wds
from PIL import Image

MEMBERS = {"depth.npy", "icdar.txt", "ids.png", "json", "png"}
# With `[annotations] cityscapes = true`: member -> the files layout's `semantic/` suffix.
SEMANTIC = {"labelids.png": "labelIds", "instanceids.png": "instanceIds",
            "color.png": "color", "panoptic.png": "panoptic"}


def depth_metres(camera_files, image):
    """A frame's depth file of the files layout (`camera_files`: its `frames/<camera>/`), in
    metres as float32."""
    depth = image["depth"]
    path = camera_files / depth["file_name"]
    if depth["format"] == "f32":
        return np.load(path)
    units = np.array(Image.open(path))
    assert units.dtype == np.uint16, f"{path}: {units.dtype}"
    return (units.astype(np.float64) * depth["scale"]).astype(np.float32)


def digests(sample):
    """A raw sample's members, each as its SHA-256."""
    return {k: hashlib.sha256(v).hexdigest() for k, v in sample.items() if not k.startswith("__")}


def check_camera(camera_dir, files_dir, keys, columns):
    """Checks one camera's shards; adds its samples' members' digests to `keys` and its
    member sets to `columns`. Returns its frames."""
    camera = camera_dir.name
    tars = sorted(str(t) for t in (camera_dir / "wds").glob("*.tar"))
    coco = json.load(open(camera_dir / "coco.json"))
    images = coco["images"]
    by_image = {}
    for ann in coco["annotations"]:
        by_image.setdefault(ann["image_id"], []).append(ann)
    raw = wds.WebDataset(tars, shardshuffle=False, empty_check=False)
    decoded = wds.WebDataset(tars, shardshuffle=False, empty_check=False).decode("rgb")
    seen = 0
    for sample, dec in zip(raw, decoded):
        assert seen < len(images), f"{camera}: more samples than the {len(images)} COCO images"
        image = images[seen]
        key = sample["__key__"]
        assert key == f"{camera}_{seen:06d}", f"{camera}: sample {seen} has key {key}"
        assert dec["__key__"] == key
        assert key not in keys, f"{key}: in two shards"
        keys[key] = digests(sample)
        columns.add(tuple(sorted(k for k in sample if not k.startswith("__"))))
        meta = json.loads(sample["json"])
        assert meta["image"] == image, f"{key}: image entry differs from COCO"
        assert meta["annotations"] == by_image.get(image["id"], []), f"{key}: annotations differ"
        for ann in meta["annotations"]:
            x, y, w, h = ann["bbox"]
            assert 0 <= x and 0 <= y and x + w <= image["width"] and y + h <= image["height"]
        stem = f"{seen:06d}"
        files = files_dir / "frames" / camera
        assert sample["ids.png"] == (files / "ids" / f"{stem}.png").read_bytes(), f"{key}: ids"
        for member, suffix in SEMANTIC.items():
            if member in sample:
                semantic = files / "semantic" / f"{stem}_{suffix}.png"
                assert sample[member] == semantic.read_bytes(), f"{key}: {member}"
        ids = Image.open(io.BytesIO(sample["ids.png"]))
        assert (ids.mode, ids.size) == ("RGB", (image["width"], image["height"])), f"{key}: ids"
        # The default decoders: RGB as float in [0, 1], depth (.npy) as it is stored.
        rgb = np.array(Image.open(files / "rgb" / f"{stem}.png")).astype(np.float32) / 255
        assert dec["png"].shape == rgb.shape and np.allclose(dec["png"], rgb, atol=1e-6), f"{key}: rgb"
        depth = dec["depth.npy"]
        expected = depth_metres(files, image)
        assert depth.dtype == np.float32, f"{key}: depth is {depth.dtype}"
        assert depth.shape == (image["height"], image["width"]), f"{key}: depth {depth.shape}"
        assert np.array_equal(depth, expected), f"{key}: depth is not the depth file × scale"
        assert (depth == 0).any() or depth.max() > 1, f"{key}: no depth in metres"
        seen += 1
    assert seen == len(images), f"{camera}: {seen} samples for {len(images)} COCO images"
    tuples = wds.WebDataset(tars, shardshuffle=False, empty_check=False).to_tuple("png;jpg", "json")
    found = sum(1 for _ in tuples)
    assert found == len(images), f"{camera}: to_tuple('png;jpg', 'json') found {found} of {len(images)}"
    print(
        f"{camera}: {seen} samples in {len(tars)} shards match COCO "
        f"({len(coco['annotations'])} annotations); depth float32 metres = depth file × scale; "
        f"to_tuple('png;jpg', 'json') finds {found}"
    )
    return seen


def check_splits(out_dir, samples):
    """Each split's shards against its COCO file and the cameras' samples (`samples`: key
    → members' digests)."""
    coco_files = sorted((out_dir / "coco").glob("*.json"))
    assert coco_files, f"{out_dir}: no coco/<split>.json"
    seen = set()
    for coco_file in coco_files:
        split = coco_file.stem
        images = json.load(open(coco_file))["images"]
        tars = sorted(str(t) for t in (out_dir / "wds" / split).glob("*.tar"))
        dataset = wds.WebDataset(tars, shardshuffle=False, empty_check=False)
        got = [(sample["__key__"], digests(sample)) for sample in dataset]
        keys = [key for key, _ in got]
        expected = [image["file_name"].removesuffix(".png") for image in images]
        assert keys == expected, f"{split}: samples not in the order of coco/{split}.json"
        for image in images:
            key = image["file_name"].removesuffix(".png")
            assert image["file_name"] == f"{key}.png", f"{split}: {image['file_name']}"
            assert image["depth"]["file_name"] == f"{key}.depth.npy", f"{split}: {key} depth"
        for key, members in got:
            assert members == samples[key], f"{split}: {key} is not its camera's sample"
            assert key not in seen, f"{key} in two splits"
            seen.add(key)
        print(f"wds/{split}/: {len(got)} samples in {len(tars)} shards, in coco/{split}.json's order")
    assert seen == set(samples), f"{len(samples) - len(seen)} frames in no split"


def main(out_dir, files_dir):
    out_dir, files_dir = Path(out_dir), Path(files_dir)
    keys, columns = {}, set()
    total = sum(
        check_camera(camera, files_dir, keys, columns)
        for camera in sorted((out_dir / "frames").iterdir())
    )
    assert len(keys) == total, f"{len(keys)} distinct keys for {total} samples"
    assert len(columns) == 1, f"samples differ in their members: {columns}"
    members = set(next(iter(columns)))
    optional = {"yolo.txt"} | set(SEMANTIC)
    assert MEMBERS <= members and members <= MEMBERS | optional, f"members {members}"
    semantic = members & set(SEMANTIC)
    assert not semantic or semantic == set(SEMANTIC), f"some Cityscapes members: {semantic}"
    print(f"{out_dir}: {total} samples, keys distinct over every camera, members {sorted(members)}")
    if (out_dir / "coco").exists():
        check_splits(out_dir, keys)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
