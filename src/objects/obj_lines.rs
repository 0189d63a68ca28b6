//! OBJ and MTL lines: a file's text + the `tobj` error it gave → the line to blame.
//!
//! tobj decides what is valid (nothing else parses models); its errors carry no position,
//! so this walks the lines for the first one that gives that error, for a `file:line`
//! message. It never accepts or refuses anything itself.

/// The 1-based line of `text` (an OBJ file) that makes tobj fail with `error`, if found.
pub fn obj_error_line(text: &str, error: &tobj::LoadError) -> Option<usize> {
    use tobj::LoadError as E;
    let counts = totals(text);
    let lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    let mut seen = [0usize; 3];
    for (number, line) in lines {
        let mut words = line.split_whitespace();
        let head = words.next().unwrap_or_default();
        let rest: Vec<&str> = words.collect();
        let floats = || rest.iter().all(|w| w.parse::<f32>().is_ok());
        let bad = match (error, head) {
            (E::PositionParseError, "v") => rest.len() < 3 || !floats(),
            (E::ColorParseError, "v") => !matches!(rest.len(), 3 | 4 | 6 | 7),
            (E::ScalingByZeroError, "v") => rest.get(3).is_some_and(|w| w.parse() == Ok(0.0f32)),
            (E::NormalParseError, "vn") => rest.len() < 3 || !floats(),
            (E::TexcoordParseError, "vt") => rest.is_empty() || !floats(),
            (E::FaceParseError | E::InvalidPolygon, "f") => {
                rest.len() < 3 || rest.iter().any(|v| vertex(v, seen).is_none())
            }
            (E::FaceVertexOutOfBounds, "f") => out_of_bounds(&rest, seen, counts, 0),
            (E::FaceTexCoordOutOfBounds, "f") => out_of_bounds(&rest, seen, counts, 1),
            (E::FaceNormalOutOfBounds, "f") => out_of_bounds(&rest, seen, counts, 2),
            (E::InvalidObjectName, "o" | "g") => rest.is_empty(),
            _ => false,
        };
        if bad {
            return Some(number);
        }
        match head {
            "v" => seen[0] += 1,
            "vt" => seen[1] += 1,
            "vn" => seen[2] += 1,
            _ => {}
        }
    }
    None
}

/// The 1-based line of `text` (an MTL file) that makes tobj fail with `error`, if found.
pub fn mtl_error_line(text: &str, error: &tobj::LoadError) -> Option<usize> {
    if !matches!(error, tobj::LoadError::MaterialParseError) {
        return None;
    }
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let head = words.next().unwrap_or_default();
        let rest: Vec<&str> = words.collect();
        let floats =
            |n: usize| rest.len() >= n && rest[..n].iter().all(|w| w.parse::<f32>().is_ok());
        let bad = match head {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => !floats(3),
            "Ns" | "Ni" | "d" | "Tr" => !floats(1),
            "illum" => rest.first().is_none_or(|w| w.parse::<u8>().is_err()),
            "newmtl" => rest.is_empty(),
            _ => false,
        };
        if bad {
            return Some(i + 1);
        }
    }
    None
}

/// Positions, texture coordinates and normals in the whole file.
fn totals(text: &str) -> [usize; 3] {
    let mut counts = [0; 3];
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            _ => {}
        }
    }
    counts
}

/// A face vertex `v/vt/vn` as 0-based indices (negative ones count back from `seen`), as
/// tobj reads it; None when tobj would not parse it.
fn vertex(text: &str, seen: [usize; 3]) -> Option<[Option<i64>; 3]> {
    let mut out = [None; 3];
    for (k, part) in text.split('/').enumerate() {
        if k > 2 {
            return None;
        }
        if part.is_empty() {
            continue;
        }
        let x: i64 = part.parse().ok()?;
        out[k] = Some(if x < 0 { seen[k] as i64 + x } else { x - 1 });
    }
    Some(out)
}

fn out_of_bounds(rest: &[&str], seen: [usize; 3], counts: [usize; 3], k: usize) -> bool {
    rest.iter().any(|v| {
        vertex(v, seen)
            .and_then(|idx| idx[k])
            .is_some_and(|i| i < 0 || i >= counts[k] as i64)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tobj_error(obj: &str) -> tobj::LoadError {
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..Default::default()
        };
        tobj::load_obj_buf(&mut std::io::Cursor::new(obj), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .unwrap_err()
    }

    #[test]
    fn each_error_finds_its_line() {
        let cases = [
            ("v 0 0 0\nv 1 x 0\nf 1 2 1\n", 2),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1 2 3\n", 4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", 5),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", 4),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 a\n", 5),
        ];
        for (obj, line) in cases {
            let error = tobj_error(obj);
            assert_eq!(obj_error_line(obj, &error), Some(line), "{obj:?}: {error}");
        }
        let mtl = "newmtl a\nKd 1 1 1\nNs abc\n";
        let error = tobj::load_mtl_buf(&mut std::io::Cursor::new(mtl)).unwrap_err();
        assert_eq!(mtl_error_line(mtl, &error), Some(3));
    }
}
