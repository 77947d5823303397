//! The node kinds MaterialX's standard library means the same thing as: each written
//! with standard nodes (one, or a short chain) instead of a definition of Veneer's own.
//! Where Veneer guards against overflow (sums, products and blends clamped to ±3·10³⁸,
//! lengths of huge vectors scaled first), the standard node computes the same value
//! everywhere the result is finite; where Veneer defines a value the standard node
//! leaves undefined (division by zero, a normalised zero vector, a smoothstep whose
//! edges meet or cross), the kind keeps its own definition.

use super::custom::mx_type;
use super::network::{Input, Node, Source, input, node};
use crate::nodes::NodeKind;
use crate::nodes::settings::{MathOp, UnaryOp};
use crate::nodes::value::ValueType;

/// What one translated node adds: the standard nodes, and per output pin of the Veneer
/// node the source that gives it.
pub struct Translated {
    pub nodes: Vec<Node>,
    pub outputs: Vec<Source>,
}

/// `kind` written with standard nodes, the last one named `name`, reading `arguments`
/// (one source per input pin of the kind, already of the pin's type); `None` when the
/// standard library has no node that means the same.
pub fn standard(kind: &NodeKind, name: &str, arguments: &[Source]) -> Option<Translated> {
    let arg = |k: usize| arguments[k].clone();
    let value = |text: &str| Source::Value(text.to_string());
    let single = |category: &str, ty: ValueType, suffix: &str, inputs: Vec<Input>| {
        let nodedef = format!("ND_{category}_{}{suffix}", mx_type(ty));
        Translated {
            nodes: vec![node(name, category, mx_type(ty), &nodedef, inputs)],
            outputs: vec![Source::Node(name.to_string())],
        }
    };
    let geometric = |category: &str, space: bool| {
        let ty = if category == "texcoord" {
            ValueType::Vec2
        } else {
            ValueType::Vec3
        };
        let inputs = match space {
            true => vec![input("space", "string", value("object"))],
            false => Vec::new(),
        };
        single(category, ty, "", inputs)
    };
    Some(match kind {
        NodeKind::Normal => geometric("normal", true),
        NodeKind::Time => Translated {
            nodes: vec![node(name, "time", "float", "ND_time_float", Vec::new())],
            outputs: vec![Source::Node(name.to_string())],
        },
        NodeKind::Uv => uv(name),
        NodeKind::Constant(constant) => single(
            "constant",
            constant.ty,
            "",
            vec![input("value", mx_type(constant.ty), arg(0))],
        ),
        NodeKind::Math(math) => {
            let category = match math.op {
                MathOp::Add => "add",
                MathOp::Subtract => "subtract",
                MathOp::Multiply => "multiply",
                MathOp::Minimum => "min",
                MathOp::Maximum => "max",
                MathOp::Divide | MathOp::Power => return None,
            };
            let ty = mx_type(math.ty);
            single(
                category,
                math.ty,
                "",
                vec![input("in1", ty, arg(0)), input("in2", ty, arg(1))],
            )
        }
        NodeKind::Unary(unary) => {
            let ty = mx_type(unary.ty);
            let trig = unary.ty != ValueType::Color;
            let zero_or_one =
                |one: bool| value(&super::value_text(&[f64::from(u8::from(one)); 3], unary.ty));
            match unary.op {
                UnaryOp::Abs => single("absval", unary.ty, "", vec![input("in", ty, arg(0))]),
                UnaryOp::Floor => single("floor", unary.ty, "", vec![input("in", ty, arg(0))]),
                UnaryOp::Sin if trig => single("sin", unary.ty, "", vec![input("in", ty, arg(0))]),
                UnaryOp::Cos if trig => single("cos", unary.ty, "", vec![input("in", ty, arg(0))]),
                UnaryOp::Sin | UnaryOp::Cos => return None,
                // x − 1·floor(x / 1) is x − floor(x) exactly.
                UnaryOp::Fract => {
                    let suffix = if unary.ty == ValueType::Float {
                        ""
                    } else {
                        "FA"
                    };
                    single(
                        "modulo",
                        unary.ty,
                        suffix,
                        vec![input("in1", ty, arg(0)), input("in2", "float", value("1"))],
                    )
                }
                UnaryOp::Negate | UnaryOp::OneMinus => single(
                    "subtract",
                    unary.ty,
                    "",
                    vec![
                        input("in1", ty, zero_or_one(unary.op == UnaryOp::OneMinus)),
                        input("in2", ty, arg(0)),
                    ],
                ),
            }
        }
        NodeKind::Clamp(clamp) => {
            let suffix = if clamp.ty == ValueType::Float {
                ""
            } else {
                "FA"
            };
            single(
                "clamp",
                clamp.ty,
                suffix,
                vec![
                    input("in", mx_type(clamp.ty), arg(0)),
                    input("low", "float", arg(1)),
                    input("high", "float", arg(2)),
                ],
            )
        }
        // step(edge, x): 1 where x reaches the edge.
        NodeKind::Step(step) if step.ty == ValueType::Float => single(
            "ifgreatereq",
            ValueType::Float,
            "",
            vec![
                input("value1", "float", arg(1)),
                input("value2", "float", arg(0)),
                input("in1", "float", value("1")),
                input("in2", "float", value("0")),
            ],
        ),
        NodeKind::Mix(mix) => {
            let ty = mx_type(mix.ty);
            single(
                "mix",
                mix.ty,
                "",
                vec![
                    input("bg", ty, arg(0)),
                    input("fg", ty, arg(1)),
                    input("mix", "float", arg(2)),
                ],
            )
        }
        NodeKind::Length(length) if length.ty != ValueType::Float => Translated {
            nodes: vec![node(
                name,
                "magnitude",
                "float",
                &format!("ND_magnitude_{}", mx_type(length.ty)),
                vec![input("in", mx_type(length.ty), arg(0))],
            )],
            outputs: vec![Source::Node(name.to_string())],
        },
        NodeKind::Dot(dot) if matches!(dot.ty, ValueType::Vec2 | ValueType::Vec3) => Translated {
            nodes: vec![node(
                name,
                "dotproduct",
                "float",
                &format!("ND_dotproduct_{}", mx_type(dot.ty)),
                vec![
                    input("in1", mx_type(dot.ty), arg(0)),
                    input("in2", mx_type(dot.ty), arg(1)),
                ],
            )],
            outputs: vec![Source::Node(name.to_string())],
        },
        NodeKind::Split(split) => {
            let (category, outputs): (&str, &[&'static str]) = match split.ty {
                ValueType::Vec2 => ("separate2", &["outx", "outy"]),
                ValueType::Vec3 => ("separate3", &["outx", "outy", "outz"]),
                ValueType::Color => ("separate3", &["outr", "outg", "outb"]),
                ValueType::Float => return None,
            };
            let ty = mx_type(split.ty);
            Translated {
                nodes: vec![node(
                    name,
                    category,
                    "multioutput",
                    &format!("ND_{category}_{ty}"),
                    vec![input("in", ty, arg(0))],
                )],
                outputs: (outputs.iter())
                    .map(|output| Source::Output(name.to_string(), output.to_string()))
                    .collect(),
            }
        }
        NodeKind::Combine(combine) => {
            let category = match combine.ty {
                ValueType::Vec2 => "combine2",
                ValueType::Vec3 | ValueType::Color => "combine3",
                ValueType::Float => return None,
            };
            let inputs = (0..combine.ty.width())
                .map(|k| input(["in1", "in2", "in3"][k], "float", arg(k)))
                .collect();
            single(category, combine.ty, "", inputs)
        }
        _ => return None,
    })
}

/// Veneer's uv from MaterialX's texture coordinate: MaterialX counts v up from the
/// bottom of the image (as OpenGL and USD do), Veneer down from the top (as glTF does).
fn uv(name: &str) -> Translated {
    let part = |suffix: &str| format!("{name}_{suffix}");
    let texcoord = part("texcoord");
    let split = part("split");
    let flipped = part("v");
    let nodes = vec![
        node(
            &texcoord,
            "texcoord",
            "vector2",
            "ND_texcoord_vector2",
            Vec::new(),
        ),
        node(
            &split,
            "separate2",
            "multioutput",
            "ND_separate2_vector2",
            vec![input("in", "vector2", Source::Node(texcoord.clone()))],
        ),
        node(
            &flipped,
            "subtract",
            "float",
            "ND_subtract_float",
            vec![
                input("in1", "float", Source::Value("1".into())),
                input("in2", "float", Source::Output(split.clone(), "outy".into())),
            ],
        ),
        node(
            name,
            "combine2",
            "vector2",
            "ND_combine2_vector2",
            vec![
                input("in1", "float", Source::Output(split, "outx".into())),
                input("in2", "float", Source::Node(flipped)),
            ],
        ),
    ];
    Translated {
        nodes,
        outputs: vec![Source::Node(name.to_string())],
    }
}

/// An Image node reading `file` (beside the document; `colour_space` none for data):
/// `image` with the node's edge and filter, its colour, alpha and luminance (Rec. 709
/// weights, as Veneer's `value` output) split off.
pub fn image(
    name: &str,
    settings: &crate::nodes::bitmap::ImageFile,
    file: &str,
    colour_space: Option<&'static str>,
) -> Translated {
    use crate::nodes::passes::{EdgeMode, Filter};
    let part = |suffix: &str| format!("{name}_{suffix}");
    let address = match settings.edge {
        EdgeMode::Wrap => "periodic",
        EdgeMode::Clamp => "clamp",
        EdgeMode::Mirror => "mirror",
    };
    let filter = match settings.filter {
        Filter::Bilinear => "linear",
        Filter::Bicubic => "cubic",
    };
    let text = |value: &str| Source::Value(value.to_string());
    let texture = name.to_string();
    let read = Source::File {
        path: file.to_string(),
        colour_space,
    };
    let colour = part("colour");
    let [r, g, b] = crate::nodes::bitmap::LUMINANCE;
    let nodes = vec![
        node(
            &texture,
            "image",
            "color4",
            "ND_image_color4",
            vec![
                input("file", "filename", read),
                input("uaddressmode", "string", text(address)),
                input("vaddressmode", "string", text(address)),
                input("filtertype", "string", text(filter)),
            ],
        ),
        node(
            &colour,
            "convert",
            "color3",
            "ND_convert_color4_color3",
            vec![input("in", "color4", Source::Node(texture.clone()))],
        ),
        node(
            &part("alpha"),
            "extract",
            "float",
            "ND_extract_color4",
            vec![
                input("in", "color4", Source::Node(texture)),
                input("index", "integer", text("3")),
            ],
        ),
        node(
            &part("rgb"),
            "convert",
            "vector3",
            "ND_convert_color3_vector3",
            vec![input("in", "color3", Source::Node(colour.clone()))],
        ),
        node(
            &part("value"),
            "dotproduct",
            "float",
            "ND_dotproduct_vector3",
            vec![
                input("in1", "vector3", Source::Node(part("rgb"))),
                input("in2", "vector3", text(&format!("{r}, {g}, {b}"))),
            ],
        ),
    ];
    Translated {
        nodes,
        outputs: [colour, part("alpha"), part("value")]
            .map(Source::Node)
            .to_vec(),
    }
}

/// Every kind [`standard`] may translate, with every setting it reads (operations and
/// value types): the import inverts the translation over these. Made once.
pub fn kinds() -> &'static [NodeKind] {
    static KINDS: std::sync::OnceLock<Vec<NodeKind>> = std::sync::OnceLock::new();
    KINDS.get_or_init(translated_kinds)
}

fn translated_kinds() -> Vec<NodeKind> {
    const TYPES: [ValueType; 4] = [
        ValueType::Float,
        ValueType::Vec2,
        ValueType::Vec3,
        ValueType::Color,
    ];
    let mut kinds: Vec<NodeKind> = Vec::new();
    let mut add = |kind: NodeKind| {
        if standard(&kind, "kind", &vec![Source::Value("0".into()); 8]).is_some()
            && !kinds.contains(&kind)
        {
            kinds.push(kind);
        }
    };
    for example in NodeKind::examples() {
        for ty in TYPES {
            let mut kind = example.clone();
            match &mut kind {
                NodeKind::Math(math) => math.ty = ty,
                NodeKind::Unary(unary) => unary.ty = ty,
                NodeKind::Mix(mix) => mix.ty = ty,
                NodeKind::Clamp(clamp) => clamp.ty = ty,
                NodeKind::Step(step) => step.ty = ty,
                NodeKind::Length(length) => length.ty = ty,
                NodeKind::Dot(dot) => dot.ty = ty,
                NodeKind::Split(split) => split.ty = ty,
                NodeKind::Combine(combine) => combine.ty = ty,
                NodeKind::Constant(constant) => constant.ty = ty,
                _ => {}
            }
            match &kind {
                NodeKind::Math(_) => {
                    for op in MathOp::ALL {
                        let mut each = kind.clone();
                        if let NodeKind::Math(math) = &mut each {
                            math.op = op;
                        }
                        add(each);
                    }
                }
                NodeKind::Unary(_) => {
                    for op in UnaryOp::ALL {
                        let mut each = kind.clone();
                        if let NodeKind::Unary(unary) = &mut each {
                            unary.op = op;
                        }
                        add(each);
                    }
                }
                _ => add(kind),
            }
        }
    }
    kinds
}
