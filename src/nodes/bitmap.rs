//! The Image node: a bitmap read from a file (PNG, JPEG, OpenEXR, HDR) over the
//! material's 2D domain, the unit tile. The compiler uploads the file's pixels into a
//! buffer (a pass that renders nothing) and the node reads it at the point's domain
//! coordinate, like a Buffer node reads a rendered one.

use super::cpu::Eval;
use super::emit::{Emit, float_literal};
use super::formulas::real::{Real, V3};
use super::interval::{Interval, Lanes};
use super::passes::{EdgeMode, Filter};
use super::pins::{COLOR, FLOAT, Signature, output};
use super::ranges::Ranges;
use super::sampled::image_node;
use super::settings::{Basis, Setting, choice};
use super::{Catalogue, Category, Configure, Definition, Evaluate};
use crate::bitmaps::{ColourSpace, MAX_TEXEL_VALUE};
use serde::{Deserialize, Serialize};

macro_rules! kinds {
    ($registry:ident @gather [$($units:tt)*] [$($configured:tt)*] $($rest:tt)*) => {
        $registry!(@gather [$($units)*] [$($configured)* (ImageFile, bitmap)] $($rest)*);
    };
}
pub(super) use kinds;

/// The weights of linear Rec. 709 luminance, which the `value` output reads.
pub const LUMINANCE: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// What an Image node reads: its file and how the file's numbers become values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BitmapSource<'a> {
    /// The path as the graph stores it, relative to the graph file's folder.
    pub path: &'a str,
    pub colour_space: ColourSpace,
    /// What reads past the image's edges see.
    pub edge: EdgeMode,
}

/// A bitmap from a file, stretched over the unit tile (its top row at v = 0), read
/// bilinearly or bicubically: photos, painted masks, height maps.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
#[serde(default)]
pub struct ImageFile {
    /// The file, relative to the graph file's folder (`../assets/photo.jpg`).
    pub path: String,
    pub colour_space: ColourSpace,
    pub edge: EdgeMode,
    pub filter: Filter,
}

impl Definition for ImageFile {
    fn title(&self) -> &'static str {
        "Image"
    }
    image_node!();
    fn keywords(&self) -> &'static [&'static str] {
        &[
            "bitmap", "photo", "picture", "texture", "file", "png", "jpeg", "exr", "hdr", "mask",
        ]
    }
    fn signature(&self) -> Signature {
        Signature::new(
            Vec::new(),
            vec![
                output("colour", COLOR),
                output("alpha", FLOAT),
                output("value", FLOAT),
            ],
        )
    }
    fn check(&self) -> Option<String> {
        // Whether the file can be read is checked against the graph's folder (see
        // `graph::check`); here, only what needs no file.
        (self.path.len() > 4096).then(|| {
            format!(
                "the path is {} bytes long, more than 4,096",
                self.path.len()
            )
        })
    }
    fn emit(&self, io: &mut Emit) {
        let function = self.filter.wgsl();
        io.bind("vec4f", format!("{function}({}, s.uv)", io.source()));
        io.uses(function);
        let name = io.name();
        let [r, g, b] = LUMINANCE.map(float_literal);
        io.outputs(vec![
            format!("{name}.xyz"),
            format!("{name}.w"),
            format!("dot({name}.xyz, vec3f({r}, {g}, {b}))"),
        ]);
    }
    fn ranges(&self, io: &mut Ranges) -> Vec<Lanes> {
        // The file's own lanes where the lint has read it; anything a texel keeps if not.
        let any = Interval::new(-f64::from(MAX_TEXEL_VALUE), f64::from(MAX_TEXEL_VALUE));
        let lanes = io
            .bitmap()
            .unwrap_or([any; 4])
            .map(|lane| self.filter.range(lane));
        let weighted = |end: fn(&Interval) -> f64| -> f64 {
            (lanes.iter().zip(LUMINANCE))
                .map(|(lane, weight)| weight * end(lane))
                .sum()
        };
        let value = Interval::new(weighted(|lane| lane.lo), weighted(|lane| lane.hi));
        vec![[lanes[0], lanes[1], lanes[2]], [lanes[3]; 3], [value; 3]]
    }
    fn bitmap(&self) -> Option<BitmapSource<'_>> {
        Some(BitmapSource {
            path: &self.path,
            colour_space: self.colour_space,
            edge: self.edge,
        })
    }
}

impl Evaluate for ImageFile {
    fn eval<R: Real>(&self, io: &Eval<R>) -> Vec<V3<R>> {
        let texel = self.filter.read(io.source(), io.domain());
        let colour = [texel[0], texel[1], texel[2]];
        let value: f64 = (colour.iter().zip(LUMINANCE))
            .map(|(lane, weight)| lane * weight)
            .sum();
        vec![colour.map(R::c), [R::c(texel[3]); 3], [R::c(value); 3]]
    }
}

impl Configure for ImageFile {
    fn settings(&mut self) -> Vec<Setting<'_>> {
        vec![
            Setting::File {
                label: "file",
                value: &mut self.path,
                extensions: &["png", "jpg", "jpeg", "exr", "hdr"],
            },
            choice("colour space", &mut self.colour_space, &ColourSpace::ALL),
            choice("edges", &mut self.edge, &EdgeMode::ALL),
            choice("filter", &mut self.filter, &Filter::ALL),
        ]
    }
}

impl Catalogue for ImageFile {
    fn menu() -> Vec<(String, Self)> {
        vec![("Image".into(), ImageFile::default())]
    }
    fn examples() -> Vec<Self> {
        // Tests run in the crate's folder, which graphs without a file are relative to.
        let photo = "assets/photos/gravel.jpg".to_string();
        vec![
            ImageFile {
                path: photo.clone(),
                ..ImageFile::default()
            },
            ImageFile {
                path: photo,
                colour_space: ColourSpace::Linear,
                edge: EdgeMode::Mirror,
                filter: Filter::Bicubic,
            },
        ]
    }
}
