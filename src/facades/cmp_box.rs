//! CmpBox: CMP XML annotation text ↔ labelled pixel boxes.
//!
//! The CMP XML has no root element: it is a series of
//! `<object><points><x/><x/><y/><y/></points><label/><labelname/><flag/></object>`. The points
//! are normalised to 0–1 and, unusually, `<x>` is the **row** (× image height) and `<y>` the
//! **column** (× image width). Classes are taken from `<labelname>`; objects with a name that
//! is not one of the twelve CMP classes are ignored, as are boxes that round to no pixels.

use std::fmt::Write as _;

use crate::model::PxRect;

use super::cmp_label::CmpLabel;

/// How far outside 0–1 a normalised coordinate may stray (annotation slop) before the file
/// is taken to be something else than CMP XML.
const SLOP: f64 = 0.05;

/// One annotated box, in pixels of the photo it belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CmpBox {
    pub label: CmpLabel,
    pub rect: PxRect,
}

impl CmpBox {
    /// Vertical centre in pixels.
    pub fn centre_y(&self) -> f64 {
        f64::from(self.rect.y0 + self.rect.y1) / 2.0
    }
}

/// Parses CMP XML for a `width × height` photo. The message of an error says what is wrong
/// and where (object number, 1-based); the caller adds the file name.
pub fn parse_cmp_xml(text: &str, width: u32, height: u32) -> Result<Vec<CmpBox>, String> {
    let body = strip_declaration(text);
    let wrapped = format!("<annotation>{body}</annotation>");
    let doc = roxmltree::Document::parse(&wrapped).map_err(|e| format!("not valid XML: {e}"))?;
    let mut boxes = Vec::new();
    let objects = doc
        .root_element()
        .children()
        .filter(|n| n.has_tag_name("object"));
    for (i, object) in objects.enumerate() {
        let number = i + 1;
        let Some(name) = child_text(object, "labelname") else {
            return Err(format!("object {number} has no <labelname>"));
        };
        let Some(label) = CmpLabel::from_name(name) else {
            continue;
        };
        let points = object
            .children()
            .find(|n| n.has_tag_name("points"))
            .ok_or_else(|| format!("object {number} ({}) has no <points>", label.name()))?;
        let rows = coordinates(points, "x", number)?;
        let cols = coordinates(points, "y", number)?;
        let rect = PxRect {
            x0: to_px(cols.0, width),
            x1: to_px(cols.1, width),
            y0: to_px(rows.0, height),
            y1: to_px(rows.1, height),
        };
        if rect.x0 < rect.x1 && rect.y0 < rect.y1 {
            boxes.push(CmpBox { label, rect });
        }
    }
    Ok(boxes)
}

/// Writes boxes of a `width × height` photo as CMP XML (no root element, `<x>` = row).
pub fn write_cmp_xml(boxes: &[CmpBox], width: u32, height: u32) -> String {
    let (w, h) = (f64::from(width), f64::from(height));
    let mut xml = String::new();
    for b in boxes {
        let r = b.rect;
        // Writing to a String cannot fail.
        let _ = write!(
            xml,
            "<object>\n\t<points>\n\t\t<x>{:.6}</x>\n\t\t<x>{:.6}</x>\n\t\t<y>{:.6}</y>\n\t\t\
             <y>{:.6}</y>\n\t</points>\n\t<label>{}</label>\n\t<labelname>{}</labelname>\n\t\
             <flag>0</flag>\n</object>\n",
            f64::from(r.y0) / h,
            f64::from(r.y1) / h,
            f64::from(r.x0) / w,
            f64::from(r.x1) / w,
            b.label.mask_value(),
            b.label.name(),
        );
    }
    xml
}

fn strip_declaration(text: &str) -> &str {
    let text = text.trim_start_matches('\u{feff}').trim_start();
    if text.starts_with("<?xml")
        && let Some(end) = text.find("?>")
    {
        return &text[end + 2..];
    }
    text
}

fn child_text<'a>(node: roxmltree::Node<'a, '_>, tag: &str) -> Option<&'a str> {
    node.children()
        .find(|n| n.has_tag_name(tag))
        .and_then(|n| n.text())
}

/// The smallest and largest of the `<tag>` values under `<points>`, clamped to 0–1.
fn coordinates(points: roxmltree::Node, tag: &str, number: usize) -> Result<(f64, f64), String> {
    let mut values = Vec::new();
    for node in points.children().filter(|n| n.has_tag_name(tag)) {
        let text = node.text().unwrap_or("").trim();
        let value: f64 = text
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| format!("object {number}: <{tag}> is `{text}`, not a number"))?;
        if !(-SLOP..=1.0 + SLOP).contains(&value) {
            return Err(format!(
                "object {number}: <{tag}> is {value}, outside 0–1 (CMP points are normalised)"
            ));
        }
        values.push(value.clamp(0.0, 1.0));
    }
    if values.len() < 2 {
        return Err(format!(
            "object {number}: <points> needs two <{tag}> values, found {}",
            values.len()
        ));
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Ok((lo, hi))
}

fn to_px(normalised: f64, size: u32) -> u32 {
    // Clamped to 0–1 above, so the product lies in 0..=size.
    (normalised * f64::from(size)).round() as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    const SNIPPET: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<object>
	<points>
		<x>0.25</x>
		<x>0.5</x>
		<y>0.1</y>
		<y>0.3</y>
	</points>
	<label>3</label>
	<labelname>window</labelname>
	<flag>0</flag>
</object>
<object>
	<points>
		<x>0.05</x>
		<x>0.0</x>
		<y>1.0</y>
		<y>0.0</y>
	</points>
	<label>10</label>
	<labelname>molding</labelname>
	<flag>0</flag>
</object>
<object>
	<points><x>0.1</x><x>0.2</x><y>0.1</y><y>0.2</y></points>
	<label>13</label>
	<labelname>chimney</labelname>
	<flag>0</flag>
</object>
"#;

    #[test]
    fn cmp_snippet_parses_rows_from_x_and_columns_from_y() {
        // 200 wide, 400 high: x (rows) scale by 400, y (columns) by 200.
        let boxes = parse_cmp_xml(SNIPPET, 200, 400).unwrap();
        assert_eq!(
            boxes,
            vec![
                CmpBox {
                    label: CmpLabel::Window,
                    rect: PxRect {
                        x0: 20,
                        y0: 100,
                        x1: 60,
                        y1: 200
                    },
                },
                CmpBox {
                    label: CmpLabel::Molding,
                    rect: PxRect {
                        x0: 0,
                        y0: 0,
                        x1: 200,
                        y1: 20
                    },
                },
            ]
        );
    }

    #[test]
    fn written_xml_parses_back_to_the_same_boxes() {
        let boxes = vec![
            CmpBox {
                label: CmpLabel::Door,
                rect: PxRect {
                    x0: 3,
                    y0: 250,
                    x1: 71,
                    y1: 333,
                },
            },
            CmpBox {
                label: CmpLabel::Sill,
                rect: PxRect {
                    x0: 0,
                    y0: 0,
                    x1: 517,
                    y1: 9,
                },
            },
        ];
        let xml = write_cmp_xml(&boxes, 517, 333);
        assert_eq!(parse_cmp_xml(&xml, 517, 333).unwrap(), boxes);
    }

    #[test]
    fn malformed_objects_are_refused_with_their_number() {
        let cases = [
            ("<object><points>", "not valid XML"),
            (
                "<object><points><x>0</x><x>1</x><y>0</y><y>1</y></points></object>",
                "object 1 has no <labelname>",
            ),
            (
                "<object><labelname>door</labelname></object>",
                "object 1 (door) has no <points>",
            ),
            (
                "<object><points><x>0</x><x>1</x><y>0</y></points><labelname>door</labelname></object>",
                "needs two <y> values, found 1",
            ),
            (
                "<object><points><x>0</x><x>zero</x><y>0</y><y>1</y></points><labelname>door</labelname></object>",
                "<x> is `zero`",
            ),
            (
                "<object><points><x>0</x><x>120</x><y>0</y><y>1</y></points><labelname>door</labelname></object>",
                "outside 0–1",
            ),
        ];
        for (xml, expected) in cases {
            let message = parse_cmp_xml(xml, 10, 10).unwrap_err();
            assert!(message.contains(expected), "{xml}: {message}");
        }
    }
}
