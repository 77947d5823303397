//! White noise (seed 003 §3.2): an independent PCG value per unit lattice cell, with no
//! interpolation between cells.

// White noise in [0, 1): the PCG hash of the cell floor(p), constant over each unit cell.
fn veneer_white_noise(p: vec3f) -> f32 {
    return veneer_lattice_pcg(floor(veneer_lattice_domain(p)));
}

// White noise as a colour in [0, 1) per channel: the three PCG lanes of the cell floor(p)
// (its red channel is the scalar white noise of the same cell).
fn veneer_white_noise_color(p: vec3f) -> vec3f {
    return veneer_unit_floats(veneer_pcg3d(veneer_cell_bits(floor(veneer_lattice_domain(p)))));
}
