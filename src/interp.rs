//! Interpolation: screen-space weights from exact edge values, perspective correction, depth.

use glam::DVec3;

/// What a vertex carries to the fragments between it and its neighbours.
///
/// Window depth and screen barycentrics are linear in screen space; `1/w` and the barycentrics
/// in the input primitive are what makes interpolation perspective-correct. A vertex made by
/// clipping carries its own values, so interpolation never needs to know what clipping did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Varyings {
    /// Window depth (linear in screen space).
    pub depth: f64,
    /// `1/w`, the weight that makes interpolation perspective-correct.
    pub inv_w: f64,
    /// Barycentrics in the input primitive (linear in clip space, so perspective-correct).
    pub barycentric: DVec3,
    /// Screen-space barycentrics in the input triangle, when its vertices all have `w > 0`
    /// (behind-the-eye vertices have no screen position).
    pub screen: Option<DVec3>,
}

/// Barycentrics of a covered sample in the input triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Barycentrics {
    /// Perspective-correct barycentrics.
    pub perspective: DVec3,
    /// Screen-space barycentrics, when the input triangle's vertices all have `w > 0`.
    pub screen: Option<DVec3>,
}

/// Screen-space weights of a sample from its exact edge values (they sum to `area2`).
///
/// Each weight is one division of exact integers, so it is correctly rounded in f64 and the
/// three sum to 1 within 2 ulp; a weight is exactly 1 at its vertex and 0 on its opposite edge.
#[must_use]
#[inline]
pub fn screen_weights(values: [i64; 3], area2: i64) -> [f64; 3] {
    let area = area2 as f64;
    values.map(|v| v as f64 / area)
}

/// Window depth at a sample with exact edge values `values` over `corners`: `Σ sᵢ zᵢ` with
/// `sᵢ = valuesᵢ / area2`, linear in screen space (Vulkan, D3D).
///
/// Computed as `(Σ valuesᵢ zᵢ) / area2`: the values convert to f64 exactly (below 2^53), so
/// the result is within a few f64 ulps of the exact value, far below f32 resolution.
#[must_use]
#[inline]
pub fn interpolate_depth(corners: [&Varyings; 3], values: [i64; 3], area2: i64) -> f64 {
    let [a, b, c] = values.map(|v| v as f64);
    (corners[0].depth * a + corners[1].depth * b + corners[2].depth * c) / area2 as f64
}

/// Barycentrics in the input primitive at a point with screen weights `s` over `corners` (the
/// three corners of a triangle, or the two ends of a line segment).
///
/// Perspective-correct weights are `(sᵢ/wᵢ) / Σ sⱼ/wⱼ`; they map the corners' own barycentrics
/// back to the input primitive. Screen-space barycentrics are linear on screen, so they are the
/// screen weights of the corners' own; at the input triangle's vertices that is `s` itself.
#[must_use]
#[inline]
pub fn interpolate<const N: usize>(corners: [&Varyings; N], s: [f64; N]) -> Barycentrics {
    let q: [f64; N] = std::array::from_fn(|i| s[i] * corners[i].inv_w);
    let q_sum: f64 = q.iter().sum();
    let perspective: DVec3 = corners
        .iter()
        .zip(q)
        .map(|(c, qi)| c.barycentric * (qi / q_sum))
        .sum();
    // `Option`'s `sum` (`None` if a corner has none, else `0 + t₀ + t₁ + …`), written out: the
    // iterator form stopped being inlined into fast's per-sample loop.
    let mut screen = Some(DVec3::ZERO);
    for (c, si) in corners.iter().zip(s) {
        screen = screen.zip(c.screen).map(|(sum, b)| sum + b * si);
    }
    Barycentrics { perspective, screen }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An input vertex: its screen barycentrics are its own unit vector.
    fn vertex(depth: f64, w: f64, barycentric: DVec3) -> Varyings {
        Varyings {
            depth,
            inv_w: 1.0 / w,
            barycentric,
            screen: Some(barycentric),
        }
    }

    #[test]
    fn equal_w_makes_perspective_equal_to_screen_space() {
        let a = vertex(0.1, 2.0, DVec3::X);
        let b = vertex(0.5, 2.0, DVec3::Y);
        let c = vertex(0.9, 2.0, DVec3::Z);
        let s = [0.25, 0.25, 0.5];
        let out = interpolate([&a, &b, &c], s);
        approx::assert_relative_eq!(out.perspective, DVec3::from(s), epsilon = 1e-15);
        approx::assert_relative_eq!(out.screen.unwrap(), DVec3::from(s), epsilon = 1e-15);
        let depth = interpolate_depth([&a, &b, &c], [1, 1, 2], 4);
        approx::assert_relative_eq!(depth, 0.025 + 0.125 + 0.45, epsilon = 1e-15);
    }

    #[test]
    fn perspective_weights_favour_the_near_vertex() {
        // Midway on screen between a vertex at w = 1 and one at w = 3: 3/4 of the way in 3D is
        // the near one, b = (1/1)/(1/1 + 1/3) = 0.75.
        let a = vertex(0.0, 1.0, DVec3::X);
        let b = vertex(0.0, 3.0, DVec3::Y);
        let c = vertex(0.0, 3.0, DVec3::Z);
        let out = interpolate([&a, &b, &c], [0.5, 0.5, 0.0]);
        approx::assert_relative_eq!(out.perspective.x, 0.75, epsilon = 1e-15);
        approx::assert_relative_eq!(out.screen.unwrap().x, 0.5, epsilon = 1e-15);
    }
}
