//! Every node kind the editor offers, grouped by category, with search and the
//! compatibility filter for wires dropped on empty space.

use crate::graph::{
    Basis, Category, MathOp, Metric, NodeKind, RampInterpolation, RampStop, UnaryOp, ValueType,
    WorleyFeature,
};

/// One entry of the add-node menu.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Menu text, e.g. "fBm (gradient)".
    pub name: String,
    pub kind: NodeKind,
}

/// Menu order of the categories.
pub const CATEGORIES: [(Category, &str); 9] = [
    (Category::Input, "Input"),
    (Category::Coordinates, "Coordinates"),
    (Category::Noise, "Noise"),
    (Category::Fractal, "Fractal"),
    (Category::Cellular, "Cellular"),
    (Category::Pattern, "Pattern"),
    (Category::Field, "Distance field"),
    (Category::Math, "Math"),
    (Category::Output, "Output"),
];

fn basis_name(basis: Basis) -> &'static str {
    match basis {
        Basis::ValueSine => "value, sine hash",
        Basis::ValuePcg => "value, PCG hash",
        Basis::Gradient => "gradient",
        Basis::Simplex => "simplex",
    }
}

/// All entries, in menu order.
pub fn entries() -> Vec<Entry> {
    let mut entries = Vec::new();
    let mut add = |name: String, kind: NodeKind| entries.push(Entry { name, kind });
    for kind in [
        NodeKind::Position,
        NodeKind::Normal,
        NodeKind::Uv,
        NodeKind::Time,
    ] {
        add(kind.title().to_string(), kind);
    }
    add("Distance field".into(), NodeKind::Field { slot: 0 });
    for (ty, name) in [
        (ValueType::Float, "Value"),
        (ValueType::Vec3, "Vector"),
        (ValueType::Color, "Colour"),
        (ValueType::Vec2, "Vector 2"),
    ] {
        add(name.to_string(), NodeKind::Constant { ty });
    }
    add(
        "Reroute".into(),
        NodeKind::Constant {
            ty: ValueType::Vec3,
        },
    );
    for kind in [
        NodeKind::Transform,
        NodeKind::Project,
        NodeKind::Cylindrical,
    ] {
        add(kind.title().to_string(), kind);
    }
    for basis in Basis::ALL {
        add(
            format!("Domain warp ({})", basis_name(basis)),
            NodeKind::DomainWarp { basis },
        );
        add(
            format!("Noise ({})", basis_name(basis)),
            NodeKind::Noise { basis },
        );
        add(
            format!("Noise bump ({})", basis_name(basis)),
            NodeKind::NoiseBump { basis },
        );
    }
    for basis in Basis::ALL {
        add(
            format!("fBm ({})", basis_name(basis)),
            NodeKind::Fbm {
                basis,
                octaves: 5,
                normalize: false,
            },
        );
        add(
            format!("Turbulence ({})", basis_name(basis)),
            NodeKind::Turbulence {
                basis,
                octaves: 4,
                normalize: false,
            },
        );
        add(
            format!("Fractal sum ({})", basis_name(basis)),
            NodeKind::FractalSum {
                basis,
                octaves: 4,
                normalize: false,
            },
        );
    }
    add(
        "Worley".into(),
        NodeKind::Worley {
            feature: WorleyFeature::F1,
            metric: Metric::Euclidean,
            octaves: 1,
        },
    );
    add(
        "Worley, fractal".into(),
        NodeKind::Worley {
            feature: WorleyFeature::F2MinusF1,
            metric: Metric::Euclidean,
            octaves: 3,
        },
    );
    for kind in [
        NodeKind::SineBand,
        NodeKind::TriangleWave,
        NodeKind::Tiles,
        NodeKind::Rings,
        NodeKind::Front,
        NodeKind::Isolines,
    ] {
        add(kind.title().to_string(), kind);
    }
    add(
        "Layers (colour)".into(),
        NodeKind::Layers {
            ty: ValueType::Color,
        },
    );
    for op in MathOp::ALL {
        add(
            format!("{op:?}"),
            NodeKind::Math {
                op,
                ty: ValueType::Float,
            },
        );
    }
    for op in UnaryOp::ALL {
        add(
            format!("{op:?}"),
            NodeKind::Unary {
                op,
                ty: ValueType::Float,
            },
        );
    }
    add(
        "Mix".into(),
        NodeKind::Mix {
            ty: ValueType::Float,
        },
    );
    add(
        "Mix colours".into(),
        NodeKind::Mix {
            ty: ValueType::Color,
        },
    );
    add(
        "Clamp".into(),
        NodeKind::Clamp {
            ty: ValueType::Float,
        },
    );
    add(
        "Step".into(),
        NodeKind::Step {
            ty: ValueType::Float,
        },
    );
    add("Smoothstep".into(), NodeKind::Smoothstep);
    add("Remap".into(), NodeKind::Remap);
    add(
        "Length".into(),
        NodeKind::Length {
            ty: ValueType::Vec3,
        },
    );
    add(
        "Dot".into(),
        NodeKind::Dot {
            ty: ValueType::Vec3,
        },
    );
    add(
        "Normalize".into(),
        NodeKind::Normalize {
            ty: ValueType::Vec3,
        },
    );
    add(
        "Split".into(),
        NodeKind::Split {
            ty: ValueType::Vec3,
        },
    );
    add(
        "Combine".into(),
        NodeKind::Combine {
            ty: ValueType::Vec3,
        },
    );
    add(
        "Combine colour".into(),
        NodeKind::Combine {
            ty: ValueType::Color,
        },
    );
    add(
        "Colour ramp".into(),
        NodeKind::ColorRamp {
            stops: vec![
                RampStop {
                    position: 0.0,
                    color: (0.05, 0.05, 0.05),
                },
                RampStop {
                    position: 1.0,
                    color: (0.95, 0.95, 0.95),
                },
            ],
            interpolation: RampInterpolation::Linear,
        },
    );
    add("Material".into(), NodeKind::Material);
    entries
}

/// Entries whose name contains every word of `query` (case-insensitive).
pub fn search(query: &str) -> Vec<Entry> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    entries()
        .into_iter()
        .filter(|entry| {
            let name = format!("{} {}", entry.name, entry.kind.title()).to_lowercase();
            words.iter().all(|word| name.contains(word))
        })
        .collect()
}

/// Which end of a dropped wire the new node must offer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dangling {
    /// The wire starts at an output of this type: the node needs a compatible input.
    FromOutput(ValueType),
    /// The wire ends at an input of this type: the node needs a compatible output.
    IntoInput(ValueType),
}

/// The pin of `kind` a dangling wire would attach to, if any: an input index for
/// `FromOutput`, an output index for `IntoInput`.
pub fn compatible_pin(kind: &NodeKind, dangling: Dangling) -> Option<usize> {
    let signature = kind.signature();
    match dangling {
        Dangling::FromOutput(ty) => signature
            .inputs
            .iter()
            .position(|pin| ty.converts_to(pin.ty)),
        Dangling::IntoInput(ty) => signature
            .outputs
            .iter()
            .position(|pin| pin.ty.converts_to(ty)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_category_has_entries_and_every_entry_checks_alone() {
        let all = entries();
        for (category, name) in CATEGORIES {
            assert!(
                all.iter().any(|e| e.kind.category() == category),
                "{name} is empty"
            );
        }
        assert!(all.len() > 50);
    }

    #[test]
    fn search_matches_all_words() {
        let found = search("fbm grad");
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].name, "fBm (gradient)");
        assert!(search("zebra").is_empty());
    }

    #[test]
    fn dropped_wires_only_offer_compatible_nodes() {
        let vec2 = Dangling::FromOutput(ValueType::Vec2);
        assert!(
            compatible_pin(
                &NodeKind::Length {
                    ty: ValueType::Vec2
                },
                vec2
            )
            .is_some()
        );
        assert!(
            compatible_pin(
                &NodeKind::Noise {
                    basis: Basis::Simplex
                },
                vec2
            )
            .is_none()
        );
        assert_eq!(
            compatible_pin(&NodeKind::Material, Dangling::FromOutput(ValueType::Float)),
            Some(0)
        );
        assert!(compatible_pin(&NodeKind::Uv, Dangling::IntoInput(ValueType::Color)).is_none());
    }
}
