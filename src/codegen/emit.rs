//! WGSL for each node: the statements it adds to `veneer_material` and the library
//! items it calls.

use crate::graph::check::CheckedNode;
use crate::graph::{
    MathOp, Metric, NodeKind, RampInterpolation, UnaryOp, Value, ValueType, WorleyFeature,
};

/// A WGSL f32 literal for `x` (`0.35f`): typed, so that expressions of constants only
/// are never abstract (naga rejects builtins of abstract arguments outside constants).
pub fn float_literal(x: f64) -> String {
    let text = format!("{x:?}");
    let text = if text.contains(['.', 'e', 'E']) {
        text
    } else {
        format!("{text}.0")
    };
    format!("{text}f")
}

/// A WGSL literal for a constant.
pub fn value_literal(value: &Value) -> String {
    match *value {
        Value::Float(x) => float_literal(x),
        Value::Vec2(x, y) => format!("vec2f({}, {})", float_literal(x), float_literal(y)),
        Value::Vec3(x, y, z) | Value::Color(x, y, z) => {
            format!(
                "vec3f({}, {}, {})",
                float_literal(x),
                float_literal(y),
                float_literal(z)
            )
        }
    }
}

/// A literal of type `ty` from three f32 lanes (a folded constant), each written as the
/// shortest decimal that reads back as the same f32.
pub fn lanes_literal(ty: ValueType, lanes: [f32; 3]) -> String {
    let [x, y, z] = lanes.map(|lane| {
        let text = format!("{lane:?}");
        if text.contains(['.', 'e', 'E']) {
            format!("{text}f")
        } else {
            format!("{text}.0f")
        }
    });
    match ty {
        ValueType::Float => x,
        ValueType::Vec2 => format!("vec2f({x}, {y})"),
        ValueType::Vec3 | ValueType::Color => format!("vec3f({x}, {y}, {z})"),
    }
}

/// What one node contributes to the material function.
#[derive(Default)]
pub struct NodeCode {
    /// Statements, one per line, without indentation.
    pub statements: Vec<String>,
    /// One WGSL expression per output pin.
    pub outputs: Vec<String>,
    /// Library items the statements call.
    pub library: Vec<String>,
    /// The WGSL type of the identifier the statements bind (the node's name), if any.
    pub binding: Option<&'static str>,
}

impl NodeCode {
    /// `let name = expression;`, of type `ty`.
    fn bind(&mut self, name: &str, ty: &'static str, expression: String) {
        self.statements.push(format!("let {name} = {expression};"));
        self.binding = Some(ty);
    }
}

/// Emits one node. `inputs` holds a WGSL expression per input pin, already converted
/// to the pin's type; `name` is the identifier reserved for the node.
pub fn emit_node(
    checked: &CheckedNode,
    inputs: &[String],
    name: &str,
    detail: super::Detail,
) -> NodeCode {
    use NodeKind::*;
    let mut code = NodeCode::default();
    let i = inputs;
    // Typed, so that an expression of constants only (abstract in WGSL) becomes f32.
    let output_type = checked
        .signature
        .outputs
        .first()
        .map(|pin| pin.ty.wgsl())
        .unwrap_or("f32");
    let single = |code: &mut NodeCode, expression: String| {
        code.statements
            .push(format!("let {name}: {output_type} = {expression};"));
        code.outputs = vec![name.to_string()];
        code.binding = Some(output_type);
    };
    match &checked.node.kind {
        Position => code.outputs = vec!["s.position".into()],
        Normal => code.outputs = vec!["s.normal".into()],
        Uv => code.outputs = vec!["s.uv".into()],
        Time => code.outputs = vec!["s.time".into()],
        Field { slot } => {
            code.outputs = vec![format!("s.fields.{}", ["x", "y", "z", "w"][*slot as usize])]
        }
        Constant { .. } => single(&mut code, i[0].clone()),
        Transform => {
            let no_rotation = i[2] == value_literal(&Value::Vec3(0.0, 0.0, 0.0));
            if no_rotation {
                single(&mut code, format!("{} * {} + {}", i[0], i[1], i[3]));
            } else {
                code.library.push("veneer_transform".into());
                single(
                    &mut code,
                    format!("veneer_transform({}, {}, {}, {})", i[0], i[1], i[2], i[3]),
                );
            }
        }
        Project => {
            code.library.push("veneer_project".into());
            single(
                &mut code,
                format!("veneer_project({}, {}, {})", i[0], i[1], i[2]),
            );
        }
        Cylindrical => {
            code.library.push("veneer_cylindrical".into());
            code.bind(
                name,
                "vec3f",
                format!("veneer_cylindrical({}, {}, {})", i[0], i[1], i[2]),
            );
            code.outputs = ["x", "y", "z"]
                .iter()
                .map(|c| format!("{name}.{c}"))
                .collect();
        }
        DomainWarp { basis } => {
            let function = format!("veneer_warp_{}", basis.suffix());
            single(
                &mut code,
                format!("{function}({}, {}, {})", i[0], i[1], i[2]),
            );
            code.library.push(function);
        }
        Noise { basis } => {
            let function = format!("veneer_noise_{}", basis.suffix());
            single(&mut code, format!("{function}({} * {})", i[0], i[1]));
            code.library.push(function);
        }
        Fbm { .. } | Turbulence { .. } | FractalSum { .. } => {
            let (mode, basis, octaves, normalize) =
                checked.node.kind.fractal().expect("a fractal kind");
            let function = format!("veneer_{}_{}", mode.name(), basis.suffix());
            let q = format!("{} * {}", i[0], i[1]);
            let cutoff = match detail {
                super::Detail::Full => float_literal(1.0e9),
                super::Detail::Footprint => {
                    code.library.push("veneer_octave_cutoff".to_string());
                    format!("veneer_octave_cutoff({q}, {})", i[2])
                }
            };
            single(
                &mut code,
                format!(
                    "{function}({q}, {octaves}, {}, {}, {}, {normalize}, {cutoff})",
                    i[2], i[3], i[4]
                ),
            );
            code.library.push(function);
        }
        Worley {
            feature,
            metric,
            octaves,
        } => {
            let feature = worley_feature_index(*feature);
            let metric = metric_index(*metric);
            let expression = if *octaves == 1 {
                code.library
                    .extend(["veneer_worley".into(), "veneer_worley_feature".into()]);
                format!(
                    "veneer_worley_feature(veneer_worley({} * {}, {}, {metric}), {feature})",
                    i[0], i[1], i[2]
                )
            } else {
                code.library.push("veneer_worley_fractal".into());
                format!(
                    "veneer_worley_fractal({} * {}, {}, {metric}, {feature}, {octaves}, {}, {})",
                    i[0], i[1], i[2], i[3], i[4]
                )
            };
            single(&mut code, expression);
        }
        SineBand => call(&mut code, name, "veneer_sine_band", i),
        TriangleWave => call(&mut code, name, "veneer_triangle_wave", i),
        Front => call(&mut code, name, "veneer_front", i),
        Isolines => call(&mut code, name, "veneer_isolines", i),
        Layers { .. } => {
            let front = |edge: &str| format!("veneer_front({}, {edge}, {}, {})", i[0], i[2], i[1]);
            single(
                &mut code,
                format!(
                    "mix(mix(mix({}, {}, {}), {}, {}), {}, {})",
                    i[9],
                    i[8],
                    front(&i[5]),
                    i[7],
                    front(&i[4]),
                    i[6],
                    front(&i[3])
                ),
            );
            code.library.push("veneer_front".to_string());
        }
        NoiseBump { basis } => {
            let function = format!("veneer_noise_bump_{}", basis.suffix());
            single(
                &mut code,
                format!("{function}({}, {}, {})", i[0], i[1], i[2]),
            );
            code.library.push(function);
        }
        Tiles => {
            code.library.push("veneer_tiles".into());
            code.bind(
                name,
                "veneer_tiles_result",
                format!("veneer_tiles({})", i.join(", ")),
            );
            code.outputs = ["mask", "cell", "local"]
                .iter()
                .map(|c| format!("{name}.{c}"))
                .collect();
        }
        Rings => call(&mut code, name, "veneer_rings", i),
        Math { op, ty } => {
            let t = ty.wgsl();
            let expression = match op {
                MathOp::Add => format!("{} + {}", i[0], i[1]),
                MathOp::Subtract => format!("{} - {}", i[0], i[1]),
                MathOp::Multiply => format!("{} * {}", i[0], i[1]),
                MathOp::Minimum => format!("min({}, {})", i[0], i[1]),
                MathOp::Maximum => format!("max({}, {})", i[0], i[1]),
                MathOp::Divide | MathOp::Power => {
                    let stem = if *op == MathOp::Divide {
                        "safe_div"
                    } else {
                        "safe_pow"
                    };
                    let function = format!("veneer_{stem}_{t}");
                    let expression = format!("{function}({}, {})", i[0], i[1]);
                    code.library.push(function);
                    expression
                }
            };
            single(&mut code, expression);
        }
        Unary { op, .. } => {
            let x = &i[0];
            let expression = match op {
                UnaryOp::Abs => format!("abs({x})"),
                UnaryOp::Fract => format!("fract({x})"),
                UnaryOp::Floor => format!("floor({x})"),
                UnaryOp::Sin => format!("sin({x})"),
                UnaryOp::Cos => format!("cos({x})"),
                UnaryOp::Negate => format!("-({x})"),
                UnaryOp::OneMinus => format!("1.0 - {x}"),
            };
            single(&mut code, expression);
        }
        Mix { .. } => single(&mut code, format!("mix({}, {}, {})", i[0], i[1], i[2])),
        Clamp { ty } => {
            let t = ty.wgsl();
            single(
                &mut code,
                format!("min(max({}, {t}({})), {t}({}))", i[0], i[1], i[2]),
            );
        }
        Step { ty } => single(
            &mut code,
            format!("step({}({}), {})", ty.wgsl(), i[0], i[1]),
        ),
        Smoothstep => call(&mut code, name, "veneer_smoothstep", i),
        Remap => call(&mut code, name, "veneer_remap", i),
        Length { .. } => single(&mut code, format!("length({})", i[0])),
        Dot { .. } => single(&mut code, format!("dot({}, {})", i[0], i[1])),
        Normalize { ty } => {
            let function = format!("veneer_safe_normalize_{}", ty.wgsl());
            single(&mut code, format!("{function}({})", i[0]));
            code.library.push(function);
        }
        Split { ty } => {
            code.bind(name, ty.wgsl(), i[0].clone());
            code.outputs = ["x", "y", "z"][..ty.width()]
                .iter()
                .map(|c| format!("{name}.{c}"))
                .collect();
        }
        Combine { ty } => single(&mut code, format!("{}({})", ty.wgsl(), i.join(", "))),
        ColorRamp {
            stops,
            interpolation,
        } => {
            let color = |k: usize| {
                value_literal(&Value::Color(
                    stops[k].color.0,
                    stops[k].color.1,
                    stops[k].color.2,
                ))
            };
            if stops.len() == 1 {
                single(&mut code, color(0));
            } else {
                code.statements.push(format!("var {name} = {};", color(0)));
                code.binding = Some("vec3f");
                for k in 1..stops.len() {
                    let (p0, p1) = (
                        float_literal(stops[k - 1].position),
                        float_literal(stops[k].position),
                    );
                    code.statements.push(match interpolation {
                        RampInterpolation::Linear => {
                            format!(
                                "{name} = veneer_ramp_linear({name}, {}, {}, {p0}, {p1});",
                                color(k),
                                i[0]
                            )
                        }
                        RampInterpolation::Constant => {
                            format!(
                                "{name} = veneer_ramp_constant({name}, {}, {}, {p1});",
                                color(k),
                                i[0]
                            )
                        }
                    });
                }
                code.library.push(match interpolation {
                    RampInterpolation::Linear => "veneer_ramp_linear".into(),
                    RampInterpolation::Constant => "veneer_ramp_constant".into(),
                });
                code.outputs = vec![name.to_string()];
            }
        }
        Material => {
            code.statements.push("return VeneerMaterial(".into());
            for (pin, expression) in checked.signature.inputs.iter().zip(i) {
                code.statements
                    .push(format!("    {expression}, // {}", pin.name));
            }
            code.statements.push(");".into());
        }
    }
    code
}

fn call(code: &mut NodeCode, name: &str, function: &str, inputs: &[String]) {
    code.statements.push(format!(
        "let {name}: f32 = {function}({});",
        inputs.join(", ")
    ));
    code.outputs = vec![name.to_string()];
    code.library.push(function.to_string());
    code.binding = Some("f32");
}

/// The integer the WGSL library uses for a Worley feature.
pub fn worley_feature_index(feature: WorleyFeature) -> i32 {
    match feature {
        WorleyFeature::F1 => 0,
        WorleyFeature::F2 => 1,
        WorleyFeature::F3 => 2,
        WorleyFeature::F2MinusF1 => 3,
    }
}

/// The integer the WGSL library uses for a distance metric.
pub fn metric_index(metric: Metric) -> i32 {
    match metric {
        Metric::Euclidean => 0,
        Metric::Manhattan => 1,
        Metric::Chebyshev => 2,
    }
}

/// `expression` of type `from` converted to `to` (a float broadcasts).
pub fn convert(expression: String, from: ValueType, to: ValueType) -> String {
    if from == ValueType::Float && to != ValueType::Float {
        format!("{}({expression})", to.wgsl())
    } else {
        expression
    }
}
