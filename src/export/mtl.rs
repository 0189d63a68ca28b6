//! Scene materials + texture files → `city.mtl` text: one `newmtl` per material, in scene
//! order, with its colour, emission and texture file.
//!
//! `Ka` repeats the base colour (so viewers that add ambient light keep the hue), `Ks` is
//! zero and `illum 1` (colour and ambient, no highlights) to match the glTF's rough,
//! non-metallic surfaces. `Ke` carries emission; `map_Kd` names the shared texture file,
//! and `map_Ke` names it again for a material whose emission follows the texture (a
//! backlit sign).
//! Colours are clamped to 0–1, as in the GLB.

use super::fixed::{push_fixed, push_u64};
use super::obj::push_name;
use super::texture_files::TextureFiles;
use crate::model::Scene;

const DECIMALS: usize = 4;

/// The MTL text of `scene`'s materials.
pub fn write_mtl(scene: &Scene, textures: &TextureFiles) -> Vec<u8> {
    let mut out = Vec::with_capacity(64 + 200 * scene.materials.len());
    out.extend_from_slice(b"# city.mtl written by cityspec (");
    out.extend_from_slice(env!("CARGO_PKG_NAME").as_bytes());
    out.push(b' ');
    out.extend_from_slice(env!("CARGO_PKG_VERSION").as_bytes());
    out.extend_from_slice(b")\n# materials ");
    push_u64(&mut out, scene.materials.len() as u64);
    out.push(b'\n');
    for material in &scene.materials {
        out.extend_from_slice(b"\nnewmtl ");
        push_name(&mut out, &material.name);
        out.push(b'\n');
        let colour = material.colour.map(super::unit_interval);
        push_rgb(&mut out, "Ka", colour);
        push_rgb(&mut out, "Kd", colour);
        push_rgb(&mut out, "Ks", [0.0; 3]);
        push_rgb(&mut out, "Ke", material.emissive.map(super::unit_interval));
        out.extend_from_slice(b"illum 1\n");
        if let Some(file) = textures.file(material.texture) {
            out.extend_from_slice(b"map_Kd ");
            out.extend_from_slice(file.path.as_bytes());
            out.push(b'\n');
            if material.emissive_textured {
                out.extend_from_slice(b"map_Ke ");
                out.extend_from_slice(file.path.as_bytes());
                out.push(b'\n');
            }
        }
    }
    out
}

fn push_rgb(out: &mut Vec<u8>, key: &str, rgb: [f32; 3]) {
    out.extend_from_slice(key.as_bytes());
    for c in rgb {
        out.push(b' ');
        push_fixed(out, c, DECIMALS);
    }
    out.push(b'\n');
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::sample_scene::sample_scene;

    #[test]
    fn materials_in_scene_order_with_colours_emission_and_shared_files() {
        let scene = sample_scene();
        let textures = TextureFiles::collect(&scene);
        let mtl = String::from_utf8(write_mtl(&scene, &textures)).unwrap();
        let brick = &textures.files()[0].path;
        let want_facade_b = format!(
            "newmtl facade_b\nKa 0.9000 0.8000 0.7000\nKd 0.9000 0.8000 0.7000\n\
             Ks 0.0000 0.0000 0.0000\nKe 0.0000 0.0000 0.0000\nillum 1\nmap_Kd {brick}\n"
        );
        assert!(mtl.contains(&want_facade_b), "{mtl}");
        assert!(mtl.contains("newmtl lamp_head\n"));
        assert!(mtl.contains("Ke 1.0000 0.9000 0.6000\nillum 1\n\nnewmtl sign\n"));
        assert_eq!(mtl.matches("newmtl ").count(), scene.materials.len());
        assert_eq!(mtl.matches(&format!("map_Kd {brick}\n")).count(), 2);
        assert_eq!(mtl.matches("map_Kd ").count(), 3);
        let order: Vec<&str> = mtl
            .lines()
            .filter_map(|l| l.strip_prefix("newmtl "))
            .collect();
        assert_eq!(order, ["facade_a", "facade_b", "roof", "lamp_head", "sign"]);
    }

    #[test]
    fn colours_are_clamped_to_the_unit_interval() {
        let mut scene = sample_scene();
        scene.materials[2].colour = [2.0, -1.0, f32::NAN];
        scene.materials[2].emissive = [0.5, 7.0, -0.0];
        let mtl = String::from_utf8(write_mtl(&scene, &TextureFiles::collect(&scene))).unwrap();
        assert!(mtl.contains(
            "newmtl roof\nKa 1.0000 0.0000 0.0000\nKd 1.0000 0.0000 0.0000\n\
             Ks 0.0000 0.0000 0.0000\nKe 0.5000 1.0000 0.0000\n"
        ));
    }
}
