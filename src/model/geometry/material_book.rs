//! Material requests (name, colour, texture, emission) → the scene's material and texture
//! lists, with unique, file-name-safe names.

use std::collections::BTreeSet;

use crate::model::{Material, Texture};

/// The scene's materials and textures as they are registered.
///
/// A texture is stored under its material's (final) name, so the two lists stay easy to
/// match by eye in an exported MTL file.
#[derive(Default)]
pub struct MaterialBook {
    textures: Vec<Texture>,
    materials: Vec<Material>,
    names: BTreeSet<String>,
}

impl MaterialBook {
    /// Registers a material (with its texture, if any) and returns its index.
    ///
    /// `name` is made file-name safe (lower-case ASCII letters, digits, `_`, `-`; anything
    /// else becomes `_`) and, if taken, suffixed `_2`, `_3`, … until unique.
    pub fn add(
        &mut self,
        name: &str,
        colour: [f32; 3],
        texture: Option<&Texture>,
        emissive: [f32; 3],
    ) -> u32 {
        let name = self.unique(&sanitise(name));
        let texture = texture.map(|t| {
            self.textures.push(t.renamed(name.clone()));
            (self.textures.len() - 1) as u32
        });
        self.materials.push(Material {
            name,
            colour,
            texture,
            emissive,
            emissive_textured: false,
        });
        (self.materials.len() - 1) as u32
    }

    /// Makes material `m`'s emission follow its texture (a backlit face).
    pub fn texture_emission(&mut self, m: u32) {
        if let Some(material) = self.materials.get_mut(m as usize) {
            material.emissive_textured = true;
        }
    }

    /// Registers a material of `colour` that shares material `like`'s texture (none if
    /// `like` has none or is not registered): a tinted copy costs no texture memory.
    pub fn add_sharing(&mut self, name: &str, colour: [f32; 3], like: u32) -> u32 {
        let name = self.unique(&sanitise(name));
        let like = self.materials.get(like as usize);
        let (texture, emissive) = like.map_or((None, [0.0; 3]), |m| (m.texture, m.emissive));
        let emissive_textured = like.is_some_and(|m| m.emissive_textured);
        self.materials.push(Material {
            name,
            colour,
            texture,
            emissive,
            emissive_textured,
        });
        (self.materials.len() - 1) as u32
    }

    fn unique(&mut self, base: &str) -> String {
        let mut name = base.to_owned();
        let mut n = 2u32;
        while self.names.contains(&name) {
            name = format!("{base}_{n}");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }

    pub fn finish(self) -> (Vec<Texture>, Vec<Material>) {
        (self.textures, self.materials)
    }
}

fn sanitise(name: &str) -> String {
    let name: String = name
        .chars()
        .map(|c| match c.to_ascii_lowercase() {
            c @ ('a'..='z' | '0'..='9' | '_' | '-') => c,
            _ => '_',
        })
        .collect();
    if name.is_empty() {
        "material".to_owned()
    } else {
        name
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_made_safe_and_unique() {
        let image = image::RgbImage::new(2, 2);
        let texture = Texture::from_rgb("whatever", image);
        let mut book = MaterialBook::default();
        let cases = [
            ("asphalt", "asphalt"),
            ("asphalt", "asphalt_2"),
            ("facade_Bâtiment 7", "facade_b_timent_7"),
            ("", "material"),
            ("asphalt_2", "asphalt_2_2"),
        ];
        for (i, (name, _)) in cases.iter().enumerate() {
            let tex = (i % 2 == 0).then_some(&texture);
            assert_eq!(book.add(name, [1.0; 3], tex, [0.0; 3]), i as u32);
        }
        let (textures, materials) = book.finish();
        let got: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        let want: Vec<&str> = cases.iter().map(|c| c.1).collect();
        assert_eq!(got, want);
        let texture_names: Vec<&str> = textures.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(
            texture_names,
            ["asphalt", "facade_b_timent_7", "asphalt_2_2"]
        );
        assert_eq!(materials[2].texture, Some(1));
        assert_eq!(materials[1].texture, None);
    }
}
