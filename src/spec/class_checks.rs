//! Class checks: the spec's `annotations.classes` + the classes its scene and objects
//! produce → an error for each class nothing produces, with a did-you-mean.
//!
//! A class no object carries would silently give zero annotations (issue 8: `"traffic_sgn"`).
//! [`produced_classes`] is the one place that says which classes a spec's city holds: the
//! scene's own classes, every `[[objects]]` label and the classes an entry's kind gives
//! objects besides it ([`ObjectSpec::companion_classes`]: poles, riders). New object kinds
//! produce their `label`; a new scene class joins [`SCENE_CLASSES`].

use super::closest::closest;
use super::findings::Findings;
use super::spec::Spec;
use crate::spec::ObjectSpec;

/// Classes (and object-name prefixes) the scene stage gives its own objects.
pub(crate) const SCENE_CLASSES: [&str; 7] = [
    "ground", "block", "road", "marking", "sidewalk", "building", "lamp",
];

/// Every class the city of `spec` holds objects of, in a fixed order: the scene's, then per
/// `[[objects]]` entry in spec order its label and its kind's companion classes.
pub fn produced_classes(spec: &Spec) -> Vec<&str> {
    let mut classes: Vec<&str> = SCENE_CLASSES.to_vec();
    for object in &spec.objects {
        let companions = ObjectSpec::companion_classes(object.kind).iter().copied();
        for class in std::iter::once(object.label.as_str()).chain(companions) {
            if !classes.contains(&class) {
                classes.push(class);
            }
        }
    }
    classes
}

/// Every `annotations.classes` entry must be a class the city holds.
pub(crate) fn check_classes(spec: &Spec, findings: &mut Findings<'_, '_>) {
    let produced = produced_classes(spec);
    for (i, class) in spec.annotations.classes.iter().enumerate() {
        if produced.contains(&class.as_str()) {
            continue;
        }
        let hint = match closest(class, produced.iter().copied()) {
            Some(near) => format!(" (did you mean `{near}`?)"),
            None => String::new(),
        };
        findings.error(
            &format!("annotations.classes[{i}]"),
            format!(
                "expected a class the city holds ({}), found {class:?}, which no object \
                 carries, so it would get no annotations{hint}",
                produced.join(", ")
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poles_and_riders_are_classes_their_entries_produce() {
        let text = "version = 1\nname = 'a'\n[layout.generate]\n[buildings]\nwidths = [5, 5]\n\
                    [[objects]]\nkind = 'traffic_light'\nlabel = 'traffic_light'\n\
                    [[objects]]\nkind = 'bicycle'\nlabel = 'bike'\n\
                    [[objects]]\nkind = 'street_name'\nlabel = 'text'\n";
        let spec: Spec = toml::from_str(text).unwrap();
        let produced = produced_classes(&spec);
        assert_eq!(
            produced[SCENE_CLASSES.len()..],
            ["traffic_light", "pole", "bike", "rider", "text"]
        );
    }
}
