//! A graph's albedo over a square of texture space, as a fit sees it: evaluated on the
//! CPU in f32 (as the GPU renders it) at each pixel's centre (the flat render's points), and the derivative of
//! a function of those pixels by the fitted coordinates, each pixel's material recorded
//! on the tape and its share of the derivative passed back.

use super::space::Space;
use super::tape::{Recording, Var};
use crate::eval::Evaluator;
use crate::render::FlatRect;
use rayon::prelude::*;

/// An image of `size`×`size` RGB pixels, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub size: u32,
    pub pixels: Vec<[f64; 3]>,
}

impl Image {
    /// The image as a photo a fit reads (for fitting one render to another).
    pub fn to_photo(&self) -> image::Rgb32FImage {
        let lanes = self.pixels.iter().flat_map(|p| p.map(|v| v as f32));
        image::Rgb32FImage::from_raw(self.size, self.size, lanes.collect()).expect("a square")
    }
}

/// Pixels per task handed to a thread.
const CHUNK: usize = 256;

/// Where a fit renders: the square, its size in pixels, the evaluator.
pub struct Canvas<'e> {
    pub evaluator: &'e Evaluator,
    pub rect: FlatRect,
    pub size: u32,
}

impl Canvas<'_> {
    /// The texture-space points of the pixels' centres.
    fn points(&self) -> Vec<[f64; 3]> {
        let n = self.size;
        (0..n * n)
            .map(|k| self.rect.sample_position(k % n, k / n, n))
            .collect()
    }

    /// The albedo with the fitted coordinates at `places`.
    pub fn render(&self, space: &Space, places: &[f64]) -> Image {
        let places: Vec<f32> = places.iter().map(|&t| t as f32).collect();
        let values = space.values(&places);
        let pixels = (self.points().par_iter())
            .map(|&point| {
                let surface = self.evaluator.flat_surface::<f32>(point);
                let albedo = self.evaluator.eval_with(&surface, &values).albedo;
                albedo.map(f64::from)
            })
            .collect();
        Image {
            size: self.size,
            pixels,
        }
    }

    /// The derivative, by each fitted coordinate, of `Σ weights[i] · albedo[i]` over the
    /// pixels (the weights a loss's derivative by each pixel gives), at `places`.
    pub fn pull_back(&self, space: &Space, places: &[f64], weights: &[[f64; 3]]) -> Vec<f64> {
        let points = self.points();
        let partials: Vec<Vec<f64>> = (points.par_chunks(CHUNK).zip(weights.par_chunks(CHUNK)))
            .map(|(points, weights)| {
                let mut sum = vec![0.0; places.len()];
                for (&point, weight) in points.iter().zip(weights) {
                    if weight.iter().all(|&w| w == 0.0) {
                        continue;
                    }
                    let mut recording = Recording::start();
                    let leaves: Vec<Var> = places.iter().map(|&t| recording.leaf(t)).collect();
                    let values = space.values(&leaves);
                    let surface = self.evaluator.flat_surface::<Var>(point);
                    let albedo = self.evaluator.eval_with(&surface, &values).albedo;
                    let seeds = [0, 1, 2].map(|c| (albedo[c], weight[c]));
                    for (total, part) in sum.iter_mut().zip(recording.gradient(&seeds)) {
                        *total += part;
                    }
                }
                sum
            })
            .collect();
        // Summed in chunk order, so the result does not depend on the threads.
        let mut gradient = vec![0.0; places.len()];
        for partial in partials {
            for (total, part) in gradient.iter_mut().zip(partial) {
                *total += part;
            }
        }
        gradient
    }
}
