//! Boolean operations on a map's polygons (`i_overlay`, non-zero fill): the one place the
//! osm and scene stages cut polygons by polygons.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::FloatOverlay;

use super::polygon::signed_area;
use crate::model::MapPolygon;

/// Rings as `i_overlay` takes and gives them: a shape's outer ring first, its holes after.
pub type Contours = Vec<Vec<[f64; 2]>>;

/// `polygon`'s rings: the outer one, then its holes.
pub fn contours(polygon: &MapPolygon) -> Contours {
    std::iter::once(&polygon.outer)
        .chain(&polygon.holes)
        .cloned()
        .collect()
}

/// `subject` less every polygon of `cut`.
pub fn difference(subject: &MapPolygon, cut: &[&MapPolygon]) -> Vec<MapPolygon> {
    if cut.is_empty() {
        return vec![subject.clone()];
    }
    let clip: Contours = cut.iter().flat_map(|p| contours(p)).collect();
    polygons(
        FloatOverlay::with_subj_and_clip(&contours(subject), &clip)
            .overlay(OverlayRule::Difference, FillRule::NonZero),
    )
}

/// The part of `subject` inside `clip` (rings whose winding numbers add: a hole inside
/// its own outer ring cancels it).
pub fn intersection(subject: &MapPolygon, clip: &Contours) -> Vec<MapPolygon> {
    polygons(
        FloatOverlay::with_subj_and_clip(&contours(subject), clip)
            .overlay(OverlayRule::Intersect, FillRule::NonZero),
    )
}

/// `i_overlay`'s shapes (outer contour first, holes after) as map polygons, turned to
/// the map's orientation (outer rings positive in `[x, z]`); empty shapes dropped.
pub fn polygons(shapes: Vec<Contours>) -> Vec<MapPolygon> {
    shapes
        .into_iter()
        .filter_map(|mut shape| {
            if shape.is_empty() {
                return None;
            }
            let mut outer = shape.remove(0);
            if signed_area(&outer) < 0.0 {
                outer.reverse();
            }
            let holes: Contours = shape
                .into_iter()
                .map(|mut h| {
                    if signed_area(&h) > 0.0 {
                        h.reverse();
                    }
                    h
                })
                .collect();
            let area = signed_area(&outer) + holes.iter().map(|h| signed_area(h)).sum::<f64>();
            (area > 0.0).then_some(MapPolygon { outer, holes, area })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, z0: f64, side: f64) -> Vec<[f64; 2]> {
        vec![
            [x0, z0],
            [x0 + side, z0],
            [x0 + side, z0 + side],
            [x0, z0 + side],
        ]
    }

    fn polygon(outer: Vec<[f64; 2]>, holes: Contours) -> MapPolygon {
        let area = signed_area(&outer) + holes.iter().map(|h| signed_area(h)).sum::<f64>();
        MapPolygon { outer, holes, area }
    }

    #[test]
    fn a_square_less_a_corner_and_a_hole_keeps_the_rest() {
        let block = polygon(square(0.0, 0.0, 10.0), Vec::new());
        let corner = polygon(square(5.0, 5.0, 10.0), Vec::new());
        let mut hole = square(1.0, 1.0, 2.0);
        hole.reverse();
        let inner = polygon(square(1.0, 6.0, 2.0), Vec::new());
        let left = difference(&block, &[&corner, &inner]);
        let area: f64 = left.iter().map(|p| p.area).sum();
        assert!((area - (100.0 - 25.0 - 4.0)).abs() < 1e-9, "{area}");
        assert!(left.iter().all(|p| signed_area(&p.outer) > 0.0));
        // A park with a pond: the pond is not the park's.
        let park: Contours = vec![square(-5.0, -5.0, 10.0), hole];
        let green = intersection(&block, &park);
        let area: f64 = green.iter().map(|p| p.area).sum();
        assert!((area - (25.0 - 4.0)).abs() < 1e-9, "{area}");
        assert_eq!(difference(&block, &[]), vec![block]);
    }
}
