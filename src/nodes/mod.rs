//! Node kinds: one definition per kind, in one file per family, and the registry every
//! stage reads.
//!
//! A kind's definition holds, in one place, its title, category and search words, its
//! pins by name (type, default, inspector range), its settings, whether it reads the
//! surface, which lattice basis it samples, its WGSL emission, its CPU evaluation
//! (generic over f32 and f64), its range propagation for the lint, its own checks, and
//! its menu entries and test examples. The family files list their kinds in a `kinds!`
//! macro; [`registry!`] gathers them into [`NodeKind`] and one `match` per part, so a
//! kind that lacks a part does not compile.
//!
//! To add a kind: write its definition in its family file and add it to that file's
//! `kinds!` list; write its WGSL function in `shaders/`. The catalogue, the inspector,
//! the checks, codegen, the evaluator, the lint and the tests that enumerate
//! [`NodeKind::examples`] pick it up.

/// The parts of a definition for a kind that reads nothing of the surface, in
/// `category`: with no lattice (`computed_in!(category)`), also with no settings to
/// check (`computed_in!(category, unchecked)`), or sampling the lattice of its `basis`
/// setting, its only setting (`computed_in!(category, sampling)`); or for a kind that
/// reads the surface, with no lattice and no settings to check
/// (`computed_in!(category, reading the surface)`).
macro_rules! computed_in {
    (@parts $category:expr, |$this:ident| $basis:expr) => {
        computed_in!(@parts $category, |$this| $basis, false);
    };
    (@parts $category:expr, |$this:ident| $basis:expr, $reads:expr) => {
        fn category(&self) -> Category {
            $category
        }
        fn reads_surface(&self) -> bool {
            $reads
        }
        fn basis(&$this) -> Option<Basis> {
            $basis
        }
    };
    ($category:expr) => {
        computed_in!(@parts $category, |self| None);
    };
    ($category:expr, unchecked) => {
        computed_in!($category);
        fn check(&self) -> Option<String> {
            None
        }
    };
    ($category:expr, reading the surface) => {
        computed_in!(@parts $category, |self| None, true);
        fn check(&self) -> Option<String> {
            None
        }
    };
    ($category:expr, sampling) => {
        computed_in!(@parts $category, |self| Some(self.basis));
        fn check(&self) -> Option<String> {
            None
        }
    };
}

/// The menu entry (its title) and test example of a kind without settings.
macro_rules! plain_catalogue {
    ($kind:ident) => {
        impl Catalogue for $kind {
            fn menu() -> Vec<(String, Self)> {
                vec![($kind.title().into(), $kind)]
            }
            fn examples() -> Vec<Self> {
                vec![$kind]
            }
        }
    };
}

/// The settings and catalogue of a kind whose settings are its lattice basis and the
/// period its noise repeats over: a menu entry per basis, `"<menu name> (<basis>)"`,
/// never repeating, and every basis in the tests, never repeating and every 6 cells.
macro_rules! basis_choice {
    ($kind:ident, $menu:literal) => {
        impl Configure for $kind {
            fn settings(&mut self) -> Vec<Setting<'_>> {
                vec![
                    choice("basis", &mut self.basis, &Basis::ALL),
                    super::settings::period_setting(&mut self.period),
                ]
            }
        }

        impl Catalogue for $kind {
            fn menu() -> Vec<(String, Self)> {
                Basis::ALL
                    .into_iter()
                    .map(|basis| {
                        (
                            format!("{} ({})", $menu, basis.menu_name()),
                            $kind { basis, period: 0 },
                        )
                    })
                    .collect()
            }
            fn examples() -> Vec<Self> {
                [0, 6]
                    .into_iter()
                    .flat_map(|period| Basis::ALL.map(|basis| $kind { basis, period }))
                    .collect()
            }
        }
    };
}

pub mod cpu;
pub mod emit;
mod file_form;
pub mod formulas;
pub mod interval;
pub mod passes;
pub mod pins;
pub mod ranges;
pub mod settings;
pub mod value;

pub mod bitmap;
mod cellular;
mod colour;
mod coordinates;
mod distance;
mod fields;
mod flood_fill;
mod fractal;
mod graph_bake;
mod group;
mod image_ops;
mod inputs;
mod levels;
mod mapping;
mod math;
pub mod mesh_field;
mod noise;
mod output;
mod patterns;
mod sampled;
pub mod sampler;
mod scatter;
mod shapes;
mod vectors;

pub use bitmap::{BitmapSource, ImageFile, LUMINANCE};
pub use cellular::Worley;
pub use colour::{Blend, BlendMode, ColorRamp};
pub use coordinates::DomainWarp;
pub use distance::{Bevel, BevelProfile, Distance, Measure};
pub use fields::Layers;
pub use flood_fill::FloodFill;
pub use fractal::{Fbm, FractalSum, Turbulence};
pub use graph_bake::{BakedMap, GraphBake};
pub use group::Group;
pub use image_ops::{
    Curvature, DirectionalBlur, DirectionalWarp, EdgeDetect, HeightOcclusion, MakeTileable,
    SlopeBlur, SlopeWarp, Transform2D,
};
pub use inputs::{Constant, Field};
pub use levels::{AutoLevels, HistogramScan};
pub use mapping::{Clamp, MapRange, MapRangeMode, Mix, Step, Switch};
pub use math::{Math, Unary};
pub use noise::{Noise, NoiseBump};
pub use sampled::{Blur, Buffer, HeightToNormal, NormalConvention, RadiusUnit, Warp};
pub use scatter::{Instance, Splatter, TileSampler};
pub use shapes::{Shape, ShapeBoolean, ShapeFromSdf, ShapeKind};
pub use vectors::{Combine, Dot, Length, Normalize, Split};

use cpu::Eval;
use emit::Emit;
use formulas::real::{Real, V3};
use interval::Lanes;
use passes::{BufferSpec, Stage};
use pins::Signature;
use ranges::Ranges;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use settings::{Basis, Setting};

/// Menu category of a node kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Category {
    Input,
    Coordinates,
    Noise,
    Fractal,
    Cellular,
    Pattern,
    Field,
    Math,
    Colour,
    Image,
    Output,
    Group,
}

impl Category {
    /// Every category, in menu order.
    pub const ALL: [Category; 12] = [
        Category::Input,
        Category::Coordinates,
        Category::Noise,
        Category::Fractal,
        Category::Cellular,
        Category::Pattern,
        Category::Field,
        Category::Math,
        Category::Colour,
        Category::Image,
        Category::Output,
        Category::Group,
    ];

    /// The menu's name for the category.
    pub fn name(self) -> &'static str {
        match self {
            Category::Input => "Input",
            Category::Coordinates => "Coordinates",
            Category::Noise => "Noise",
            Category::Fractal => "Fractal",
            Category::Cellular => "Cellular",
            Category::Pattern => "Pattern",
            Category::Field => "Distance field",
            Category::Math => "Math",
            Category::Colour => "Colour",
            Category::Image => "Image",
            Category::Output => "Output",
            Category::Group => "Groups",
        }
    }
}

/// What every node kind defines (the object-safe parts; see also [`Evaluate`],
/// [`Catalogue`] and, for kinds with settings, [`Configure`]).
pub trait Definition {
    /// A short human-readable name (default labels, messages, generated comments).
    fn title(&self) -> &'static str;
    /// The menu category.
    fn category(&self) -> Category;
    /// More words the add-node search matches (the names peers use).
    fn keywords(&self) -> &'static [&'static str];
    /// The pins, which may depend on the settings.
    fn signature(&self) -> Signature;
    /// Whether the node reads the surface itself (position, normal, uv, time, fields, or
    /// is the output), so constant folding must leave it in the shader.
    fn reads_surface(&self) -> bool;
    /// The lattice noise basis the node samples, if any: the lint and the snapshots'
    /// adapter-dependence read this one answer.
    fn basis(&self) -> Option<Basis>;
    /// What is wrong with the settings, if anything (the graph check reports it).
    fn check(&self) -> Option<String>;
    /// Writes the node's WGSL.
    fn emit(&self, io: &mut Emit);
    /// The ranges of the outputs given the ranges of the inputs, warning of hazards.
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes>;
    /// The title an unlabelled node of these settings shows: the kind's, unless a
    /// setting names it better (a Math node's operation).
    fn shown_title(&self) -> String {
        self.title().to_string()
    }
    /// The texel-space passes the node runs over its sampled input's buffer before it
    /// reads it, built from its inputs' constants (`constant(pin)`, `None` when the pin
    /// is wired); an error names what must be constant. None for most kinds.
    fn stages(&self, constant: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<Stage>, String> {
        let _ = constant;
        Ok(Vec::new())
    }
    /// What `veneer check` reports of the node beyond hazards, from its inputs'
    /// constants (`constant(pin)`, `None` when the pin is wired): a sampler says how many
    /// cells it searches. None for most kinds.
    fn report(&self, constant: &dyn Fn(&str) -> Option<[f64; 3]>) -> Option<String> {
        let _ = constant;
        None
    }
    /// How the buffer of the node's sampled input is stored, when the node sets it (a
    /// Buffer node); sampled inputs wired to this node's output read the same buffer.
    fn buffer(&self) -> Option<BufferSpec> {
        None
    }
    /// The bitmap file the node reads, when it reads one (an Image node): the compiler
    /// uploads it into a buffer the node samples.
    fn bitmap(&self) -> Option<BitmapSource<'_>> {
        None
    }
    /// A picture of the settings that the editor draws in the node's body and its
    /// inspector (the colour ramp's gradient); none by default.
    fn body(&self) -> Option<Body<'_>> {
        None
    }
}

/// A picture of a node's settings, declared by its definition and drawn by the editor
/// (which matches on this, never on node kinds).
pub enum Body<'a> {
    /// A bar of the colours `colour` gives each factor from 0 to 1, with a tick at each
    /// of `ticks` (factors).
    Gradient {
        colour: Box<dyn Fn(f64) -> [f64; 3] + 'a>,
        ticks: Vec<f64>,
    },
}

impl Body<'_> {
    /// The size the editor draws a body picture at in a node, in canvas units (the
    /// layout's footprints reckon with it).
    pub const SIZE: (f32, f32) = (160.0, 18.0);
}

/// CPU evaluation, generic over the precision (f32 like the GPU, f64 as the reference).
pub trait Evaluate {
    /// The outputs, each as three lanes, given the inputs.
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>>;
}

/// Where a kind appears in the editor's menu and in the tests.
pub trait Catalogue: Sized {
    /// The add-node menu's entries for this kind: a name and the settings it starts with.
    fn menu() -> Vec<(String, Self)>;
    /// Settings the tests cover: every structural variant worth comparing between the
    /// CPU and the GPU.
    fn examples() -> Vec<Self>;
}

/// The inspector's view of a kind's structural settings.
pub trait Configure {
    /// The settings, each borrowing the value it edits.
    fn settings(&mut self) -> Vec<Setting<'_>>;
}

/// Gathers the families' kinds into [`NodeKind`] and its dispatch. Each family's
/// `kinds!` macro appends its unit kinds (no settings) and its kinds with settings, then
/// hands on to the next family.
macro_rules! registry {
    (@gather [$($units:tt)*] [$($configured:tt)*]) => {
        registry!(@define [$($units)*] [$($configured)*]);
    };
    (@gather [$($units:tt)*] [$($configured:tt)*] $family:ident $($rest:ident)*) => {
        $family::kinds!(registry @gather [$($units)*] [$($configured)*] $($rest)*);
    };
    (@define [$(($unit:ident, $unit_family:ident))*] [$(($kind:ident, $kind_family:ident))*]) => {
        /// Every kind of node Veneer knows, with its structural settings (see each
        /// definition in its family file).
        #[derive(Clone, Debug, PartialEq)]
        #[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
        pub enum NodeKind {
            $(
                #[doc = concat!("See [`", stringify!($unit_family), "::", stringify!($unit), "`].")]
                $unit,
            )*
            $(
                #[doc = concat!("See [`", stringify!($kind_family), "::", stringify!($kind), "`].")]
                $kind($kind_family::$kind),
            )*
        }

        impl NodeKind {
            /// The kind's definition.
            pub fn definition(&self) -> &dyn Definition {
                match self {
                    $(NodeKind::$unit => &$unit_family::$unit,)*
                    $(NodeKind::$kind(definition) => definition,)*
                }
            }

            /// The outputs of a node of this kind on the CPU.
            pub fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
                match self {
                    $(NodeKind::$unit => $unit_family::$unit.eval(io),)*
                    $(NodeKind::$kind(definition) => definition.eval(io),)*
                }
            }

            /// The structural settings, for the inspector.
            pub fn settings(&mut self) -> Vec<Setting<'_>> {
                match self {
                    $(NodeKind::$unit => Vec::new(),)*
                    $(NodeKind::$kind(definition) => definition.settings(),)*
                }
            }

            /// The add-node menu: every kind's entries, in registry order.
            pub fn menu() -> Vec<(String, NodeKind)> {
                let mut entries = Vec::new();
                $(entries.extend(
                    <$unit_family::$unit as Catalogue>::menu()
                        .into_iter()
                        .map(|(name, _)| (name, NodeKind::$unit)),
                );)*
                $(entries.extend(
                    <$kind_family::$kind as Catalogue>::menu()
                        .into_iter()
                        .map(|(name, settings)| (name, NodeKind::$kind(settings))),
                );)*
                entries
            }

            /// Every kind with the settings its tests cover.
            pub fn examples() -> Vec<NodeKind> {
                let mut kinds = Vec::new();
                $(kinds.extend(
                    <$unit_family::$unit as Catalogue>::examples()
                        .into_iter()
                        .map(|_| NodeKind::$unit),
                );)*
                $(kinds.extend(
                    <$kind_family::$kind as Catalogue>::examples()
                        .into_iter()
                        .map(NodeKind::$kind),
                );)*
                kinds
            }

            /// The name of every kind, as graph files spell it.
            pub const NAMES: &[&str] = &[$(stringify!($unit),)* $(stringify!($kind),)*];

            /// The kind's name, as graph files spell it.
            pub fn name(&self) -> &'static str {
                match self {
                    $(NodeKind::$unit => stringify!($unit),)*
                    $(NodeKind::$kind(_) => stringify!($kind),)*
                }
            }
        }

        impl Serialize for NodeKind {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let name = self.name();
                let index = NodeKind::NAMES.iter().position(|n| *n == name).unwrap_or(0) as u32;
                match self {
                    $(NodeKind::$unit => serializer.serialize_unit_variant("NodeKind", index, name),)*
                    $(NodeKind::$kind(settings) => {
                        file_form::serialize_inline(serializer, index, name, settings)
                    })*
                }
            }
        }

        impl<'de> Deserialize<'de> for NodeKind {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                struct Kinds;
                impl<'de> serde::de::Visitor<'de> for Kinds {
                    type Value = NodeKind;
                    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                        f.write_str("a node kind")
                    }
                    fn visit_enum<A: serde::de::EnumAccess<'de>>(
                        self,
                        data: A,
                    ) -> Result<NodeKind, A::Error> {
                        use serde::de::VariantAccess;
                        let (file_form::Name(name), variant) = data.variant()?;
                        match name.as_str() {
                            $(stringify!($unit) => variant.unit_variant().map(|()| NodeKind::$unit),)*
                            $(stringify!($kind) => variant
                                .struct_variant(&[], file_form::InlineVisitor::new())
                                .map(NodeKind::$kind),)*
                            other => Err(serde::de::Error::unknown_variant(other, NodeKind::NAMES)),
                        }
                    }
                }
                deserializer.deserialize_enum("NodeKind", NodeKind::NAMES, Kinds)
            }
        }
    };
}

registry!(@gather [] [] inputs coordinates noise fractal cellular patterns shapes scatter fields mesh_field math mapping vectors colour sampled bitmap graph_bake image_ops distance flood_fill levels output group);

impl NodeKind {
    /// A short human-readable name (used for default labels and messages).
    pub fn title(&self) -> &'static str {
        self.definition().title()
    }

    /// The menu category.
    pub fn category(&self) -> Category {
        self.definition().category()
    }

    /// The pins of this node kind (they depend on settings such as `ty`).
    pub fn signature(&self) -> Signature {
        self.definition().signature()
    }

    /// The lattice basis the node samples, if any.
    pub fn basis(&self) -> Option<Basis> {
        self.definition().basis()
    }

    /// Whether the node re-evaluates an input's upstream per instance it places.
    pub fn re_evaluates(&self) -> bool {
        self.signature().inputs.iter().any(|pin| pin.re_evaluated)
    }

    /// Whether the node reads an input as a buffer (at other points than the one
    /// shaded) or reads a bitmap file: a graph using it renders passes.
    pub fn samples(&self) -> bool {
        self.signature().inputs.iter().any(|pin| pin.sampled)
            || self.definition().bitmap().is_some()
    }
}

/// The outputs' ranges of a kind with one float output in [0, 1].
fn unit_range() -> Vec<Lanes> {
    vec![interval::splat(interval::Interval::UNIT)]
}
