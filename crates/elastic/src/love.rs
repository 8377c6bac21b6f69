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

/// Normal surface displacement [m] at `(x, y)` [m] of an elastic half-space of composite
/// modulus `e_star` [Pa] under the uniform pressure `p` [Pa] on the rectangle `|x'| <= a`,
/// `|y'| <= b` (half-sides `a`, `b` [m]), Love's solution (method.md section 1):
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
