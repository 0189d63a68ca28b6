//! The stage table: the one place a cached stage is declared.
//!
//! Each stage has one [`Declaration`] (its name, the `VERSION` constants its key holds, the
//! stages it reads, the input files it hashes, what it writes, how it is loaded, whether it
//! is an artifact) and one typed inputs value ([`LayoutInputs`] … [`FramesInputs`]): the
//! parts of the spec it reads. That value is both the stage's argument and, serialized
//! whole, the spec part of its key ([`Keys::of`]); the evaluator (`pipeline`) holds these
//! values and no `Spec`, so a stage cannot read a spec field its key omits, and a field
//! added to a stage's inputs reaches its key without another line.
//!
//! A stage may also read what a stage it reads was keyed by (the overview and the frames
//! read the city's scale off [`ExportInputs`]): such a value sits in an `#[serde(skip)]`
//! field typed as that stage's inputs, and only for a stage in [`Declaration::reads`],
//! whose key is in its own.
//!
//! Everything else is derived from here: the keys, the order stages are evaluated and
//! verified in, the artifact list, the names a cache entry may hold (`output_names`), the
//! golden test's pins and ARCHITECTURE's key table ([`key_table`], checked by a test).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::sync::Arc;

use serde::Serialize;

use super::inputs::{FacadeInput, LayoutSource, SpecInputs};
use super::stage_key::StageKey;
use crate::cache::Load;
use crate::spec::{
    AnnotationsSpec, BuildingsSpec, CameraSpec, GenerateSpec, LampsSpec, LightingSpec, ObjectSpec,
    OnError, OutputLayout, OutputSpec, Palette, Spec, SplitsSpec, TrafficSpec, WeatherSpec,
};
use crate::{
    annotate, cameras, dataset, export, facades, lamps, layout, lidar, mirror, objects, parse,
    place, plan, preview, render, scene, sensor, traffic, views,
};

/// A cached stage, in evaluation order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    Layout,
    Mirror,
    Parse,
    Facades,
    Place,
    Lamps,
    Plan,
    Preview,
    Export,
    Overview,
    /// One per `[[cameras]]` entry.
    Frames,
    /// One when the spec has `[splits]`, else none.
    Dataset,
}

/// What a stage's cache entry may name (see `output_names`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Produces {
    /// Exactly these files.
    Fixed(&'static [&'static str]),
    /// `layout.png`, or `map.json` for a map layout (`osm::read`).
    Layout,
    /// `facades.json` and `textures/<file>.png`.
    Facades,
    /// `city.obj`, `city.mtl`, `city.glb` and `textures/<file>.png`.
    Export,
    /// Everything under `frames/<camera>/`.
    Frames,
    /// `coco/<split>.json` and everything under `yolo/`.
    Dataset,
}

/// One stage's declaration.
#[derive(Debug)]
pub struct Declaration {
    pub stage: Stage,
    /// The name in cache entries, reports and `manifest.json`.
    pub name: &'static str,
    /// The folder and entry function (for ARCHITECTURE's table).
    pub entry: &'static str,
    /// The `VERSION` constants its key holds besides `codec::VERSION`, the key's own first.
    pub versions: &'static [(&'static str, u32)],
    /// The stages whose keys its key holds: the edges of the graph.
    pub reads: &'static [Stage],
    /// The input files whose digests its key holds, in words.
    pub files: &'static str,
    pub produces: Produces,
    /// Whether a lookup reads its outputs' bytes (a stage others decode) or only verifies
    /// them (artifacts the driver copies).
    pub load: Load,
    /// Whether its outputs are files of the output folder.
    pub artifact: bool,
}

use Stage::*;

/// Every stage, in evaluation order (the order of [`Stage`]).
const TABLE: [Declaration; 12] = [
    Declaration {
        stage: Layout,
        name: "layout",
        entry: "`layout::generate` / `layout::decode` / `osm::read`",
        versions: &[("layout::VERSION", layout::VERSION)],
        reads: &[],
        files: "the layout image, when drawn (then no spec part); the extract, for a map",
        produces: Produces::Layout,
        load: Load::Bytes,
        artifact: false,
    },
    Declaration {
        stage: Mirror,
        name: "mirror",
        entry: "`mirror::mirror`",
        versions: &[("mirror::VERSION", mirror::VERSION)],
        reads: &[Layout],
        files: "",
        produces: Produces::Fixed(&["layout.png"]),
        load: Load::Bytes,
        artifact: true,
    },
    Declaration {
        stage: Parse,
        name: "parse",
        entry: "`parse::parse`",
        versions: &[("parse::VERSION", parse::VERSION)],
        reads: &[Mirror],
        files: "",
        produces: Produces::Fixed(&["parsed.json"]),
        load: Load::Bytes,
        artifact: false,
    },
    Declaration {
        stage: Facades,
        name: "facades",
        entry: "`facades::process` / `facades::process_builtin`",
        versions: &[
            ("facades::VERSION", facades::VERSION),
            ("facades::BUILTIN_VERSION", facades::BUILTIN_VERSION),
        ],
        reads: &[],
        files: "every file of the facade folder and the floors file (or the built-in set's version)",
        produces: Produces::Facades,
        load: Load::Bytes,
        artifact: false,
    },
    Declaration {
        stage: Place,
        name: "place",
        entry: "`place::place` / `place::place_map_city`",
        versions: &[("place::VERSION", place::VERSION)],
        // Facades only when `buildings.widths` is absent (see `PlaceInputs`); Layout only
        // for a map layout (`place::place_map_city` on its blocks without buildings, when
        // `fill_empty_blocks` asks for it), Parse only for a layout image.
        reads: &[Layout, Parse, Facades],
        files: "",
        produces: Produces::Fixed(&["buildings.json"]),
        load: Load::Bytes,
        artifact: false,
    },
    Declaration {
        stage: Lamps,
        name: "lamps",
        entry: "`lamps::site_lamps` / `lamps::map_lamps`",
        versions: &[("lamps::VERSION", lamps::VERSION)],
        // Layout and Place only for a map layout (`lamps::map_lamps` on its roads, out of
        // the buildings the place stage put on its blocks), Mirror and Parse only for a
        // layout image.
        reads: &[Layout, Mirror, Parse, Place],
        files: "",
        produces: Produces::Fixed(&["lamps.json"]),
        load: Load::Bytes,
        artifact: false,
    },
    Declaration {
        stage: Plan,
        name: "plan",
        entry: "`plan::assemble`",
        versions: &[("plan::VERSION", plan::VERSION)],
        reads: &[Parse, Lamps, Place],
        files: "",
        produces: Produces::Fixed(&["plan.json"]),
        load: Load::References,
        artifact: true,
    },
    Declaration {
        stage: Preview,
        name: "preview",
        entry: "`preview::draw`",
        versions: &[("preview::VERSION", preview::VERSION)],
        // Layout only for a map layout (its picture), the others only for a layout image.
        reads: &[Layout, Mirror, Parse, Lamps, Place],
        files: "",
        produces: Produces::Fixed(&["plan.png"]),
        load: Load::References,
        artifact: true,
    },
    Declaration {
        stage: Export,
        name: "export",
        entry: "`scene::build`, `objects::insert`, `export::export`",
        versions: &[
            ("export::VERSION", export::VERSION),
            ("scene::VERSION", scene::VERSION),
            ("scene::MAP_VERSION", scene::MAP_VERSION),
            ("objects::VERSION", objects::VERSION),
        ],
        // Layout only for a map layout, Parse, Lamps and Place only for a layout image.
        reads: &[Layout, Parse, Lamps, Place, Facades],
        files: "every mesh model and word file the objects name",
        produces: Produces::Export,
        load: Load::References,
        artifact: true,
    },
    Declaration {
        stage: Overview,
        name: "overview",
        entry: "`cameras::overview`, `render::render`",
        versions: &[
            ("render::VERSION", render::VERSION),
            ("cameras::VERSION", cameras::VERSION),
        ],
        reads: &[Export],
        files: "",
        produces: Produces::Fixed(&["overview.png"]),
        load: Load::References,
        artifact: true,
    },
    Declaration {
        stage: Frames,
        name: "frames",
        entry: "`views::poses`, `render::render`, `sensor::develop`, `annotate::*`",
        versions: &[
            ("render::VERSION", render::VERSION),
            ("cameras::VERSION", cameras::VERSION),
            ("annotate::VERSION", annotate::VERSION),
            ("sensor::VERSION", sensor::VERSION),
            ("views::VERSION", views::VERSION),
            ("lidar::VERSION", lidar::VERSION),
        ],
        reads: &[Export],
        files: "",
        produces: Produces::Frames,
        load: Load::References,
        artifact: true,
    },
    Declaration {
        stage: Dataset,
        name: "dataset",
        entry: "`dataset::assemble`",
        versions: &[("dataset::VERSION", dataset::VERSION)],
        // Every camera path's frames.
        reads: &[Frames],
        files: "",
        produces: Produces::Dataset,
        load: Load::References,
        artifact: true,
    },
];

impl std::fmt::Display for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Stage {
    /// Every stage, in evaluation order.
    pub const ALL: [Stage; 12] = [
        Layout, Mirror, Parse, Facades, Place, Lamps, Plan, Preview, Export, Overview, Frames,
        Dataset,
    ];

    pub fn declaration(self) -> &'static Declaration {
        &TABLE[self as usize]
    }

    pub fn name(self) -> &'static str {
        self.declaration().name
    }

    /// The stage named `name`, if any.
    pub fn named(name: &str) -> Option<Stage> {
        Stage::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The artifact stages, in evaluation order.
    pub fn artifacts() -> impl Iterator<Item = Stage> {
        Stage::ALL.into_iter().filter(|s| s.declaration().artifact)
    }
}

/// `layout`: generated from the spec, or the user's image (keyed by its bytes' hash).
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum LayoutInputs {
    Generate {
        generate: GenerateSpec,
        palette: Palette,
        seed: u64,
    },
    /// The user's image: its path (for messages) and bytes, keyed by their hash.
    Drawn {
        #[serde(skip)]
        path: std::path::PathBuf,
        #[serde(skip)]
        bytes: Arc<Vec<u8>>,
    },
    /// An OpenStreetMap extract: its path (for messages) and bytes, keyed by their hash,
    /// and the box.
    Map {
        osm_version: u32,
        bbox: Option<crate::model::GeoBox>,
        #[serde(skip)]
        path: std::path::PathBuf,
        #[serde(skip)]
        bytes: Arc<Vec<u8>>,
    },
}

impl LayoutInputs {
    /// The layout stage's inputs: `layout`, read by the driver, and the spec's generator.
    fn of(layout: &LayoutSource, spec: &Spec) -> LayoutInputs {
        let l = &spec.layout;
        match layout {
            LayoutSource::Image { path, bytes } => LayoutInputs::Drawn {
                path: path.clone(),
                bytes: Arc::new(bytes.clone()),
            },
            LayoutSource::Osm { path, bytes, bbox } => LayoutInputs::Map {
                osm_version: crate::osm::VERSION,
                bbox: *bbox,
                path: path.clone(),
                bytes: Arc::new(bytes.clone()),
            },
            LayoutSource::Generate => LayoutInputs::Generate {
                generate: l.generate.clone().unwrap_or_default(),
                palette: l.palette.clone(),
                seed: spec.seed,
            },
        }
    }

    /// Whether the layout is a map (`[layout.osm]`).
    pub fn is_map(&self) -> bool {
        matches!(self, LayoutInputs::Map { .. })
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct MirrorInputs {
    pub mirror: Vec<u8>,
}

#[derive(Clone, Debug, Serialize)]
pub struct ParseInputs {
    pub palette: Palette,
}

#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum LampsInputs {
    /// A layout image's lamps: the paper's rule on its strips.
    Layout {
        lamps: LampsSpec,
        palette: Palette,
        metres_per_pixel: f64,
    },
    /// A map's: where it has them, and seeded as `lamps` says (None: `seed_lamps` off).
    Map { lamps: Option<LampsSpec> },
}

#[derive(Clone, Debug, Serialize)]
pub struct FacadesInputs {
    pub floor_height: f64,
    pub on_error: OnError,
}

#[derive(Clone, Debug, Serialize)]
pub struct PlaceInputs {
    pub buildings: BuildingsSpec,
    pub metres_per_pixel: f64,
    pub seed: u64,
    /// A map layout's `fill_empty_blocks` (the stage runs for a map only with it).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub fill_empty_blocks: bool,
}

impl PlaceInputs {
    /// Paper 3.2: without explicit widths every facade is one building size, so the
    /// placement reads the facades.
    pub fn reads_facades(&self) -> bool {
        self.buildings.widths.is_none()
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct PlanInputs {
    pub metres_per_pixel: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct PreviewInputs {}

/// The export, and the scene and objects it writes (not cached themselves).
#[derive(Clone, Debug, Serialize)]
pub struct ExportInputs {
    pub scene_version: u32,
    /// `scene::MAP_VERSION` for a map layout; none for a layout image, whose key it
    /// leaves as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub map_scene_version: Option<u32>,
    pub objects_version: u32,
    pub objects: Vec<ObjectSpec>,
    pub widths: Option<Vec<f64>>,
    pub metres_per_pixel: f64,
    pub seed: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct OverviewInputs {
    pub cameras_version: u32,
    pub lighting: LightingSpec,
    pub seed: u64,
    /// The city's scale: the export's, whose key the overview's holds.
    #[serde(skip)]
    pub export: Arc<ExportInputs>,
}

/// One camera path's frames: the content (`path`, keying its plan and chunks) and how
/// they are written (`output`).
#[derive(Clone, Debug)]
pub struct FramesInputs {
    pub path: PathInputs,
    pub output: OutputSpec,
}

/// What a camera path's frames hold, whatever `[output]` says.
#[derive(Clone, Debug, Serialize)]
pub struct PathInputs {
    /// `cameras::VERSION`, `annotate::VERSION`.
    pub versions: [u32; 2],
    pub sensor_version: u32,
    pub views_version: u32,
    /// `lidar::VERSION`, with the camera's `lidar` only: a camera without one keys as
    /// before.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lidar_version: Option<u32>,
    /// `traffic::VERSION` and `[traffic]`, when the traffic moves: a spec without it keys
    /// as before.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub traffic: Option<(u32, TrafficSpec)>,
    pub camera: CameraSpec,
    pub lighting: LightingSpec,
    pub weather: WeatherSpec,
    pub annotations: AnnotationsSpec,
    pub seed: u64,
    /// The city's scale and objects: the export's, whose key the path's holds.
    #[serde(skip)]
    pub export: Arc<ExportInputs>,
}

/// The dataset-level files: the splits, whether YOLO is written, and the camera paths
/// they gather (by name, in spec order).
#[derive(Clone, Debug, Serialize)]
pub struct DatasetInputs {
    pub splits: SplitsSpec,
    pub yolo: bool,
    /// Off, it stays out of the key (which is then as before the switch existed).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub cityscapes: bool,
    pub cameras: Vec<String>,
    pub seed: u64,
    /// With `[output] layout = "webdataset"`, its `samples_per_shard` (the split shards');
    /// absent from the key with the files layout.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub webdataset: Option<u32>,
}

impl PathInputs {
    /// What `camera`'s path of `spec` reads, in a city keyed by `export`.
    fn of(spec: &Spec, camera: &CameraSpec, export: &Arc<ExportInputs>) -> PathInputs {
        PathInputs {
            versions: [cameras::VERSION, annotate::VERSION],
            sensor_version: sensor::VERSION,
            views_version: views::VERSION,
            lidar_version: camera.lidar.is_some().then_some(lidar::VERSION),
            traffic: spec.traffic.clone().map(|t| (traffic::VERSION, t)),
            // A camera's own lighting and weather replace the spec's, in the key once (as
            // `lighting`, `weather`): a camera without them keys as before.
            camera: CameraSpec {
                lighting: None,
                weather: None,
                ..camera.clone()
            },
            lighting: camera
                .lighting
                .clone()
                .unwrap_or_else(|| spec.lighting.clone()),
            weather: camera
                .weather
                .clone()
                .unwrap_or_else(|| spec.weather.clone()),
            annotations: spec.annotations.clone(),
            seed: spec.seed,
            export: Arc::clone(export),
        }
    }
}

/// Every stage's inputs, for one spec: all the evaluator knows of it.
#[derive(Clone, Debug)]
pub struct Inputs {
    pub layout: LayoutInputs,
    pub mirror: MirrorInputs,
    pub parse: ParseInputs,
    pub lamps: LampsInputs,
    pub facades: FacadesInputs,
    pub place: PlaceInputs,
    pub plan: PlanInputs,
    pub preview: PreviewInputs,
    pub export: Arc<ExportInputs>,
    pub overview: OverviewInputs,
    /// One per `[[cameras]]` entry.
    pub frames: Vec<FramesInputs>,
    /// With `[splits]`.
    pub dataset: Option<DatasetInputs>,
}

impl Inputs {
    /// The parts of `spec` each stage reads, and the layout image it names, if any.
    pub fn of(spec: &Spec, layout: &LayoutSource) -> Inputs {
        let l = &spec.layout;
        // A map is in metres.
        let map = matches!(layout, LayoutSource::Osm { .. });
        let mpp = if map { 1.0 } else { l.metres_per_pixel };
        let export = Arc::new(ExportInputs {
            scene_version: scene::VERSION,
            map_scene_version: map.then_some(scene::MAP_VERSION),
            objects_version: objects::VERSION,
            objects: spec.objects.clone(),
            widths: spec.buildings.widths.clone(),
            metres_per_pixel: mpp,
            seed: spec.seed,
        });
        let frames = spec
            .cameras
            .iter()
            .map(|camera| FramesInputs {
                path: PathInputs::of(spec, camera, &export),
                output: spec.output.clone(),
            })
            .collect();
        Inputs {
            layout: LayoutInputs::of(layout, spec),
            mirror: MirrorInputs {
                mirror: l.mirror.clone(),
            },
            parse: ParseInputs {
                palette: l.palette.clone(),
            },
            lamps: match &l.osm {
                Some(osm) => LampsInputs::Map {
                    lamps: osm.seed_lamps.then(|| spec.lamps.clone()),
                },
                None => LampsInputs::Layout {
                    lamps: spec.lamps.clone(),
                    palette: l.palette.clone(),
                    metres_per_pixel: mpp,
                },
            },
            facades: FacadesInputs {
                floor_height: spec.facades.floor_height,
                on_error: spec.facades.on_error,
            },
            place: PlaceInputs {
                buildings: spec.buildings.clone(),
                metres_per_pixel: mpp,
                seed: spec.seed,
                fill_empty_blocks: l.osm.as_ref().is_some_and(|osm| osm.fill_empty_blocks),
            },
            plan: PlanInputs {
                metres_per_pixel: mpp,
            },
            preview: PreviewInputs {},
            overview: OverviewInputs {
                cameras_version: cameras::VERSION,
                lighting: spec.lighting.clone(),
                seed: spec.seed,
                export: Arc::clone(&export),
            },
            export,
            frames,
            dataset: spec.splits.as_ref().map(|splits| DatasetInputs {
                splits: splits.clone(),
                yolo: spec.annotations.yolo,
                cityscapes: spec.annotations.cityscapes,
                cameras: spec.cameras.iter().map(|c| c.name.clone()).collect(),
                seed: spec.seed,
                webdataset: (spec.output.layout == OutputLayout::Webdataset)
                    .then_some(spec.output.samples_per_shard),
            }),
        }
    }

    /// The spec part of `stage`'s key: its inputs, serialized whole (camera path `camera`
    /// for `frames`).
    fn key_part(&self, stage: Stage, camera: usize) -> serde_json::Value {
        let value = match stage {
            Layout => serde_json::to_value(&self.layout),
            Mirror => serde_json::to_value(&self.mirror),
            Parse => serde_json::to_value(&self.parse),
            Lamps => serde_json::to_value(&self.lamps),
            Facades => serde_json::to_value(&self.facades),
            Place => serde_json::to_value(&self.place),
            Plan => serde_json::to_value(&self.plan),
            Preview => serde_json::to_value(&self.preview),
            Export => serde_json::to_value(&*self.export),
            Overview => serde_json::to_value(&self.overview),
            Frames => serde_json::to_value(&self.frames[camera].path),
            Dataset => serde_json::to_value(&self.dataset),
        };
        value.expect("stage inputs serialize to JSON")
    }

    /// Whether `stage`'s key holds the key of `read`, one of its declared reads.
    fn uses(&self, stage: Stage, read: Stage) -> bool {
        if !self.runs(read) {
            return false;
        }
        let map = self.layout.is_map();
        match (stage, read) {
            (Place, Facades) => self.place.reads_facades(),
            (Export | Preview | Place | Lamps, Layout) | (Lamps, Place) => map,
            _ => true,
        }
    }

    /// Whether the spec has `stage`: a map layout has no mirror, parse or plan stage (its
    /// streets and buildings come from the map), and a place stage only to fill its blocks
    /// without buildings.
    pub fn runs(&self, stage: Stage) -> bool {
        if !self.layout.is_map() {
            return true;
        }
        match stage {
            Mirror | Parse | Plan => false,
            Place => self.place.fill_empty_blocks,
            _ => true,
        }
    }
}

/// Every stage's key, from the inputs and the input files' hashes alone.
pub struct Keys {
    /// Every stage's but the frames'.
    city: BTreeMap<Stage, String>,
    /// One per `[[cameras]]` entry.
    pub frames: Vec<String>,
    /// With `[splits]`.
    pub dataset: Option<String>,
    /// Per camera, the key of its frames' content, whatever `[output]` says: its plan
    /// and chunks are keyed by it, so a change of layout renders nothing again.
    pub paths: Vec<String>,
    /// What each key above is the hash of, by key (for `cityspec explain`).
    pub made: BTreeMap<String, StageKey>,
}

impl Keys {
    pub fn of(inputs: &Inputs, files: &SpecInputs) -> Keys {
        let mut keys = Keys {
            city: BTreeMap::new(),
            frames: Vec::new(),
            dataset: None,
            paths: Vec::new(),
            made: BTreeMap::new(),
        };
        for stage in Stage::ALL.into_iter().filter(|s| inputs.runs(*s)) {
            let cameras = match stage {
                Frames => inputs.frames.len(),
                Dataset => usize::from(inputs.dataset.is_some()),
                _ => 1,
            };
            for camera in 0..cameras {
                let declaration = stage.declaration();
                let mut key = StageKey::new(declaration.name, declaration.versions[0].1)
                    .spec_whole(inputs.key_part(stage, camera));
                for &read in declaration.reads {
                    if read == Frames {
                        // Every camera path's key, in spec order, as one input.
                        let all = crate::hash::sha256_hex(keys.frames.join("\n").as_bytes());
                        key = key.input("frames", &all);
                    } else if inputs.uses(stage, read) {
                        key = key.input(read.name(), &keys.city[&read]);
                    }
                }
                for (name, digest) in file_digests(stage, files) {
                    key = key.input(name, &digest);
                }
                let key = key.finish_into(&mut keys.made);
                match stage {
                    Frames => keys.add_path(key, &inputs.frames[camera].output),
                    Dataset => keys.dataset = Some(key),
                    _ => {
                        keys.city.insert(stage, key);
                    }
                }
            }
        }
        keys
    }

    /// A camera path's content key, and its frames' key: the same for plain files, or
    /// the content key wrapped with `[output]` for WebDataset shards.
    fn add_path(&mut self, path: String, output: &OutputSpec) {
        let frames = match output.layout {
            OutputLayout::Files => path.clone(),
            OutputLayout::Webdataset => StageKey::new("frames", super::webdataset::VERSION)
                .spec("output", output)
                .input("path", &path)
                .finish_into(&mut self.made),
        };
        self.frames.push(frames);
        self.paths.push(path);
    }

    /// `stage`'s key (`camera` for `frames`).
    pub fn of_stage(&self, stage: Stage, camera: Option<usize>) -> &str {
        match (stage, camera) {
            (Frames, Some(camera)) => &self.frames[camera],
            (Dataset, _) => self.dataset.as_deref().unwrap_or_default(),
            _ => &self.city[&stage],
        }
    }

    /// Every stage's (stage, camera, key), in evaluation order.
    pub fn all(&self) -> Vec<(Stage, Option<usize>, &str)> {
        Stage::ALL
            .into_iter()
            .flat_map(|stage| match stage {
                Frames => (0..self.frames.len())
                    .map(|c| (stage, Some(c), self.frames[c].as_str()))
                    .collect::<Vec<_>>(),
                Dataset => self
                    .dataset
                    .iter()
                    .map(|key| (stage, None, key.as_str()))
                    .collect(),
                _ => self
                    .city
                    .get(&stage)
                    .map(|key| (stage, None, key.as_str()))
                    .into_iter()
                    .collect(),
            })
            .collect()
    }
}

/// The digests of the input files `stage` reads, by name in its key.
fn file_digests(stage: Stage, files: &SpecInputs) -> Vec<(&'static str, String)> {
    match stage {
        Layout => match &files.layout {
            LayoutSource::Generate => Vec::new(),
            LayoutSource::Image { bytes, .. } => {
                vec![("image", crate::hash::sha256_hex(bytes))]
            }
            LayoutSource::Osm { bytes, .. } => {
                vec![("extract", crate::hash::sha256_hex(bytes))]
            }
        },
        Facades => match &files.facades {
            FacadeInput::Builtin => vec![("builtin", facades::BUILTIN_VERSION.to_string())],
            FacadeInput::Folder { digest, .. } => vec![("folder", digest.clone())],
        },
        Export => vec![("meshes", files.meshes_digest.clone())],
        _ => Vec::new(),
    }
}

/// ARCHITECTURE's key table, made from the declarations and the inputs' field names (of
/// `spec`'s inputs: pass one with a generated layout and a camera).
pub fn key_table(spec: &Spec) -> String {
    // With splits, so that the dataset stage has inputs to list.
    let mut spec = spec.clone();
    spec.splits.get_or_insert(SplitsSpec {
        train: 1.0,
        val: 0.0,
        test: 0.0,
        by: Default::default(),
    });
    let inputs = Inputs::of(&spec, &LayoutSource::Generate);
    let mut table = String::from(
        "| stage | entry | `VERSION`s in its key | spec parts in its key | stages it reads | input files |\n\
         |---|---|---|---|---|---|\n",
    );
    for stage in Stage::ALL {
        let d = stage.declaration();
        let parts = match inputs.key_part(stage, 0) {
            serde_json::Value::Object(map) => map.keys().map(|k| format!("`{k}`")).collect(),
            _ => Vec::new(),
        };
        let versions: Vec<String> = d.versions.iter().map(|(n, _)| format!("`{n}`")).collect();
        let reads: Vec<&str> = d.reads.iter().map(|s| s.name()).collect();
        let _ = writeln!(
            table,
            "| {} | {} | {} | {} | {} | {} |",
            d.name,
            d.entry,
            versions.join(", "),
            dash(&parts.join(", ")),
            dash(&reads.join(", ")),
            dash(d.files),
        );
    }
    table
}

fn dash(text: &str) -> &str {
    if text.is_empty() { "—" } else { text }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spec with a generated layout, objects and a camera.
    fn test_spec() -> Spec {
        let text = "version = 1\nname = 'a'\n[layout.generate]\n\
                    [[objects]]\nkind = 'car'\nlabel = 'car'\n\
                    [[cameras]]\nname = 'c'\npath = 'roads'\nframes = 1\n";
        toml::from_str(text).expect("the test spec parses")
    }

    #[test]
    fn the_table_is_in_the_order_of_the_enum() {
        for (i, stage) in Stage::ALL.into_iter().enumerate() {
            assert_eq!(TABLE[i].stage, stage);
            assert_eq!(stage as usize, i);
            assert_eq!(Stage::named(stage.name()), Some(stage));
        }
    }

    #[test]
    fn a_stage_reads_only_stages_evaluated_before_it() {
        for stage in Stage::ALL {
            for read in stage.declaration().reads {
                assert!(read < &stage, "{} reads {}", stage.name(), read.name());
            }
        }
    }

    /// The `VERSION`s an inputs value carries as fields are the ones its declaration
    /// lists: the golden pins and the key cannot disagree on them.
    #[test]
    fn versions_in_the_inputs_are_the_declared_ones() {
        let spec = test_spec();
        let inputs = Inputs::of(&spec, &LayoutSource::Generate);
        for stage in Stage::ALL {
            let mut carried = vec![stage.declaration().versions[0].1];
            if let serde_json::Value::Object(map) = inputs.key_part(stage, 0) {
                for (name, value) in map {
                    if name.contains("version") {
                        match value {
                            serde_json::Value::Array(all) => carried
                                .extend(all.iter().filter_map(|v| v.as_u64()).map(|v| v as u32)),
                            v => carried.extend(v.as_u64().map(|v| v as u32)),
                        }
                    }
                }
            }
            let mut declared: Vec<u32> = stage
                .declaration()
                .versions
                .iter()
                // In a key only when the spec uses them (the test spec does not).
                .filter(|(name, _)| {
                    ![
                        "facades::BUILTIN_VERSION",
                        "lidar::VERSION",
                        "scene::MAP_VERSION",
                    ]
                    .contains(name)
                })
                .map(|(_, v)| *v)
                .collect();
            let mut sorted = carried.clone();
            sorted.sort_unstable();
            declared.sort_unstable();
            assert_eq!(sorted, declared, "{}", stage.name());
        }
    }

    /// Every field of a stage's inputs is in its key: changing any spec value a stage
    /// reads changes that stage's key.
    #[test]
    fn every_input_reaches_the_key() {
        let spec = test_spec();
        let files = SpecInputs::generated();
        let base = Keys::of(&Inputs::of(&spec, &LayoutSource::Generate), &files);
        let mut changed = spec.clone();
        changed.layout.metres_per_pixel = 0.6;
        let after = Keys::of(&Inputs::of(&changed, &LayoutSource::Generate), &files);
        for stage in [Lamps, Place, Plan, Export, Overview, Frames] {
            assert_ne!(
                base.of_stage(stage, Some(0)),
                after.of_stage(stage, Some(0)),
                "{}",
                stage.name()
            );
        }
        for stage in [Layout, Mirror, Parse, Facades] {
            assert_eq!(base.of_stage(stage, None), after.of_stage(stage, None));
        }
    }

    /// A camera's extra outputs are in its frames' key when on, and off leave the key as
    /// it was before they existed (no field in it).
    #[test]
    fn extra_frame_outputs_key_only_when_on() {
        let spec = test_spec();
        let files = SpecInputs::generated();
        let inputs = Inputs::of(&spec, &LayoutSource::Generate);
        let part = inputs.key_part(Frames, 0).to_string();
        assert!(!part.contains("normals"), "{part}");
        let base = Keys::of(&inputs, &files);
        let mut changed = spec.clone();
        changed.cameras[0].normals = true;
        let after = Keys::of(&Inputs::of(&changed, &LayoutSource::Generate), &files);
        assert_ne!(
            base.of_stage(Frames, Some(0)),
            after.of_stage(Frames, Some(0))
        );
        assert_eq!(base.of_stage(Export, None), after.of_stage(Export, None));
    }
}
