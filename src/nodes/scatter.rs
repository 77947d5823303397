//! Scatter: the tile sampler, which places a pattern once per cell of a grid, and the
//! splatter, which places a number of them per tile at random, each instance moved,
//! turned, scaled and tinted at random (see `sampler`); and the Instance node, through
//! which a placed pattern reads the instance it is drawn for.
//!
//! The pattern is any subgraph: the sampler's `pattern` and `pattern_colour` inputs are
//! re-evaluated (see `graph::frames`), in each instance's frame, and its `mask` at each
//! instance's centre.

use super::cpu::{Eval, Instance as CpuInstance};
use super::emit::Emit;
use super::formulas::instances::{self, TileBlend};
use super::formulas::real::{Real, V3, splat};
use super::interval::{self, Interval, Lanes};
use super::pins::{
    COLOR, FLOAT, InputPin, POINT, PinDefault, Signature, VEC2, f, input, output, rgb, v2,
};
use super::ranges::Ranges;
use super::sampler::{self, Layout, Projection};
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)* (Instance, scatter)]
            [$($configured)* (TileSampler, scatter) (Splatter, scatter)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// What a placed pattern reads of the instance it is drawn for: its cell, number and
/// random numbers. At the shaded point (outside any sampler's pattern) every output is 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance;

/// The Instance node's outputs, in order, and the `veneer_instance` members they read.
/// (The random number first: thumbnails show it, one grey per instance.)
const INSTANCE_OUTPUTS: [(&str, super::value::ValueType, &str); 4] = [
    ("random", FLOAT, "random"),
    ("id", FLOAT, "id"),
    ("randoms", super::pins::VEC3, "randoms"),
    ("cell", VEC2, "cell"),
];

impl Definition for Instance {
    computed_in!(Category::Input, reading the surface);
    fn title(&self) -> &'static str {
        "Instance"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "tile sampler",
            "scatter",
            "random",
            "per instance",
            "id",
            "seed",
        ]
    }
    fn signature(&self) -> Signature {
        let outputs = INSTANCE_OUTPUTS.map(|(name, ty, _)| match name {
            "id" => output(name, ty).identity(),
            _ => output(name, ty),
        });
        Signature::new(vec![], outputs.to_vec())
    }
    fn emit(&self, io: &mut Emit) {
        let outputs = match io.instance() {
            Some(instance) => INSTANCE_OUTPUTS
                .map(|(_, _, member)| format!("{instance}.{member}"))
                .to_vec(),
            None => INSTANCE_OUTPUTS
                .map(|(_, ty, _)| super::emit::lanes_literal(ty, [0.0; 3]))
                .to_vec(),
        };
        io.outputs(outputs);
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        let cells = Interval::new(0.0, 4095.0);
        vec![
            interval::splat(Interval::UNIT),
            interval::splat(Interval::new(0.0, 4096.0 * 4096.0 - 1.0)),
            interval::splat(Interval::UNIT),
            [cells, cells, Interval::point(0.0)],
        ]
    }
}

impl Evaluate for Instance {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let instance = io.instance().copied().unwrap_or_else(CpuInstance::none);
        let zero = R::c(0.0);
        vec![
            splat(instance.random),
            splat(instance.id),
            instance.randoms,
            [instance.cell[0], instance.cell[1], zero],
        ]
    }
}

plain_catalogue!(Instance);

/// Places a pattern once per cell of a `columns` × `rows` grid over a tile of `size`
/// (in the xz plane, repeating), each instance moved, turned, scaled, tinted and raised
/// at random and kept where the mask at its centre and the density allow; overlapping
/// instances blend by `blend`. An instance is drawn within its own square, never cut
/// by its cell: the search covers every cell whose instances can reach the point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct TileSampler {
    pub blend: TileBlend,
}

/// What a sampler's unwired `pattern` draws.
const DOME: &str = "a dome";

/// A sampler's pins: the point, the re-evaluated pattern, colour and mask, the tile's
/// size, `layout`'s pins, and the per-instance controls.
fn sampler_signature(layout: &[InputPin]) -> Signature {
    let mut inputs = vec![
        POINT,
        input("pattern", FLOAT, PinDefault::Builtin(DOME)).re_evaluated(),
        input("pattern_colour", COLOR, rgb(1.0, 1.0, 1.0))
            .limits(0.0, 1.0)
            .re_evaluated(),
        input("mask", FLOAT, f(1.0)).limits(0.0, 1.0).re_evaluated(),
        input("size", VEC2, v2(1.0, 1.0)).soft(0.0, 10.0),
    ];
    inputs.extend_from_slice(layout);
    inputs.extend([
        input("rotation", FLOAT, f(0.0)).soft(-180.0, 180.0),
        input("rotation_random", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("scale", FLOAT, f(1.0)).soft(0.0, 2.0),
        input("scale_xy", VEC2, v2(1.0, 1.0)).soft(0.0, 2.0),
        input("scale_random", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("height", FLOAT, f(1.0)).soft(0.0, 2.0),
        input("height_random", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("colour_low", COLOR, rgb(1.0, 1.0, 1.0)).limits(0.0, 1.0),
        input("colour_high", COLOR, rgb(1.0, 1.0, 1.0)).limits(0.0, 1.0),
        input("luminance_random", FLOAT, f(0.0)).limits(0.0, 1.0),
        input("density", FLOAT, f(1.0)).limits(0.0, 1.0),
        input("seed", FLOAT, f(0.0)).soft(0.0, 100.0),
    ]);
    Signature::new(
        inputs,
        vec![
            output("height", FLOAT),
            output("colour", COLOR),
            output("mask", FLOAT),
            output("id", FLOAT).identity(),
            output("random", FLOAT),
            output("local", VEC2),
        ],
    )
}

/// The search words of both samplers.
const SAMPLER_KEYWORDS: &[&str] = &[
    "tiler",
    "scatter",
    "splatter",
    "instances",
    "grid",
    "pebbles",
    "scales",
    "rivets",
    "bricks",
    "planks",
    "stamp",
];

impl Definition for TileSampler {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Tile sampler"
    }
    fn keywords(&self) -> &'static [&'static str] {
        SAMPLER_KEYWORDS
    }
    fn signature(&self) -> Signature {
        sampler_signature(&[
            input("columns", FLOAT, f(8.0))
                .limits(1.0, 4096.0)
                .soft(1.0, 64.0),
            input("rows", FLOAT, f(8.0))
                .limits(1.0, 4096.0)
                .soft(1.0, 64.0),
            input("row_offset", FLOAT, f(0.0)).limits(0.0, 1.0),
            input("column_offset", FLOAT, f(0.0)).limits(0.0, 1.0),
            input("position_random", FLOAT, f(0.0)).limits(0.0, 1.0),
        ])
    }
    fn emit(&self, io: &mut Emit) {
        sampler::emit(io, self.blend, Layout::Grid, Projection::Planar);
    }
    fn report(&self, constant: &dyn Fn(&str) -> Option<[f64; 3]>) -> Option<String> {
        Some(sampler::search_report(Layout::Grid, constant))
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        sampler::ranges(io, self.blend)
    }
}

impl Evaluate for TileSampler {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        sampler::eval(io, self.blend, Layout::Grid, Projection::Planar)
    }
}

impl Configure for TileSampler {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("blend", &mut self.blend, &TileBlend::ALL)]
    }
}

impl Catalogue for TileSampler {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Tile sampler".into(),
            TileSampler {
                blend: TileBlend::Max,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        TileBlend::ALL
            .into_iter()
            .map(|blend| TileSampler { blend })
            .collect()
    }
}

/// Scatters `count` instances of a pattern over each tile of `size` at stratified
/// random places (one per cell of the grid that holds them, moved within its cell by
/// `position_random`), each turned, scaled, tinted and raised at random as the tile
/// sampler's; overlapping instances blend by `blend` in a fixed order. The cost at a
/// point grows with the instances that reach it, not with `count`. Planar over the xz
/// plane, or triplanar: on the three axis planes blended by the normal, seamless over
/// any mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Splatter {
    pub blend: TileBlend,
    pub projection: Projection,
}

impl Definition for Splatter {
    computed_in!(Category::Pattern, unchecked);
    fn title(&self) -> &'static str {
        "Splatter"
    }
    fn keywords(&self) -> &'static [&'static str] {
        SAMPLER_KEYWORDS
    }
    fn signature(&self) -> Signature {
        sampler_signature(&[
            input("count", FLOAT, f(40.0))
                .limits(1.0, instances::SPLAT_LIMIT)
                .soft(1.0, 400.0),
            input("position_random", FLOAT, f(0.5)).limits(0.0, 1.0),
        ])
    }
    fn emit(&self, io: &mut Emit) {
        sampler::emit(io, self.blend, Layout::Splat, self.projection);
    }
    fn report(&self, constant: &dyn Fn(&str) -> Option<[f64; 3]>) -> Option<String> {
        let planes = match self.projection {
            Projection::Planar => "",
            Projection::Triplanar => " on each of three planes",
        };
        Some(format!(
            "{}{planes}",
            sampler::search_report(Layout::Splat, constant)
        ))
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        sampler::ranges(io, self.blend)
    }
}

impl Evaluate for Splatter {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        sampler::eval(io, self.blend, Layout::Splat, self.projection)
    }
}

impl Configure for Splatter {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            choice("blend", &mut self.blend, &TileBlend::ALL),
            choice("projection", &mut self.projection, &Projection::ALL),
        ]
    }
}

impl Catalogue for Splatter {
    fn menu() -> Vec<(String, Self)> {
        Projection::ALL
            .into_iter()
            .map(|projection| {
                let blend = TileBlend::Max;
                (
                    format!("Splatter ({projection:?})"),
                    Splatter { blend, projection },
                )
            })
            .collect()
    }
    fn examples() -> Vec<Self> {
        let blends = TileBlend::ALL.into_iter();
        blends
            .flat_map(|blend| Projection::ALL.map(|projection| Splatter { blend, projection }))
            .collect()
    }
}
