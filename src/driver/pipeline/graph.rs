//! The stage graph: for each cached stage, what it gathers (its inputs, fetched or run
//! on demand) and how it runs; the typed values later stages read.

use std::sync::Arc;

use image::RgbImage;

use super::super::BuildError;
use super::super::codec;
use super::super::inputs::FacadeInput;
use super::super::stages::{LampsInputs, LayoutInputs, OverviewInputs, Stage};
use super::Pipeline;
use super::evaluate::{one, value};
use super::frames_stage::lighting;
use crate::cache::Blob;
use crate::model::{Building, FacadeSet, Lamp, MapBuilding, OsmMap, ParsedLayout, Scene};
use crate::{
    cameras, export, facades, lamps, layout, mirror, parse, place, plan, preview, render, rng,
};

impl Pipeline<'_> {
    pub(super) fn need_layout(&mut self) -> Result<(), BuildError> {
        if self.inputs.layout.is_map() {
            return self.need_map();
        }
        self.stage(
            Stage::Layout,
            None,
            |p| &mut p.layout,
            |_| Ok(()),
            |p, ()| {
                let image = match &p.inputs.layout {
                    LayoutInputs::Generate {
                        generate,
                        palette,
                        seed,
                    } => {
                        let mut stream = rng::stream(*seed, "layout", 0);
                        layout::generate(generate, palette, &mut stream).image
                    }
                    LayoutInputs::Drawn { path, bytes } => {
                        layout::decode(bytes).map_err(|source| BuildError::Layout {
                            spec: p.spec_path.clone(),
                            file: path.clone(),
                            source,
                        })?
                    }
                    LayoutInputs::Map { .. } => unreachable!("a map is read by need_map"),
                };
                let png = codec::encode_png(&image);
                Ok((image, one("layout.png", png)))
            },
        )
    }

    /// The layout stage of a map layout: the extract read into `map.json`.
    fn need_map(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Layout,
            None,
            |p| &mut p.map,
            |_| Ok(()),
            |p, ()| {
                let LayoutInputs::Map {
                    bbox, path, bytes, ..
                } = &p.inputs.layout
                else {
                    unreachable!("need_map runs for a map layout")
                };
                let map = crate::osm::read(bytes, *bbox).map_err(|source| BuildError::Osm {
                    file: path.clone(),
                    source,
                })?;
                let json = codec::to_json(&map);
                Ok((map, one("map.json", json)))
            },
        )
    }

    /// The map of a map layout.
    pub(super) fn osm_map(&mut self) -> Result<Arc<OsmMap>, BuildError> {
        self.need_map()?;
        value(&mut self.map, Stage::Layout, |o| {
            codec::from_json(codec::output(o, "map.json")?)
        })
    }

    /// The map a map layout's city is built on: the map, with the place stage's
    /// buildings on its blocks without any when the spec fills them.
    pub(super) fn city_map(&mut self) -> Result<Arc<OsmMap>, BuildError> {
        if let Some(map) = &self.city_map {
            return Ok(Arc::clone(map));
        }
        let map = self.osm_map()?;
        let city = if self.inputs.runs(Stage::Place) {
            let placed = self.placed_on_map()?;
            let mut city = (*map).clone();
            city.buildings.extend(placed.iter().cloned());
            Arc::new(city)
        } else {
            map
        };
        self.city_map = Some(Arc::clone(&city));
        Ok(city)
    }

    /// The city's streets: the parsed layout's roads, or the map's.
    pub(super) fn streets(&mut self) -> Result<super::CityStreets, BuildError> {
        Ok(if self.inputs.layout.is_map() {
            super::CityStreets::Map(self.city_map()?)
        } else {
            super::CityStreets::Layout(self.parsed()?)
        })
    }

    pub(super) fn layout_image(&mut self) -> Result<Arc<RgbImage>, BuildError> {
        self.need_layout()?;
        value(&mut self.layout, Stage::Layout, |o| {
            codec::decode_png(codec::output(o, "layout.png")?)
        })
    }

    pub(super) fn need_mirror(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Mirror,
            None,
            |p| &mut p.mirror,
            |p| p.layout_image(),
            |p, layout| {
                let image = mirror::mirror(&layout, &p.inputs.mirror.mirror);
                let png = codec::encode_png(&image);
                Ok((image, one("layout.png", png)))
            },
        )
    }

    pub(super) fn mirrored_image(&mut self) -> Result<Arc<RgbImage>, BuildError> {
        self.need_mirror()?;
        value(&mut self.mirror, Stage::Mirror, |o| {
            codec::decode_png(codec::output(o, "layout.png")?)
        })
    }

    pub(super) fn need_parse(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Parse,
            None,
            |p| &mut p.parse,
            |p| p.mirrored_image(),
            |p, image| {
                let parsed = parse::parse(&image, &p.inputs.parse.palette);
                let json = codec::to_json(&parsed);
                Ok((parsed, one("parsed.json", json)))
            },
        )
    }

    pub(super) fn parsed(&mut self) -> Result<Arc<ParsedLayout>, BuildError> {
        self.need_parse()?;
        value(&mut self.parse, Stage::Parse, |o| {
            codec::from_json(codec::output(o, "parsed.json")?)
        })
    }

    pub(super) fn need_lamps(&mut self) -> Result<(), BuildError> {
        let LampsInputs::Layout {
            lamps,
            palette,
            metres_per_pixel: mpp,
        } = &self.inputs.lamps
        else {
            return self.need_map_lamps();
        };
        let (spacing, min_distance) = (lamps.spacing / mpp, lamps.min_distance / mpp);
        let palette = palette.clone();
        let gather = |p: &mut Self| Ok((p.mirrored_image()?, p.parsed()?));
        self.stage(
            Stage::Lamps,
            None,
            |p| &mut p.lamps,
            gather,
            move |_, (image, parsed)| {
                let sites = lamps::site_lamps(&image, &parsed, &palette, spacing, min_distance);
                let json = codec::to_json(&sites);
                Ok((sites, one("lamps.json", json)))
            },
        )
    }

    /// A map layout's lamps stage: where the map has lamps, and seeded along the rest of
    /// its roads, out of its buildings and the ones placed on its blocks.
    fn need_map_lamps(&mut self) -> Result<(), BuildError> {
        let gather = |p: &mut Self| p.city_map();
        self.stage(
            Stage::Lamps,
            None,
            |p| &mut p.lamps,
            gather,
            |p, map| {
                let seeded = match &p.inputs.lamps {
                    LampsInputs::Map { lamps } => lamps.as_ref(),
                    LampsInputs::Layout { .. } => None,
                };
                let sites = lamps::map_lamps(&map, seeded);
                let json = codec::to_json(&sites);
                Ok((sites, one("lamps.json", json)))
            },
        )
    }

    /// The lamps stage's lamps.
    pub(super) fn lamp_sites(&mut self) -> Result<Arc<Vec<Lamp>>, BuildError> {
        self.need_lamps()?;
        value(&mut self.lamps, Stage::Lamps, |o| {
            codec::from_json(codec::output(o, "lamps.json")?)
        })
    }

    pub(super) fn need_place(&mut self) -> Result<(), BuildError> {
        if self.inputs.layout.is_map() {
            return self.need_map_place();
        }
        let gather = |p: &mut Self| Ok((p.parsed()?, p.place_facades()?));
        self.stage(
            Stage::Place,
            None,
            |p| &mut p.place,
            gather,
            |p, (parsed, facades)| {
                let inputs = &p.inputs.place;
                let buildings = place::place_city(
                    &parsed.blocks,
                    &inputs.buildings,
                    facades.as_deref(),
                    inputs.metres_per_pixel,
                    inputs.seed,
                );
                let json = codec::to_json(&buildings);
                Ok((buildings, one("buildings.json", json)))
            },
        )
    }

    /// The facades placing reads: only when the spec gives no widths (paper 3.2).
    fn place_facades(&mut self) -> Result<Option<Arc<FacadeSet>>, BuildError> {
        Ok(match self.inputs.place.reads_facades() {
            false => None,
            true => Some(self.facade_set()?),
        })
    }

    /// A map layout's place stage: buildings on the map's blocks without any.
    fn need_map_place(&mut self) -> Result<(), BuildError> {
        let gather = |p: &mut Self| Ok((p.osm_map()?, p.place_facades()?));
        self.stage(
            Stage::Place,
            None,
            |p| &mut p.map_place,
            gather,
            |p, (map, facades)| {
                let inputs = &p.inputs.place;
                let buildings =
                    place::place_map_city(&map, &inputs.buildings, facades.as_deref(), inputs.seed);
                let json = codec::to_json(&buildings);
                Ok((buildings, one("buildings.json", json)))
            },
        )
    }

    /// The buildings a map layout's place stage put on its blocks without any.
    fn placed_on_map(&mut self) -> Result<Arc<Vec<MapBuilding>>, BuildError> {
        self.need_map_place()?;
        value(&mut self.map_place, Stage::Place, |o| {
            codec::from_json(codec::output(o, "buildings.json")?)
        })
    }

    pub(super) fn buildings(&mut self) -> Result<Arc<Vec<Building>>, BuildError> {
        self.need_place()?;
        value(&mut self.place, Stage::Place, |o| {
            codec::from_json(codec::output(o, "buildings.json")?)
        })
    }

    pub(super) fn need_plan(&mut self) -> Result<(), BuildError> {
        let gather = |p: &mut Self| Ok((p.parsed()?, p.lamp_sites()?, p.buildings()?));
        self.stage(
            Stage::Plan,
            None,
            |p| &mut p.plan,
            gather,
            |p, (parsed, lamps, buildings)| {
                let mpp = p.inputs.plan.metres_per_pixel;
                let city = plan::assemble(&parsed, &lamps, &buildings, mpp);
                Ok(((), one("plan.json", codec::to_pretty_json(&city))))
            },
        )
    }

    pub(super) fn need_preview(&mut self) -> Result<(), BuildError> {
        if self.inputs.layout.is_map() {
            return self.stage(
                Stage::Preview,
                None,
                |p| &mut p.preview,
                |p| p.city_map(),
                |_, map| {
                    let picture = crate::osm::draw(&map, MAP_PICTURE_SIDE);
                    Ok(((), one("plan.png", codec::encode_png(&picture))))
                },
            );
        }
        let gather = |p: &mut Self| {
            Ok((
                p.mirrored_image()?,
                p.parsed()?,
                p.lamp_sites()?,
                p.buildings()?,
            ))
        };
        self.stage(
            Stage::Preview,
            None,
            |p| &mut p.preview,
            gather,
            |_, (image, parsed, lamps, buildings)| {
                let picture = preview::draw(&image, &parsed, &lamps, &buildings);
                Ok(((), one("plan.png", codec::encode_png(&picture))))
            },
        )
    }

    pub(super) fn need_facades(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Facades,
            None,
            |p| &mut p.facades,
            |_| Ok(()),
            |p, ()| {
                let f = &p.inputs.facades;
                let processed = match &p.facade_input {
                    FacadeInput::Builtin => facades::process_builtin(f.floor_height, f.on_error),
                    FacadeInput::Folder { source, .. } => {
                        facades::process(source, f.floor_height, f.on_error)
                    }
                };
                let (set, warnings) = processed.map_err(|source| BuildError::Facades {
                    spec: p.spec_path.clone(),
                    source,
                })?;
                for warning in warnings {
                    p.report(warning);
                }
                let outputs = codec::facade_set_outputs(&set);
                Ok((set, outputs))
            },
        )
    }

    pub(super) fn facade_set(&mut self) -> Result<Arc<FacadeSet>, BuildError> {
        self.need_facades()?;
        value(
            &mut self.facades,
            Stage::Facades,
            codec::facade_set_from_outputs,
        )
    }

    pub(super) fn need_export(&mut self) -> Result<(), BuildError> {
        self.stage(
            Stage::Export,
            None,
            |p| &mut p.export,
            |p| Ok((p.scene()?, p.lamp_sites()?, p.facade_set()?)),
            |p, (scene, lamps, facades)| {
                // Writing the OBJ and GLB is mostly serial: the renderer's preparation and
                // the overview's shadow map, which the overview (run next, its key holds
                // this stage's) needs, are made beside it on the other cores.
                let (files, ()) = rayon::join(
                    || export::export(&scene),
                    || p.prepare_for_overview(&scene, &lamps, &facades),
                );
                let outputs = files
                    .into_iter()
                    .map(|(path, bytes)| (path, Blob::Bytes(bytes)))
                    .collect();
                Ok(((), outputs))
            },
        )
    }

    /// The prepared scene, and the shadow map of the overview's sun in it, made ahead of
    /// the overview stage. Nothing when preparing fails: `prepared_scene` then reports it.
    fn prepare_for_overview(&self, scene: &Scene, lamps: &[Lamp], facades: &FacadeSet) {
        let Ok(prepared) = render::prepare_with(scene, &self.mips) else {
            return;
        };
        let lighting = overview_lighting(&self.inputs.overview, scene, lamps, facades);
        if lighting.shadows {
            prepared.shadow_map(lighting.sun_direction, lighting.shadow_map_side);
        }
        let _ = self.prepared.set(Arc::new(prepared));
    }

    /// `overview.png`: the textured city from the air, rendered by cityspec's renderer.
    pub(super) fn need_overview(&mut self) -> Result<(), BuildError> {
        let gather = |p: &mut Self| {
            Ok((
                p.prepared_scene()?,
                p.scene()?,
                p.streets()?,
                p.lamp_sites()?,
                p.facade_set()?,
            ))
        };
        self.stage(
            Stage::Overview,
            None,
            |p| &mut p.overview,
            gather,
            |p, (prepared, scene, streets, lamps, facades)| {
                let lighting = overview_lighting(&p.inputs.overview, &scene, &lamps, &facades);
                let shot = match streets {
                    super::CityStreets::Layout(parsed) => {
                        cameras::overview(&parsed, p.inputs.overview.export.metres_per_pixel)
                    }
                    super::CityStreets::Map(map) => cameras::map_overview(map.extent),
                };
                let frame = render_shot(&prepared, &shot, &lighting);
                Ok(((), one("overview.png", codec::encode_png(&frame))))
            },
        )
    }
}

/// The longer side of a map layout's `plan.png`, pixels.
const MAP_PICTURE_SIDE: u32 = 2048;

/// An overview shot rendered: black when it has no pose (an empty city).
pub(crate) fn render_shot(
    prepared: &render::PreparedScene,
    shot: &cameras::Overview,
    lighting: &render::Lighting,
) -> RgbImage {
    match &shot.pose {
        Some(pose) => {
            let mut intrinsics =
                render::Intrinsics::from_fov(shot.width, shot.height, shot.tan_half_fov);
            intrinsics.far = shot.far;
            render::render(prepared, pose, &intrinsics, lighting, shot.supersample).rgb()
        }
        None => RgbImage::new(shot.width, shot.height),
    }
}

/// The overview's lighting: the spec's light under the overview's sun, seen from the air.
fn overview_lighting(
    inputs: &OverviewInputs,
    scene: &Scene,
    lamps: &[Lamp],
    facades: &FacadeSet,
) -> render::Lighting {
    let sun = render::Sun::overview(&inputs.lighting, inputs.seed);
    let mpp = inputs.export.metres_per_pixel;
    lighting(
        &inputs.lighting,
        inputs.seed,
        mpp,
        &sun,
        scene,
        lamps,
        facades,
    )
    .from_the_air(cameras::OVERVIEW_SHADOW_MAP_SIDE)
}
