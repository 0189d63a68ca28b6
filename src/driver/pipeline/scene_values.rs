//! The scene and the prepared scene: not cached, built from cached values when a stage
//! that reads them must run.

use std::sync::Arc;
use std::time::Instant;

use super::super::BuildError;
use super::super::report::{StageRun, StageStatus};
use super::Pipeline;
use std::collections::BTreeMap;

use super::super::stages::ExportInputs;
use crate::model::geometry::FacadeChoice;
use crate::model::{Building, FacadeSet, Scene};
use crate::{objects, render, scene};

impl Pipeline<'_> {
    /// The 3D scene. Not cached: it is a fast function of cached values, and only the
    /// export (and later the renderer) reads it.
    pub(super) fn scene(&mut self) -> Result<Arc<Scene>, BuildError> {
        if let Some(scene) = &self.scene {
            let scene = Arc::clone(scene);
            let diagnostics = self.scene_diagnostics.clone();
            self.read_diagnostics(&diagnostics)?;
            return Ok(scene);
        }
        if self.inputs.layout.is_map() {
            return self.map_scene();
        }
        let parsed = self.parsed()?;
        let lamps = self.lamp_sites()?;
        let buildings = self.buildings()?;
        let facades = self.facade_set()?;
        let start = Instant::now();
        let inputs = Arc::clone(&self.inputs.export);
        let built = scene::build(&scene::SceneInput {
            layout: &parsed,
            lamps: &lamps,
            buildings: &buildings,
            facades: &facades,
            widths: inputs.widths.as_deref(),
            metres_per_pixel: inputs.metres_per_pixel,
            seed: inputs.seed,
        });
        let mut built = built;
        // Inserting objects is mostly serial (each entry's placing follows its stream): the
        // other cores make the mip chains of the city's own textures (facades, roofs,
        // ground) meanwhile, which the renderer's preparation then takes.
        let (inserted, mips) = rayon::join(
            || {
                objects::insert(&objects::ObjectsInput {
                    specs: &inputs.objects,
                    layout: &parsed,
                    lamps: &lamps,
                    buildings: &buildings,
                    facades: &facades,
                    widths: inputs.widths.as_deref(),
                    meshes: &self.meshes,
                    metres_per_pixel: inputs.metres_per_pixel,
                    seed: inputs.seed,
                })
            },
            || render::TextureMips::of(&built.textures),
        );
        self.mips = mips;
        let mut inserted = inserted.map_err(|source| BuildError::Objects {
            spec: self.spec_path.clone(),
            source,
        })?;
        // `count` is an upper bound; falling short is told, with the numbers, by every
        // stage that reads the scene (see `read_diagnostics` below).
        self.scene_diagnostics = inserted.shortfalls(&inputs.objects);
        let sign_faces = std::mem::take(&mut inserted.sign_faces);
        let info = std::mem::take(&mut inserted.info);
        let first = objects::merge(&mut built, inserted);
        self.sign_faces = sign_faces.iter().map(|(i, f)| (first + i, *f)).collect();
        self.object_info = city_info(&built, first, &buildings, &facades, &inputs);
        self.object_info.extend(info.into_iter().map(Some));
        self.keep_scene(built, start)
    }

    /// The scene of a map layout: the map's city (`scene::map_city`, lamps where the map
    /// has them) and the objects placed on its streets (`objects::insert_map`).
    fn map_scene(&mut self) -> Result<Arc<Scene>, BuildError> {
        let map = self.city_map()?;
        let lamps = self.lamp_sites()?;
        let facades = self.facade_set()?;
        let start = Instant::now();
        let inputs = Arc::clone(&self.inputs.export);
        let mut built = scene::map_city(&scene::MapSceneInput {
            map: &map,
            lamps: &lamps,
            facades: &facades,
            seed: inputs.seed,
        });
        let (inserted, mips) = rayon::join(
            || {
                objects::insert_map(&objects::MapObjectsInput {
                    specs: &inputs.objects,
                    map: &map,
                    lamps: &lamps,
                    facades: &facades,
                    meshes: &self.meshes,
                    seed: inputs.seed,
                })
            },
            || render::TextureMips::of(&built.textures),
        );
        self.mips = mips;
        let mut inserted = inserted.map_err(|source| BuildError::Objects {
            spec: self.spec_path.clone(),
            source,
        })?;
        self.scene_diagnostics = inserted.shortfalls(&inputs.objects);
        let sign_faces = std::mem::take(&mut inserted.sign_faces);
        let info = std::mem::take(&mut inserted.info);
        let first = objects::merge(&mut built, inserted);
        self.sign_faces = sign_faces.iter().map(|(i, f)| (first + i, *f)).collect();
        self.object_info = vec![None; first];
        self.object_info.extend(info.into_iter().map(Some));
        self.keep_scene(built, start)
    }

    /// Keeps `built`, made since `start`, as the build's scene, and tells its diagnostics.
    fn keep_scene(&mut self, built: Scene, start: Instant) -> Result<Arc<Scene>, BuildError> {
        self.triangles = Some(built.triangle_count());
        self.runs.push(StageRun {
            stage: "scene",
            camera: None,
            key: String::new(),
            status: StageStatus::Ran,
            time: start.elapsed(),
            repaired: None,
        });
        let built = Arc::new(built);
        self.scene = Some(Arc::clone(&built));
        let diagnostics = self.scene_diagnostics.clone();
        self.read_diagnostics(&diagnostics)?;
        Ok(built)
    }

    pub(super) fn prepared_scene(&mut self) -> Result<Arc<render::PreparedScene>, BuildError> {
        if let Some(prepared) = self.prepared.get() {
            return Ok(Arc::clone(prepared));
        }
        let scene = self.scene()?;
        let prepared =
            render::prepare_with(&scene, &self.mips).map_err(|source| BuildError::Render {
                spec: self.spec_path.clone(),
                source,
            })?;
        let prepared = Arc::new(prepared);
        let _ = self.prepared.set(Arc::clone(&prepared));
        Ok(prepared)
    }
}

/// What the annotations know of the city's own first `first` objects: a building's
/// `facade` attribute (its facade's name); nothing of the others.
fn city_info(
    scene: &Scene,
    first: usize,
    buildings: &[Building],
    facades: &FacadeSet,
    inputs: &ExportInputs,
) -> Vec<Option<objects::ObjectInfo>> {
    let choice = FacadeChoice {
        facades,
        widths: inputs.widths.as_deref(),
        metres_per_pixel: inputs.metres_per_pixel,
        seed: inputs.seed,
    }
    .all(buildings);
    let facade_of: BTreeMap<String, &str> = buildings
        .iter()
        .zip(&choice)
        .filter_map(|(b, c)| {
            Some((
                scene::building_name(b.id),
                facades.facades[(*c)?].name.as_str(),
            ))
        })
        .collect();
    scene.objects[..first]
        .iter()
        .map(|object| {
            let facade = facade_of.get(&object.name)?;
            Some(objects::ObjectInfo {
                traffic: None,
                label: object.class.clone(),
                text: None,
                corners: Vec::new(),
                attributes: BTreeMap::from([("facade".to_owned(), (*facade).to_owned())]),
                keypoints: None,
            })
        })
        .collect()
}
