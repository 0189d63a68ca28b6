//! `cityspec osm`: an extract read into the map a city will be built from, written as
//! JSON and a picture.

use std::path::{Path, PathBuf};

use super::BuildError;
use crate::atomic_file::write_atomic;
use crate::model::{GeoBox, OsmMap, encode_png};
use crate::spec::read_capped;

/// The largest extract `cityspec osm` reads: a city's PBF (Berlin's is about 80 MB) fits,
/// with room.
pub const MAX_EXTRACT_BYTES: u64 = 1 << 30;

/// Where `cityspec osm` writes, and how large the picture is.
pub struct OsmOutputs {
    /// The map as JSON.
    pub json: Option<PathBuf>,
    /// A picture of the map (PNG), and its longer side in pixels.
    pub picture: Option<(PathBuf, u32)>,
    /// The 3D city of the map from the air (PNG), as `overview.png` shows a spec's city.
    pub overview: Option<PathBuf>,
}

/// The seed of the map city's facades and unmapped heights, and of its sun.
const SEED: u64 = 1;

/// Reads `file` (restricted to `bbox` when given) and writes what `outputs` asks for.
pub fn read_osm(
    file: &Path,
    bbox: Option<GeoBox>,
    outputs: &OsmOutputs,
) -> Result<OsmMap, BuildError> {
    let bytes = read_capped(file, MAX_EXTRACT_BYTES).map_err(|source| BuildError::OsmFile {
        file: file.to_owned(),
        source,
    })?;
    let map = crate::osm::read(&bytes, bbox).map_err(|source| BuildError::Osm {
        file: file.to_owned(),
        source,
    })?;
    drop(bytes);
    let write = |path: &Path, bytes: &[u8]| {
        write_atomic(path, bytes).map_err(|source| BuildError::Output {
            path: path.to_owned(),
            source,
        })
    };
    if let Some(path) = &outputs.json {
        let mut json = serde_json::to_vec_pretty(&map).expect("a map serializes");
        json.push(b'\n');
        write(path, &json)?;
    }
    if let Some((path, side)) = &outputs.picture {
        write(path, &encode_png(&crate::osm::draw(&map, *side)))?;
    }
    if let Some(path) = &outputs.overview {
        write(path, &encode_png(&overview(file, &map)?))?;
    }
    Ok(map)
}

/// The map's 3D city (the built-in facades, a day sun at the map's latitude) from the air.
fn overview(file: &Path, map: &OsmMap) -> Result<image::RgbImage, BuildError> {
    let floor = crate::spec::FacadesSpec::default().floor_height;
    let (facades, _) = crate::facades::process_builtin(floor, crate::spec::OnError::Error)
        .map_err(|source| BuildError::Facades {
            spec: file.to_owned(),
            source,
        })?;
    // Lamps as a build with the default `[lamps]` has them.
    let lamps = crate::lamps::map_lamps(map, Some(&crate::spec::LampsSpec::default()));
    let scene = crate::scene::map_city(&crate::scene::MapSceneInput {
        map,
        lamps: &lamps,
        facades: &facades,
        seed: SEED,
    });
    let prepared = crate::render::prepare(&scene).map_err(|source| BuildError::Render {
        spec: file.to_owned(),
        source,
    })?;
    let light = crate::spec::LightingSpec {
        latitude: map.origin[0],
        ..crate::spec::LightingSpec::default()
    };
    let sun = crate::render::Sun::overview(&light, SEED);
    let lighting = crate::render::lighting_for(&light, &sun, &scene, &facades, &[], SEED)
        .from_the_air(crate::cameras::OVERVIEW_SHADOW_MAP_SIDE);
    let shot = crate::cameras::map_overview(map.extent);
    Ok(super::pipeline::render_shot(&prepared, &shot, &lighting))
}
