//! One facade: photo + XML boxes (+ floors from the side file) → a cropped, sized [`Facade`].
//!
//! The crop keeps the rows below the first (topmost) molding box, from its bottom edge to
//! the image bottom; a facade with no molding is kept whole. Windows whose centre lies
//! below the crop line are re-expressed in the crop's texture coordinates; windows above it
//! (attics, dormers) are dropped. The molding colour is the mean of the topmost molding
//! box's pixels, or of the top 5 % of the rows when there is no molding.

use std::borrow::Cow;
use std::io::Cursor;

use image::{ImageReader, Limits, RgbImage};

use crate::model::{Facade, PxRect, Roof, Texture};

use super::cmp_box::{CmpBox, parse_cmp_xml};
use super::cmp_label::CmpLabel;
use super::roof_set::{mean_colour, nearest_roof};
use super::window_rows::estimate_floors;
use super::{FacadeError, FacadeFile, FacadeSource, Photo};

/// Largest accepted width or height of a facade photo.
pub const MAX_SIDE: u32 = 8192;
/// Smallest accepted width or height of a facade photo.
const MIN_SIDE: u32 = 8;

/// Processes one facade file. `floors` is the side file's entry for it, if any.
pub fn crop_facade(
    source: &FacadeSource,
    file: &FacadeFile,
    floors: Option<u32>,
    floor_height: f64,
    roofs: &[Roof],
) -> Result<Facade, FacadeError> {
    let xml_path = || source.path(&file.name, "xml");
    let xml = file
        .xml
        .as_deref()
        .ok_or_else(|| FacadeError::MissingXml { file: xml_path() })?;
    let photo = photo_of(file, || source.path(&file.name, "jpg"))?;
    let (width, height) = photo.dimensions();
    let boxes = parse_cmp_xml(xml, width, height).map_err(|message| FacadeError::BadXml {
        file: xml_path(),
        message,
    })?;

    let molding = boxes
        .iter()
        .filter(|b| b.label == CmpLabel::Molding)
        .min_by_key(|b| (b.rect.y0, b.rect.y1, b.rect.x0));
    let top = molding.map_or(0, |m| m.rect.y1);
    if top + MIN_SIDE > height {
        return Err(FacadeError::EmptyCrop {
            file: xml_path(),
            row: top,
            height,
        });
    }
    let in_crop = |label: CmpLabel| -> Vec<PxRect> {
        boxes
            .iter()
            .filter(|b| b.label == label && b.centre_y() > f64::from(top))
            .map(|b| clip_below(b, top))
            .collect()
    };
    let windows = in_crop(CmpLabel::Window);
    let mut ground = in_crop(CmpLabel::Door);
    ground.extend(in_crop(CmpLabel::Shop));
    let floors = match floors {
        Some(n) => n,
        None => estimate_floors(&windows, &ground)
            .ok_or_else(|| FacadeError::NoWindows { file: xml_path() })?,
    };

    let molding_colour = molding_colour(&photo, molding);
    let crop_rect = PxRect {
        x0: 0,
        y0: top,
        x1: width,
        y1: height,
    };
    let cropped = sub_image(&photo, crop_rect);
    let (cw, ch) = (f64::from(width), f64::from(height - top));
    let building_height = f64::from(floors) * floor_height;
    Ok(Facade {
        name: file.name.clone(),
        floors,
        height: building_height,
        width: cw / ch * building_height,
        molding: molding_colour,
        colour: mean_colour(&cropped),
        roof: nearest_roof(molding_colour, roofs),
        windows: windows.iter().map(|r| crop_uv(r, top, cw, ch)).collect(),
        texture: Texture::from_rgb(format!("facade_{}", safe_name(&file.name)), cropped),
    })
}

/// The file's photo: decoded, or the painted image, of an accepted size.
fn photo_of(
    file: &FacadeFile,
    photo_path: impl Fn() -> String,
) -> Result<Cow<'_, RgbImage>, FacadeError> {
    Ok(match &file.photo {
        Photo::File(bytes) => Cow::Owned(decode_photo(bytes, photo_path)?),
        Photo::Painted(image) => {
            check_size(image.width(), image.height(), photo_path)?;
            Cow::Borrowed(image)
        }
    })
}

/// The mean colour of the topmost molding box, or of the top 5 % of the rows without one.
fn molding_colour(photo: &RgbImage, molding: Option<&CmpBox>) -> [u8; 3] {
    match molding {
        Some(m) => mean_colour(&sub_image(photo, m.rect)),
        None => {
            let (width, height) = photo.dimensions();
            let rows = (height / 20).max(1);
            mean_colour(&sub_image(
                photo,
                PxRect {
                    x0: 0,
                    y0: 0,
                    x1: width,
                    y1: rows,
                },
            ))
        }
    }
}

/// A box's texture coordinates `[u0, v0, u1, v1]` in the crop below row `top`, `cw` ×
/// `ch` pixels.
fn crop_uv(r: &PxRect, top: u32, cw: f64, ch: f64) -> [f32; 4] {
    [
        (f64::from(r.x0) / cw) as f32,
        (f64::from(r.y0 - top) / ch) as f32,
        (f64::from(r.x1) / cw) as f32,
        (f64::from(r.y1 - top) / ch) as f32,
    ]
}

/// The box with its top clipped to the crop line (its centre is below it).
fn clip_below(b: &CmpBox, top: u32) -> PxRect {
    PxRect {
        y0: b.rect.y0.max(top),
        ..b.rect
    }
}

fn sub_image(image: &RgbImage, r: PxRect) -> RgbImage {
    image::imageops::crop_imm(image, r.x0, r.y0, r.width(), r.height()).to_image()
}

/// Decodes the photo (any format the image crate reads; CMP ships JPEG), refusing sizes
/// outside [MIN_SIDE, MAX_SIDE] before decoding pixels.
fn decode_photo(bytes: &[u8], path: impl Fn() -> String) -> Result<RgbImage, FacadeError> {
    let bad = |source: image::ImageError| FacadeError::BadImage {
        file: path(),
        source,
    };
    let reader = || {
        ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| bad(image::ImageError::IoError(e)))
    };
    // A cut-off JPEG decodes without complaint (grey rows): refuse it by its missing end.
    if let Err(why) = crate::model::image_file::check_complete(bytes) {
        return Err(FacadeError::Truncated { file: path(), why });
    }
    let (width, height) = reader()?.into_dimensions().map_err(bad)?;
    check_size(width, height, &path)?;
    let mut reader = reader()?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(u64::from(MAX_SIDE) * u64::from(MAX_SIDE) * 8);
    reader.limits(limits);
    Ok(reader.decode().map_err(bad)?.to_rgb8())
}

/// Refuses a photo with a side outside [MIN_SIDE, MAX_SIDE].
fn check_size(width: u32, height: u32, path: impl Fn() -> String) -> Result<(), FacadeError> {
    if !(MIN_SIDE..=MAX_SIDE).contains(&width) || !(MIN_SIDE..=MAX_SIDE).contains(&height) {
        return Err(FacadeError::BadSize {
            file: path(),
            width,
            height,
            max_side: MAX_SIDE,
        });
    }
    Ok(())
}

/// Keeps ASCII letters, digits, `-` and `_`; anything else becomes `_`.
fn safe_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
