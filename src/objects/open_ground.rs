//! A map's open ground as places for people: the paths across its parks
//! (`OsmMap::paths`) or its squares (`OsmMap::squares`), cut into triangles (`earcut`) and
//! drawn by area, so a point is uniform over them.

use rand::RngExt;
use rand_pcg::Pcg64;

use crate::model::MapArea;
use crate::model::geometry::polygon::{triangle_area, triangles};

/// Areas of open ground, ready to draw points on.
pub struct OpenGround {
    /// Each area's triangles, with the area's index.
    triangles: Vec<([[f64; 2]; 3], usize)>,
    /// Square metres at each triangle's end, triangles end to end.
    ends: Vec<f64>,
}

impl OpenGround {
    /// `areas` cut into triangles.
    pub fn of(areas: &[MapArea]) -> OpenGround {
        let triangles: Vec<([[f64; 2]; 3], usize)> = (areas.iter().enumerate())
            .flat_map(|(i, a)| {
                let cut = triangles(&a.shape.outer, &a.shape.holes);
                cut.into_iter().map(move |t| (t, i))
            })
            .collect();
        let ends = triangles
            .iter()
            .scan(0.0, |at, &(t, _)| {
                *at += triangle_area(t);
                Some(*at)
            })
            .collect();
        OpenGround { triangles, ends }
    }

    /// A point drawn uniformly over the areas (a triangle by area, a point in it), and the
    /// index of its area; None when they cover nothing.
    pub fn draw(&self, rng: &mut Pcg64) -> Option<([f64; 2], usize)> {
        let total = *self.ends.last()?;
        let at = rng.random::<f64>() * total;
        let k = (self.ends.partition_point(|&e| e <= at)).min(self.ends.len() - 1);
        let (mut u, mut v): (f64, f64) = (rng.random(), rng.random());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        let ([a, b, c], area) = self.triangles[k];
        let p = [
            a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]),
            a[1] + u * (b[1] - a[1]) + v * (c[1] - a[1]),
        ];
        Some((p, area))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::MapPolygon;
    use crate::model::geometry::polygon::contains;

    fn area(outer: Vec<[f64; 2]>, holes: Vec<Vec<[f64; 2]>>, area: f64) -> MapArea {
        MapArea {
            block: 0,
            shape: MapPolygon { outer, holes, area },
        }
    }

    #[test]
    fn points_are_drawn_by_area_and_never_in_a_hole() {
        // A 10 × 10 square with a 4 × 4 hole (84 m²), and a 1 × 16 strip (16 m²).
        let square = area(
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![vec![[3.0, 3.0], [3.0, 7.0], [7.0, 7.0], [7.0, 3.0]]],
            84.0,
        );
        let strip = area(
            vec![[20.0, 0.0], [21.0, 0.0], [21.0, 16.0], [20.0, 16.0]],
            Vec::new(),
            16.0,
        );
        let ground = OpenGround::of(&[square.clone(), strip.clone()]);
        let mut rng = crate::rng::stream(3, "test", 0);
        let drawn: Vec<([f64; 2], usize)> =
            (0..2000).filter_map(|_| ground.draw(&mut rng)).collect();
        assert_eq!(drawn.len(), 2000);
        let mut on_strip = 0;
        for &(p, i) in &drawn {
            let a = if i == 0 { &square } else { &strip };
            assert!(contains(&a.shape.outer, p), "{p:?} off area {i}");
            assert!(
                !a.shape.holes.iter().any(|h| contains(h, p)),
                "{p:?} in a hole"
            );
            on_strip += usize::from(i == 1);
        }
        // 16 % of the area: 320 of 2000, give or take.
        assert!((250..=390).contains(&on_strip), "{on_strip}");
        assert!(OpenGround::of(&[]).draw(&mut rng).is_none());
    }
}
