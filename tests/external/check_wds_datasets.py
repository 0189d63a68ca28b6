"""Loads every camera's WebDataset tars of a build together with Hugging Face `datasets`
(`load_dataset("webdataset", ...)`) and checks: one row per frame of every camera, keys
distinct, every column present (not None) in every row, the depth float32 metres equal to
the camera's own depth file × its scale (from the same frames built with the files layout),
and the JSON's image entry and annotations those of the camera's COCO file, where
`datasets` keeps them (it drops the keys its first 5 samples lack: printed). With
`[splits]`, `wds/<split>/` loads as `datasets`' splits in `coco/<split>.json`'s order.

    python check_wds_datasets.py out/day-wds out/day
"""

import json
import re
import sys
import tempfile
from pathlib import Path

import datasets
import numpy as np

from check_wds import depth_metres


def compare(got, raw, path, dropped):
    """`got` (a JSON member as `datasets` gives it) equals `raw` (the JSON) where `datasets`
    kept it. `datasets` makes the member a struct of the keys of the first shard's first 5
    samples: a key those lack is not in `got` (added to `dropped`), a key they have and
    this sample lacks is None."""
    if isinstance(raw, dict):
        assert isinstance(got, dict), f"{path}: {got!r} for an object"
        for k, v in raw.items():
            if k in got:
                compare(got[k], v, f"{path}.{k}", dropped)
            else:
                dropped.add(re.sub(r"\[\d+\]", "[]", f"{path}.{k}".split(".", 1)[1]))
        extra = [k for k in got if k not in raw and got[k] is not None]
        assert not extra, f"{path}: {extra} not in the sample"
    elif isinstance(raw, list):
        assert isinstance(got, list) and len(got) == len(raw), f"{path}: {got!r}"
        for n, (g, r) in enumerate(zip(got, raw)):
            compare(g, r, f"{path}[{n}]", dropped)
    else:
        assert got == raw, f"{path}: {got!r}, the sample has {raw!r}"


def check_splits(out_dir, cache):
    """With `[splits]`: `wds/<split>/` loaded as `datasets`' splits, one row per image of
    `coco/<split>.json`, in its order."""
    data_files = {
        split.name: sorted(str(t) for t in split.glob("*.tar"))
        for split in sorted((out_dir / "wds").iterdir())
    }
    loaded = datasets.load_dataset("webdataset", data_files=data_files, cache_dir=cache)
    assert sorted(loaded) == sorted(data_files), f"splits {sorted(loaded)}"
    for split, dataset in loaded.items():
        images = json.load(open(out_dir / "coco" / f"{split}.json"))["images"]
        expected = [image["file_name"].removesuffix(".png") for image in images]
        assert dataset["__key__"] == expected, f"{split}: rows not in coco/{split}.json's order"
        print(f"datasets: split {split}, {len(dataset)} rows in coco/{split}.json's order")


def main(out_dir, files_dir):
    out_dir, files_dir = Path(out_dir), Path(files_dir)
    tars = sorted(str(t) for t in out_dir.glob("frames/*/wds/*.tar"))
    cocos = {
        camera.name: json.load(open(camera / "coco.json"))
        for camera in sorted((out_dir / "frames").iterdir())
    }
    frames = sum(len(c["images"]) for c in cocos.values())
    datasets.disable_progress_bars()
    with tempfile.TemporaryDirectory() as cache:
        dataset = datasets.load_dataset(
            "webdataset", data_files={"train": tars}, split="train", cache_dir=cache
        )
        assert len(dataset) == frames, f"{len(dataset)} rows for {frames} frames"
        keys = dataset["__key__"]
        assert len(set(keys)) == len(keys), f"{len(keys)} rows, {len(set(keys))} distinct keys"
        columns = [c for c in dataset.column_names if not c.startswith("__")]
        dataset = dataset.with_format("numpy", columns=["depth.npy"], output_all_columns=True)
        dropped = set()
        for row in dataset:
            key = row["__key__"]
            missing = [c for c in columns if row[c] is None]
            assert not missing, f"{key}: no {missing}"
            camera, stem = key.rsplit("_", 1)
            coco = cocos[camera]
            image = coco["images"][int(stem)]
            annotations = [a for a in coco["annotations"] if a["image_id"] == image["id"]]
            compare(row["json"]["image"], image, f"{key}.image", dropped)
            compare(row["json"]["annotations"], annotations, f"{key}.annotations", dropped)
            depth = np.asarray(row["depth.npy"])
            expected = depth_metres(files_dir / "frames" / camera, image)
            assert depth.dtype == np.float32, f"{key}: depth is {depth.dtype}"
            assert np.array_equal(depth, expected), f"{key}: depth is not the depth file × scale"
        if (out_dir / "wds").exists():
            check_splits(out_dir, cache)
    print(
        f"datasets.load_dataset('webdataset') over {len(tars)} tars of {len(cocos)} cameras: "
        f"{frames} rows, keys distinct, columns {columns} in every row, depth intact, JSON "
        f"intact but for the keys its first 5 samples lack: {sorted(dropped) or 'none'}"
    )


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
