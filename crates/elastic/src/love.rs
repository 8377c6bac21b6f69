//! Love's (1929) solution: surface displacement under uniform pressure on a rectangle.

use std::f64::consts::PI;

/// `x ln(y + r) ` with the conventions that make Love's sum continuous: the term vanishes with
/// `x`, and `ln(y + r)` for `y <= 0` is evaluated as `ln(x^2 / (r - y))` (the same number,
/// without cancellation).
fn term(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let r = x.hypot(y);
    let log = if y > 0.0 {
        (y + r).ln()
    } else {
        (x * x / (r - y)).ln()
    };
    x * log
}

/// `F(x, y) = x asinh(y/x) + y asinh(x/y)` up to terms that cancel in the sum below, written
/// with logarithms as `x ln(y + r) + y ln(x + r)`.
fn corner(x: f64, y: f64) -> f64 {
    term(x, y) + term(y, x)
}

/// Normal surface displacement \[m\] at `(x, y)` \[m\] of an elastic half-space of composite
/// modulus `e_star` \[Pa\] under the uniform pressure `p` \[Pa\] on the rectangle `|x'| <= a`,
/// `|y'| <= b` (half-sides `a`, `b` \[m\]), Love's solution (docs/method.md section 1):
/// `u = p / (pi E*) [F(x+a, y+b) - F(x+a, y-b) - F(x-a, y+b) + F(x-a, y-b)]`
/// with `F(s, t) = s ln(t + r) + t ln(s + r)`, `r = sqrt(s^2 + t^2)`.
///
/// ```
/// // Centre of a square of side 2a: u = 8 ln(1 + sqrt 2) p a / (pi E*) ~ 2.2444 p a / E*.
/// let u = elastic::love::rectangle_displacement(0.0, 0.0, 1.0, 1.0, 1.0, 1.0);
/// assert!((u - 8.0 * (1.0 + 2f64.sqrt()).ln() / std::f64::consts::PI).abs() < 1e-14);
/// ```
pub fn rectangle_displacement(x: f64, y: f64, a: f64, b: f64, p: f64, e_star: f64) -> f64 {
    p / (PI * e_star)
        * (corner(x + a, y + b) - corner(x + a, y - b) - corner(x - a, y + b) + corner(x - a, y - b))
}

/// Distance, in half-sides of the rectangle, beyond which [`cell_influence`] uses the
/// multipole expansion: there its truncation error (~(a/r)^6) and the rounding error of the
/// closed form (which subtracts terms ~ r ln r to get ~ a b / r) are both about 2e-12
/// (measured against quadrature; the closed form's error keeps growing with distance).
const FAR: f64 = 64.0;

/// Displacement \[m\] at `(x, y)` \[m\] under unit pressure (1 Pa) on the rectangle of half-sides
/// `a`, `b` \[m\] centred at the origin: [`rectangle_displacement`] near the rectangle, and its
/// multipole expansion far from it, which is faster and more accurate there:
/// `u = 4ab/(pi E*) [1/r + (a^2 d_xx + b^2 d_yy)(1/r)/6
///      + (a^4/5 d_xxxx + 6 a^2 b^2/9 d_xxyy + b^4/5 d_yyyy)(1/r)/24 + O((a/r)^6 / r)]`.
pub fn cell_influence(x: f64, y: f64, a: f64, b: f64, e_star: f64) -> f64 {
    if x * x + y * y < (FAR * a.max(b)).powi(2) {
        rectangle_displacement(x, y, a, b, 1.0, e_star)
    } else {
        rectangle_multipole(x, y, a, b, e_star)
    }
}

/// The multipole expansion of [`cell_influence`] (unit pressure), valid far from the
/// rectangle (relative error ~ (max(a, b)/r)^6).
pub fn rectangle_multipole(x: f64, y: f64, a: f64, b: f64, e_star: f64) -> f64 {
    let r2 = x * x + y * y;
    let r = r2.sqrt();
    let inv_r = 1.0 / r;
    let (x2, y2) = (x * x, y * y);
    let inv_r5 = inv_r / (r2 * r2);
    let inv_r9 = inv_r5 / (r2 * r2);
    let dxx = (2.0 * x2 - y2) * inv_r5;
    let dyy = (2.0 * y2 - x2) * inv_r5;
    let dxxxx = 3.0 * (8.0 * x2 * x2 - 24.0 * x2 * y2 + 3.0 * y2 * y2) * inv_r9;
    let dxxyy = -3.0 * (4.0 * x2 * x2 - 27.0 * x2 * y2 + 4.0 * y2 * y2) * inv_r9;
    let dyyyy = 3.0 * (3.0 * x2 * x2 - 24.0 * x2 * y2 + 8.0 * y2 * y2) * inv_r9;
    let (a2, b2) = (a * a, b * b);
    let second = (a2 * dxx + b2 * dyy) / 6.0;
    let fourth = (a2 * a2 / 5.0 * dxxxx + 6.0 * a2 * b2 / 9.0 * dxxyy + b2 * b2 / 5.0 * dyyyy) / 24.0;
    4.0 * a * b / (PI * e_star) * (inv_r + second + fourth)
}
