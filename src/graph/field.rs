//! Distance fields as the graph file describes them: the source vertices of each field
//! of the preview mesh and the method that solves it. They are part of the file format,
//! so they live here; `geodesic` solves them (and re-exports [`Method`] and
//! [`HeatOptions`]), and the graph never depends on the solvers.

use serde::{Deserialize, Serialize};

/// A distance field over the preview mesh: the vertices it spreads from (numbered as
/// the mesh file lists them, see [`crate::mesh::FileVertices`]) and how it is computed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FieldSource {
    pub sources: Vec<u32>,
    #[serde(default = "FieldSource::default_method")]
    pub method: Method,
}

impl FieldSource {
    fn default_method() -> Method {
        Method::Heat(Default::default())
    }
}

/// How a distance field is computed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Method {
    /// The heat method.
    Heat(HeatOptions),
    /// Exact polyhedral distances (window propagation), within a budget of windows per
    /// triangle that good meshes never reach; a degenerate mesh that exhausts it gets
    /// paths along edges (upper bounds) for the vertices left.
    Exact,
    /// Shortest paths along edges.
    Dijkstra,
}

impl Method {
    /// A short name for reports and messages.
    pub fn name(self) -> &'static str {
        match self {
            Method::Heat(HeatOptions { robust, refine, .. }) => match (robust, refine) {
                (false, true) => "heat",
                (true, true) => "heat (robust)",
                (false, false) => "heat (unrefined)",
                (true, false) => "heat (robust, unrefined)",
            },
            Method::Exact => "exact",
            Method::Dijkstra => "dijkstra",
        }
    }

    /// Refuses settings that cannot give a meaningful field (a heat time factor out of
    /// range), before any mesh work.
    pub fn validate(self) -> Result<(), TimeFactorError> {
        match self {
            Method::Heat(options) => options.validate(),
            Method::Exact | Method::Dijkstra => Ok(()),
        }
    }
}

/// Choices of the heat method.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct HeatOptions {
    /// The diffusion time as a multiple of the mean edge length squared (1 is the
    /// paper's choice; smaller is sharper but stiffer, larger is smoother).
    pub time_factor: f64,
    /// Mollify the edge lengths and retriangulate to the intrinsic Delaunay
    /// triangulation first, for meshes with slivers and degenerate triangles.
    pub robust: bool,
    /// Solve on an intrinsic Delaunay refinement of the mesh: edges flipped to Delaunay,
    /// those longer than the mean split at their midpoints (at most 1.5 new vertices per
    /// vertex a triangle uses), the same surface sampled more finely and evenly. More accurate, at up
    /// to twice the set-up. Meshes of more than 100,000 vertices are solved unrefined
    /// (`geodesic::REFINE_UP_TO`: there refining costs more than twice). Files leave it
    /// out when on (files from before it existed load refined).
    #[serde(skip_serializing_if = "is_on")]
    pub refine: bool,
}

/// Whether `flag` is on (for leaving a setting that is on by default out of files).
fn is_on(flag: &bool) -> bool {
    *flag
}

impl Default for HeatOptions {
    fn default() -> Self {
        HeatOptions {
            time_factor: 1.0,
            robust: false,
            refine: true,
        }
    }
}

impl HeatOptions {
    /// The time factors the method is trusted with. Below, the heat underflows between
    /// neighbours and the field is wrong beyond the sources' first ring (20% off at
    /// 10⁻³ on a torus, 35% at 10⁻⁶); above, the mass term is lost in rounding against
    /// the Laplacian and every distance collapses towards 0 (96% off at 10¹², all 0 at
    /// 10¹³; still 5% at 10⁶, as at 10³).
    pub const TIME_FACTORS: std::ops::RangeInclusive<f64> = 1.0e-3..=1.0e6;

    /// Refuses options the method cannot give a meaningful field with.
    pub fn validate(&self) -> Result<(), TimeFactorError> {
        if Self::TIME_FACTORS.contains(&self.time_factor) {
            Ok(())
        } else {
            Err(TimeFactorError(self.time_factor))
        }
    }
}

/// A heat time factor outside [`HeatOptions::TIME_FACTORS`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "time factor {0:e} is outside {min:e} to {max:e}: smaller ones underflow the heat, larger ones round every distance towards 0 (1 is the usual choice)",
    min = HeatOptions::TIME_FACTORS.start(),
    max = HeatOptions::TIME_FACTORS.end()
)]
pub struct TimeFactorError(pub f64);
