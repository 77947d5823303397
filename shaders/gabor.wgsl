//! Gabor noise (Lagae et al. 2009, "Procedural noise using sparse Gabor convolution"; as
//! Blender 4.x's Gabor texture, in 3D): a sum of Gabor kernels at eight PCG-placed
//! impulses per unit cell, each with a random sign. Anisotropic: every kernel's plane wave
//! runs along one orientation, or along random ones, or in between.

// The Gabor kernel at offset `x` (|x| < 1) from its impulse: a unit-width Gaussian
// exp(-pi |x|^2) times a Hann window 0.5 + 0.5 cos(pi |x|^2) (which takes it smoothly to 0
// at radius 1, where the impulse's support ends), times the sine (zero mean, as Blender
// uses) of a plane wave of `frequency` cycles per unit along the unit vector `direction`.
// The phase is reduced to half a turn either side of 0 before the sine, so any finite
// frequency gives a finite, accurately computed value.
fn veneer_gabor_kernel(x: vec3f, frequency: f32, direction: vec3f) -> f32 {
    let r2 = dot(x, x);
    let envelope = exp(-3.14159265 * r2) * (0.5 + 0.5 * cos(3.14159265 * r2));
    let phase = fract(frequency * dot(x, direction) + 0.5) - 0.5;
    return envelope * sin(6.28318531 * phase);
}

// The plane-wave direction of one impulse from two uniform numbers `u`: a random unit
// vector (uniform on the sphere: z = 2 u.x - 1, longitude 2 pi (u.y - 0.5)), turned into
// the hemisphere of `dir` (a mirrored kernel only changes sign, and signs are random
// anyway), then blended towards the unit vector `dir` by `anisotropy` in [0, 1] and
// normalised; the random vector alone where `dir` is zero (isotropic noise). The blend
// never shortens below 1 / sqrt(2), so normalising is safe.
fn veneer_gabor_direction(dir: vec3f, anisotropy: f32, u: vec2f) -> vec3f {
    let z = 2.0 * u.x - 1.0;
    let longitude = 6.28318531 * (u.y - 0.5);
    let s = sqrt(max(1.0 - z * z, 0.0));
    let random = vec3f(s * cos(longitude), s * sin(longitude), z);
    let turned = select(random, -random, dot(random, dir) < 0.0);
    let a = clamp(anisotropy, 0.0, 1.0);
    let blended = turned * (1.0 - a) + dir * a;
    return normalize(select(blended, random, all(dir == vec3f(0.0))));
}

// The kernels of the eight impulses of lattice cell `cell` at `x`, the point's offset from
// the cell's lowest corner. Impulse i: h = PCG3D(PCG3D(cell bits) + i); its centre is
// unit_floats(h) within the cell; u = unit_floats(PCG3D(h)) gives its direction (u.xy)
// and its sign (+ where u.z < 0.5).
fn veneer_gabor_cell(cell: vec3f, x: vec3f, frequency: f32, anisotropy: f32, dir: vec3f) -> f32 {
    let base = veneer_pcg3d(veneer_cell_bits(cell));
    var sum = 0.0;
    for (var i = 0u; i < 8u; i++) {
        let h = veneer_pcg3d(base + vec3u(i));
        let offset = x - veneer_unit_floats(h);
        if dot(offset, offset) < 1.0 {
            let u = veneer_unit_floats(veneer_pcg3d(h));
            let k = veneer_gabor_kernel(offset, frequency, veneer_gabor_direction(dir, anisotropy, u.xy));
            sum += select(-k, k, u.z < 0.5);
        }
    }
    return sum;
}

// The sum of the kernels of the impulses of the 27 cells around p (only those reach p),
// with `dir` the unit orientation or zero (see the Gabor noise below): zero mean, standard
// deviation about 1.0146 (1 / 0.3285345) for frequencies of a cycle per unit and more.
fn veneer_gabor_sum(point: vec3f, frequency: f32, anisotropy: f32, dir: vec3f) -> f32 {
    let p = veneer_lattice_domain(point);
    let cell = floor(p);
    let f = p - cell;
    var sum = 0.0;
    for (var z = -1; z <= 1; z++) {
        for (var y = -1; y <= 1; y++) {
            for (var x = -1; x <= 1; x++) {
                let o = vec3f(f32(x), f32(y), f32(z));
                sum += veneer_gabor_cell(cell + o, f - o, frequency, anisotropy, dir);
            }
        }
    }
    return sum;
}

// Gabor noise in [0, 1] with `frequency` cycles per unit (kernels reach one unit from
// their impulse), `anisotropy` in [0, 1] (0: every kernel turned at random, isotropic;
// 1: every kernel along `orientation`) and `orientation` (any length; the zero vector
// means isotropic whatever the anisotropy). The kernel sum n is mapped to
// 0.5 + 0.5 clamp(n / (3 sigma), -1, 1), where sigma = 1.01461 is the standard deviation
// of n for frequencies of a cycle per unit and more (impulses of independent random sign,
// so sigma^2 = 8 impulses per cell times the integral of the squared kernel, 0.5 *
// 0.257357, the squared sine averaging 1/2); 1 / (3 sigma) = 0.3285345, so about 0.3% of
// points clip. Lower frequencies give less contrast (none at frequency 0).
fn veneer_gabor(p: vec3f, frequency: f32, anisotropy: f32, orientation: vec3f) -> f32 {
    let n = veneer_gabor_sum(p, frequency, anisotropy, veneer_safe_normalize_vec3f(orientation));
    return 0.5 + 0.5 * clamp(n * 0.3285345, -1.0, 1.0);
}
