//! What a graph's preview settings must satisfy before anything renders them: a
//! placement that survives the conversion to the GPU's f32, and field settings the
//! geodesic methods can honour. (Source vertices are checked against the mesh when it is
//! loaded: `geodesic::check_field_sources`.)

use super::Preview;

/// Whether `value` is finite and stays finite as an f32.
fn fits_f32(value: f64) -> bool {
    value.is_finite() && value.abs() <= f64::from(f32::MAX)
}

impl Preview {
    /// Every problem of the preview settings, as messages naming the setting; empty
    /// when they are fine.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if !(fits_f32(self.size) && self.size > 0.0) {
            problems.push(format!(
                "preview size {} must be a positive number within the f32 range",
                self.size
            ));
        }
        let (x, y, z) = self.center;
        if ![x, y, z].into_iter().all(fits_f32) {
            problems.push(format!(
                "preview center ({x}, {y}, {z}) must be finite numbers within the f32 range"
            ));
        }
        if self.fields.len() > 4 {
            problems.push(format!(
                "{} preview fields given; a mesh carries at most 4",
                self.fields.len()
            ));
        }
        for (slot, field) in self.fields.iter().enumerate() {
            if let Err(error) = field.method.validate() {
                problems.push(format!("preview field {slot}: {error}"));
            }
        }
        if let Some(tessellation) = &self.tessellation
            && let Err(error) = tessellation.refinement().validate()
        {
            problems.push(format!("preview {error}"));
        }
        problems
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph::{FieldSource, HeatOptions, Method};

    #[test]
    fn non_finite_placements_and_bad_fields_are_named() {
        let mut preview = Preview::default();
        assert!(preview.problems().is_empty());
        preview.size = f64::NAN;
        preview.center = (0.0, f64::INFINITY, 1e39);
        preview.fields = vec![
            FieldSource {
                sources: vec![0],
                method: Method::Heat(HeatOptions {
                    time_factor: 0.0,
                    ..HeatOptions::default()
                }),
            };
            5
        ];
        let problems = preview.problems().join("\n");
        for expected in [
            "preview size NaN",
            "preview center",
            "5 preview fields",
            "preview field 4: time factor 0",
        ] {
            assert!(
                problems.contains(expected),
                "{expected} missing from {problems}"
            );
        }
    }
}
