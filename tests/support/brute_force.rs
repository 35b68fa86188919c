//! The brute-force oracle: every pixel of the viewport, `orient2d` in i128, explicit top-left bias.
//!
//! It shares no code with the reference: edges are classified by D3D11's geometric wording
//! (a top edge is horizontal with the third vertex below it; a left edge has the third vertex to
//! its right) rather than by edge direction, and nothing is reordered or stepped.

/// A point in subpixel units.
pub type P = (i128, i128);

/// Twice the signed area of `a, b, c`.
pub fn orient2d(a: P, b: P, c: P) -> i128 {
    (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
}

/// Whether edge `p q` of the triangle with third vertex `r` is a top or a left edge (D3D11 §3.4).
pub fn is_top_or_left(p: P, q: P, r: P) -> bool {
    if p.1 == q.1 {
        // Horizontal: a top edge when the triangle lies below it (y grows downwards).
        r.1 > p.1
    } else {
        // Left when r lies right of the line at r's height:
        // r.x > p.x + (r.y − p.y)(q.x − p.x)/(q.y − p.y), multiplied through by q.y − p.y.
        let dy = q.1 - p.1;
        let side = (r.0 - p.0) * dy - (r.1 - p.1) * (q.0 - p.0);
        side * dy.signum() > 0
    }
}

/// Whether the sample `s` is covered by triangle `t` under the top-left rule.
pub fn covers(t: [P; 3], s: P) -> bool {
    if orient2d(t[0], t[1], t[2]) == 0 {
        return false;
    }
    (0..3).all(|i| {
        let (p, q, r) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
        // Make "inside" positive whatever the winding.
        let e = orient2d(p, q, s) * orient2d(p, q, r).signum();
        e > 0 || (e == 0 && is_top_or_left(p, q, r))
    })
}

/// Every covered pixel of a `width × height` viewport, row by row, with samples at pixel centres.
pub fn coverage(t: [P; 3], width: u32, height: u32, bits: u8) -> Vec<(u32, u32)> {
    let one = 1i128 << bits;
    let mut out = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let s = (i128::from(x) * one + one / 2, i128::from(y) * one + one / 2);
            if covers(t, s) {
                out.push((x, y));
            }
        }
    }
    out
}

#[test]
fn oracle_sanity() {
    // A 2×2-pixel square split on its diagonal: each sample belongs to exactly one half.
    let s = 256;
    let (a, b, c, d) = ((0, 0), (2 * s, 0), (2 * s, 2 * s), (0, 2 * s));
    let first = coverage([a, b, c], 2, 2, 8);
    let second = coverage([a, c, d], 2, 2, 8);
    assert_eq!(first.len() + second.len(), 4);
    assert!(first.iter().all(|p| !second.contains(p)));
}
