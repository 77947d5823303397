//! The lighting model a material is shaded with, and which of the material's inputs
//! each model's lighting reads.

use serde::{Deserialize, Serialize};

/// The lighting model the preview and `veneer render` shade a material with. Every
/// material returns every channel; the model says which ones the lighting reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
pub enum Shading {
    /// Albedo, specular colour and shininess under the seeds' key light and ambient.
    #[default]
    BlinnPhong,
    /// Base colour (the albedo), metallic, roughness, occlusion and the tangent-space
    /// normal: Cook-Torrance GGX under the key light and the environment.
    MetallicRoughness,
    /// Seed 003's lighting as its appendix C listings write it: Phong's R·V highlight,
    /// the diffuse by N·L as it comes (below 0 on the far side, which the frame clamps),
    /// no ambient fill, and the bumped normal left as `normalize(N) + bump`.
    Thesis,
    /// [`Shading::Thesis`] with |N·L|, as listings C.4 and C.5 write it: the far side is
    /// lit as the near one.
    ThesisAbsolute,
    /// [`Shading::Thesis`] with C.6.4's environment, the waves' final look: the colour
    /// is the environment in the direction of the light's reflection (which the listing
    /// looks up in a sphere map; here the environment itself, the procedural sky by
    /// default, shown through the exposure and tone mapper) plus the highlight, the
    /// diffuse term dropped as the listing drops it.
    ThesisSphereMap,
}

impl Shading {
    /// Every model, in menu order.
    pub const ALL: [Shading; 5] = [
        Shading::BlinnPhong,
        Shading::MetallicRoughness,
        Shading::Thesis,
        Shading::ThesisAbsolute,
        Shading::ThesisSphereMap,
    ];

    pub(super) fn is_default(&self) -> bool {
        *self == Shading::default()
    }

    /// The model's name as the editor shows it.
    pub fn name(self) -> &'static str {
        match self {
            Shading::BlinnPhong => "Blinn-Phong",
            Shading::MetallicRoughness => "metallic-roughness",
            Shading::Thesis => "thesis Phong",
            Shading::ThesisAbsolute => "thesis Phong |N·L|",
            Shading::ThesisSphereMap => "thesis sphere map",
        }
    }

    /// Whether the lighting reads an environment (its maps are bound, and the preview
    /// offers the environment, exposure and tone mapper).
    pub fn reads_environment(self) -> bool {
        matches!(self, Shading::MetallicRoughness | Shading::ThesisSphereMap)
    }

    /// Whether colours are linear light (metallic-roughness) rather than the display
    /// values the seeds' and the thesis's lighting show.
    pub fn is_linear(self) -> bool {
        self == Shading::MetallicRoughness
    }

    /// Whether the lighting reads the material's input `pin` (Blinn-Phong and the
    /// thesis's Phong leave out metallic, roughness and occlusion, the thesis's sphere map
    /// the albedo too; metallic-roughness, specular and shininess).
    pub fn reads(self, pin: &str) -> bool {
        let ignored: &[&str] = match self {
            Shading::MetallicRoughness => &["specular", "shininess"],
            Shading::BlinnPhong | Shading::Thesis | Shading::ThesisAbsolute => {
                &["metallic", "roughness", "occlusion"]
            }
            // C.6.4 shows the environment where the others show the diffuse colour.
            Shading::ThesisSphereMap => &["albedo", "metallic", "roughness", "occlusion"],
        };
        !ignored.contains(&pin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inputs one shading's lighting reads and another's does not are those its
    /// WGSL lighting file reads from the material.
    #[test]
    fn the_inputs_a_shading_reads_are_those_its_lighting_file_reads() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let material =
            crate::graph::Node::new(crate::graph::NodeId(1), crate::graph::NodeKind::Material);
        let pins = material.kind.signature().inputs;
        let files = [
            (Shading::BlinnPhong, "render_lit_blinn_phong.wgsl"),
            (
                Shading::MetallicRoughness,
                "render_lit_metallic_roughness.wgsl",
            ),
            (Shading::Thesis, "render_lit_thesis.wgsl"),
            (
                Shading::ThesisSphereMap,
                "render_lit_thesis_sphere_map.wgsl",
            ),
        ];
        let texts = files.map(|(_, file)| std::fs::read_to_string(root.join(file)).unwrap());
        for pin in pins {
            let lit = texts
                .each_ref()
                .map(|text| text.contains(&format!("material.{}", pin.name)));
            // Inputs read outside the lighting (alpha, bump, height, normal) or by all.
            if lit.iter().all(|&read| read == lit[0]) {
                assert!(
                    files.iter().all(|(shading, _)| shading.reads(pin.name)),
                    "{}",
                    pin.name
                );
                continue;
            }
            for ((shading, file), read) in files.iter().zip(lit) {
                assert_eq!(shading.reads(pin.name), read, "{} in {file}", pin.name);
            }
        }
    }
}
