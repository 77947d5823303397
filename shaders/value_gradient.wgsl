//! Value-gradient noise (seed 003 §3.2; Ebert et al., Texturing and Modeling, ch. 2): a
//! weighted sum of value noise and gradient noise, which hides the grid of each.

// Value-gradient noise in [0, 1]: the mean of PCG value noise and gradient noise (each in
// [0, 1]). Both hash the same lattice with PCG3D but read disjoint bits of it (the value
// the top 24 bits of the first lane, the gradient its low 4 bits), so they are independent.
fn veneer_noise_value_gradient(p: vec3f) -> f32 {
    return 0.5 * (veneer_noise_value_pcg(p) + veneer_noise_gradient(p));
}
