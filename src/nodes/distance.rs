//! Distance nodes: the exact Euclidean distance from a mask (jump flooding, a pass per
//! step; see `shaders/jump_flood.wgsl`) and the bevel built on it.

use super::cpu::Eval;
use super::emit::Emit;
use super::formulas::jump_flood::{JFA_STEPS, bevel, jfa_distance, jfa_seed, jfa_step};
use super::formulas::real::{Real, V3};
use super::interval::{Interval, Lanes, splat};
use super::passes::Stage;
use super::pins::{FLOAT, Signature, f, input, output};
use super::ranges::Ranges;
use super::sampled::image_node;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather
            [$($units)*]
            [$($configured)* (Distance, distance) (Bevel, distance)]
            $($rest)*);
    };
}
pub(super) use kinds;

/// What a distance reads where no texel is seeded at all (an empty mask): farther than
/// anything on the tile.
const FAR: f64 = 1.0e4;

/// The stages of a distance transform of the mask buffer: the seeds (the texels above
/// 0.5, or below it when measuring `inside`), every jump-flooding step, the distances.
fn flood_stages(inside: bool) -> Vec<Stage> {
    let mut stages = vec![Stage {
        label: "distance seeds".into(),
        wgsl: format!("veneer_jfa_seed(SOURCE, texel, {}u)", u32::from(inside)),
        library: vec!["veneer_jfa_seed"],
        unchanged_up_to: 0,
        cpu: Box::new(move |image, texel| jfa_seed(image, texel, inside)),
    }];
    for k in 0..JFA_STEPS {
        stages.push(Stage {
            label: format!("jump flood step {}", k + 1),
            wgsl: format!("veneer_jfa_step(SOURCE, texel, {k}u)"),
            library: vec!["veneer_jfa_step"],
            unchanged_up_to: 0,
            cpu: Box::new(move |image, texel| jfa_step(image, texel, k)),
        });
    }
    stages.push(Stage {
        label: "distances".into(),
        wgsl: format!(
            "veneer_jfa_distance(SOURCE, texel, {})",
            super::emit::float_literal(FAR)
        ),
        library: vec!["veneer_jfa_distance"],
        unchanged_up_to: 0,
        cpu: Box::new(|image, texel| jfa_distance(image, texel, FAR)),
    });
    stages
}

/// The distance read at the point from the last stage's buffer, in WGSL.
fn read_distance(io: &Emit) -> String {
    format!("veneer_buffer_bilinear({}, s.uv).x", io.input("mask"))
}

/// Which side of a mask a distance measures.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Measure {
    /// Outside the mask, to its nearest texel above 0.5 (0 on the mask).
    #[default]
    Outside,
    /// Inside the mask, to its edge (0 outside it).
    Inside,
}

impl Measure {
    const ALL: [Measure; 2] = [Measure::Outside, Measure::Inside];
}

/// The Euclidean distance in domain units from a mask (its texels above 0.5), exact up
/// to jump flooding's rare misses, across the wrap when the buffer wraps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Distance {
    pub measure: Measure,
}

impl Definition for Distance {
    image_node!();
    fn title(&self) -> &'static str {
        "Distance"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "distance transform",
            "jump flood",
            "sdf",
            "outline",
            "grow",
            "expand",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![input("mask", FLOAT, f(0.0)).sampled()],
            vec![output("distance", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let read = read_distance(io);
        io.single(read);
        io.uses("veneer_buffer_bilinear");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![splat(Interval::new(0.0, FAR))]
    }
    fn stages(&self, _: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        Ok(flood_stages(self.measure == Measure::Inside))
    }
}

impl Evaluate for Distance {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let distance = io.image("mask").bilinear(io.domain())[0];
        vec![[R::c(distance); 3]]
    }
}

impl Configure for Distance {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("measure", &mut self.measure, &Measure::ALL)]
    }
}

impl Catalogue for Distance {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Distance".into(),
            Distance {
                measure: Measure::Outside,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        Measure::ALL
            .into_iter()
            .map(|measure| Distance { measure })
            .collect()
    }
}

/// How a bevel rises from a mask's edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum BevelProfile {
    /// A straight chamfer.
    Linear,
    /// An S-curve, flat at both ends.
    #[default]
    Smooth,
    /// A quarter circle: steep at the edge, flat on top.
    Round,
}

impl BevelProfile {
    const ALL: [BevelProfile; 3] = [
        BevelProfile::Linear,
        BevelProfile::Smooth,
        BevelProfile::Round,
    ];
}

/// A height from a mask whose edges are bevelled: 0 outside the mask, rising over
/// `width` domain units inside its edge to 1 (stones, tiles and planks from their masks).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Bevel {
    pub profile: BevelProfile,
}

impl Definition for Bevel {
    image_node!();
    fn title(&self) -> &'static str {
        "Bevel"
    }
    fn keywords(&self) -> &'static [&'static str] {
        &["chamfer", "rounded edges", "height from mask", "emboss"]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            vec![
                input("mask", FLOAT, f(0.0)).sampled(),
                input("width", FLOAT, f(0.03)).soft(0.0, 0.2).at_least(0.0),
            ],
            vec![output("height", FLOAT)],
        )
    }
    fn check(&self) -> Option<String> {
        None
    }
    fn emit(&self, io: &mut Emit) {
        let call = format!(
            "veneer_bevel({}, {}, {}u)",
            read_distance(io),
            io.input("width"),
            self.profile as u32
        );
        io.single(call);
        io.uses("veneer_buffer_bilinear");
        io.uses("veneer_bevel");
    }
    fn ranges(&self, _: &mut Ranges) -> Vec<Lanes> {
        vec![splat(Interval::UNIT)]
    }
    fn stages(&self, _: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        Ok(flood_stages(true))
    }
}

impl Evaluate for Bevel {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let distance = io.image("mask").bilinear(io.domain())[0];
        let width = io.float("width").to_f64();
        vec![[R::c(bevel(distance, width, self.profile as u32)); 3]]
    }
}

impl Configure for Bevel {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![choice("profile", &mut self.profile, &BevelProfile::ALL)]
    }
}

impl Catalogue for Bevel {
    fn menu() -> Vec<(String, Self)> {
        vec![(
            "Bevel".into(),
            Bevel {
                profile: BevelProfile::Smooth,
            },
        )]
    }
    fn examples() -> Vec<Self> {
        BevelProfile::ALL
            .into_iter()
            .map(|profile| Bevel { profile })
            .collect()
    }
}
