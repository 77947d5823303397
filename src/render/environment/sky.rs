//! The procedural sky Veneer lights metallic-roughness previews with by default: a blue
//! zenith fading to a pale horizon, a dim warm ground, and two soft rectangular studio
//! panels that give polished and metallic materials something to reflect. Every edge is
//! smooth, so the prefiltered maps have no fireflies and the background no aliasing.

use glam::Vec3;

/// Radiance (linear) straight up, at the horizon and of the ground.
const ZENITH: Vec3 = Vec3::new(0.22, 0.32, 0.52);
const HORIZON: Vec3 = Vec3::new(0.62, 0.62, 0.64);
const GROUND: Vec3 = Vec3::new(0.11, 0.10, 0.09);

/// A soft rectangular panel: where it faces from, its half-extents across and up (in
/// the tangent plane of its direction) and its radiance.
struct Panel {
    direction: Vec3,
    half_width: f32,
    half_height: f32,
    radiance: f32,
}

/// A key panel high on the left-front and a fill panel low on the right-back.
const PANELS: [Panel; 2] = [
    Panel {
        direction: Vec3::new(-0.45, 0.55, 0.70),
        half_width: 0.32,
        half_height: 0.20,
        radiance: 3.0,
    },
    Panel {
        direction: Vec3::new(0.80, 0.25, -0.55),
        half_width: 0.22,
        half_height: 0.30,
        radiance: 1.2,
    },
];

/// The sky's radiance from unit `direction`.
pub fn radiance(direction: Vec3) -> Vec3 {
    let y = direction.y;
    let sky = HORIZON.lerp(ZENITH, y.max(0.0).powf(0.6));
    // The ground darkens within a few degrees below the horizon.
    let ground = (HORIZON * 0.5).lerp(GROUND, (-y * 12.0).clamp(0.0, 1.0));
    let base = if y >= 0.0 { sky } else { ground };
    base + Vec3::splat(PANELS.iter().map(|panel| panel.light(direction)).sum())
}

impl Panel {
    /// The panel's radiance seen from `direction`: full inside, fading out over the
    /// outer fifth of each half-extent.
    fn light(&self, direction: Vec3) -> f32 {
        let axis = self.direction.normalize();
        let facing = direction.dot(axis);
        if facing <= 0.0 {
            return 0.0;
        }
        let across = Vec3::Y.cross(axis).normalize();
        let up = axis.cross(across);
        // Gnomonic coordinates: where the ray meets the plane one unit along the axis.
        let (x, y) = (direction.dot(across) / facing, direction.dot(up) / facing);
        let edge =
            |coordinate: f32, half: f32| 1.0 - smoothstep(0.8 * half, half, coordinate.abs());
        self.radiance * edge(x, self.half_width) * edge(y, self.half_height)
    }
}

fn smoothstep(low: f32, high: f32, x: f32) -> f32 {
    let t = ((x - low) / (high - low)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}
