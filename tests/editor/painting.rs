//! The window paints each pixel about once. On a software rasteriser the window's cost
//! is the area its triangles cover; egui's default frames covered the wood preset's
//! window 2.7 times over (the graph's area filled by the panel and again by the canvas,
//! every node by its shadow, its frame and its header).

use crate::support::{editor, scratch, settle_previews};
use egui::epaint::{ClippedPrimitive, Primitive};
use egui::{Pos2, Rect, pos2};

/// The part of the triangle `corners` inside `clip` (Sutherland–Hodgman), as a polygon.
fn clipped(corners: [Pos2; 3], clip: Rect) -> Vec<Pos2> {
    let mut polygon = corners.to_vec();
    // Each side's signed distance, positive inside.
    let sides: [fn(Pos2, Rect) -> f32; 4] = [
        |p, r| p.x - r.min.x,
        |p, r| r.max.x - p.x,
        |p, r| p.y - r.min.y,
        |p, r| r.max.y - p.y,
    ];
    for inside in sides {
        let mut kept = Vec::with_capacity(polygon.len() + 2);
        for (index, &point) in polygon.iter().enumerate() {
            let next = polygon[(index + 1) % polygon.len()];
            let (here, there) = (inside(point, clip), inside(next, clip));
            if here >= 0.0 {
                kept.push(point);
            }
            if (here >= 0.0) != (there >= 0.0) {
                kept.push(point + (next - point) * (here / (here - there)));
            }
        }
        polygon = kept;
        if polygon.is_empty() {
            break;
        }
    }
    polygon
}

fn polygon_area(polygon: &[Pos2]) -> f32 {
    let twice: f32 = (0..polygon.len())
        .map(|index| {
            let (a, b) = (polygon[index], polygon[(index + 1) % polygon.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum();
    twice.abs() / 2.0
}

/// The area, in pixels, that `primitives` cover inside their clip rectangles, counting
/// each layer over another again.
fn covered(primitives: &[ClippedPrimitive]) -> f32 {
    primitives
        .iter()
        .filter_map(|primitive| match &primitive.primitive {
            Primitive::Mesh(mesh) => Some((mesh, primitive.clip_rect)),
            Primitive::Callback(_) => None,
        })
        .map(|(mesh, clip)| {
            mesh.indices
                .chunks_exact(3)
                .map(|triangle| {
                    let corner = |index: u32| mesh.vertices[index as usize].pos;
                    let corners = [
                        corner(triangle[0]),
                        corner(triangle[1]),
                        corner(triangle[2]),
                    ];
                    polygon_area(&clipped(corners, clip))
                })
                .sum::<f32>()
        })
        .sum()
}

#[test]
fn clipping_keeps_what_is_inside() {
    let clip = Rect::from_min_max(pos2(0.0, 0.0), pos2(10.0, 10.0));
    let inside = [pos2(1.0, 1.0), pos2(5.0, 1.0), pos2(1.0, 5.0)];
    assert_eq!(polygon_area(&clipped(inside, clip)), 8.0);
    // Half of this right triangle's legs stick out to the right and below.
    let across = [pos2(0.0, 0.0), pos2(20.0, 0.0), pos2(0.0, 20.0)];
    assert_eq!(polygon_area(&clipped(across, clip)), 100.0);
    let outside = [pos2(11.0, 0.0), pos2(15.0, 0.0), pos2(11.0, 5.0)];
    assert_eq!(polygon_area(&clipped(outside, clip)), 0.0);
}

#[test]
fn the_wood_preset_window_is_painted_about_once_over() {
    let mut harness = editor(&scratch("painting"), None);
    settle_previews(&mut harness);
    harness.run();
    let output = harness.output();
    let primitives = harness
        .ctx
        .tessellate(output.shapes.clone(), output.pixels_per_point);
    let window = harness.ctx.content_rect().area();
    let screens = covered(&primitives) / window;
    // Every pixel once (the clear colour is the canvas), the nodes, the side panel and
    // the preview over it, text and wires: 1.03 screens when this was written.
    assert!(
        screens < 1.3,
        "the window's shapes cover it {screens:.2} times over"
    );
}
