//! Pin types and constant values stored in graph files.

use serde::{Deserialize, Serialize};
use std::fmt;

/// The type carried by a pin or a wire.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ValueType {
    Float,
    Vec2,
    Vec3,
    Color,
}

impl ValueType {
    /// Number of scalar components.
    pub fn width(self) -> usize {
        match self {
            ValueType::Float => 1,
            ValueType::Vec2 => 2,
            ValueType::Vec3 | ValueType::Color => 3,
        }
    }

    /// The WGSL spelling of the type.
    pub fn wgsl(self) -> &'static str {
        match self {
            ValueType::Float => "f32",
            ValueType::Vec2 => "vec2f",
            ValueType::Vec3 | ValueType::Color => "vec3f",
        }
    }

    /// Whether a wire from an output of type `self` may feed an input of type `to`.
    ///
    /// A float broadcasts to any vector (as in Blender's shader nodes), and vec3 and
    /// colour are interchangeable; everything else is a type mismatch.
    pub fn converts_to(self, to: ValueType) -> bool {
        self == to || self == ValueType::Float || (self.width() == 3 && to.width() == 3)
    }
}

impl fmt::Display for ValueType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = match self {
            ValueType::Float => "float",
            ValueType::Vec2 => "vec2",
            ValueType::Vec3 => "vec3",
            ValueType::Color => "color",
        };
        f.write_str(name)
    }
}

/// A constant value of an unconnected input, as written in a graph file.
///
/// Values are kept in f64 so that the f64 reference evaluator sees exactly the
/// decimal the artist typed; the GPU rounds them to f32.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Value {
    Float(f64),
    Vec2(f64, f64),
    Vec3(f64, f64, f64),
    Color(f64, f64, f64),
}

impl Value {
    /// The type of this value.
    pub fn ty(&self) -> ValueType {
        match self {
            Value::Float(_) => ValueType::Float,
            Value::Vec2(..) => ValueType::Vec2,
            Value::Vec3(..) => ValueType::Vec3,
            Value::Color(..) => ValueType::Color,
        }
    }

    /// The components, padded with zeros to three.
    pub fn components(&self) -> [f64; 3] {
        match *self {
            Value::Float(x) => [x, x, x],
            Value::Vec2(x, y) => [x, y, 0.0],
            Value::Vec3(x, y, z) | Value::Color(x, y, z) => [x, y, z],
        }
    }

    /// This value converted to `ty` (a float broadcasts; vec3 and colour swap freely).
    pub fn convert(&self, ty: ValueType) -> Value {
        let [x, y, z] = self.components();
        match ty {
            ValueType::Float => Value::Float(x),
            ValueType::Vec2 => Value::Vec2(x, y),
            ValueType::Vec3 => Value::Vec3(x, y, z),
            ValueType::Color => Value::Color(x, y, z),
        }
    }

    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        self.components().iter().all(|c| c.is_finite())
    }
}
