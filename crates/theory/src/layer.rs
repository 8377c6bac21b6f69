//! A rigid sphere of radius `r` \[m\] on an elastic layer of thickness `h` \[m\] on a rigid
//! base, the layer of plane-strain modulus `e_star = E / (1 - nu^2)` \[Pa\] and Poisson's ratio
//! `nu`: the corrections of Hertz that users apply by hand.

use std::f64::consts::PI;

/// How the layer meets its rigid base.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// Bonded (no slip).
    Bonded,
    /// Free to slide (frictionless).
    Frictionless,
}

/// Dimitriadis et al. (Biophys. J. 82, 2002) load \[N\] at approach `delta` \[m\]: Hertz's load
/// times a polynomial in `chi = sqrt(R delta) / h`,
/// `1 - (2 a0/pi) chi + (4 a0^2/pi^2) chi^2 - (8/pi^3)(a0^3 + 4 pi^2 b0/15) chi^3
/// + (16 a0/pi^4)(a0^3 + 3 pi^2 b0/5) chi^4`, with, bonded,
/// `a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu)`,
/// `b0 = (0.6387 - 1.0277 nu + 1.5164 nu^2)/(1 - nu)`, and sliding
/// `a0 = -0.347 (3 - 2 nu)/(1 - nu)`, `b0 = 0.056 (5 - 2 nu)/(1 - nu)`. A fit for
/// `chi <~ 0.5`-1; at `nu = 0.5` bonded the `chi^4` coefficient is -0.0974 (often quoted +).
pub fn dimitriadis_load(delta: f64, r: f64, h: f64, e_star: f64, nu: f64, base: Base) -> f64 {
    let chi = (r * delta.max(0.0)).sqrt() / h;
    let (a0, b0) = dimitriadis_coefficients(nu, base);
    let poly = 1.0 - 2.0 * a0 / PI * chi + 4.0 * a0 * a0 / (PI * PI) * chi * chi
        - 8.0 / PI.powi(3) * (a0.powi(3) + 4.0 * PI * PI * b0 / 15.0) * chi.powi(3)
        + 16.0 * a0 / PI.powi(4) * (a0.powi(3) + 3.0 * PI * PI * b0 / 5.0) * chi.powi(4);
    crate::hertz::load_of_approach(delta, r, e_star) * poly
}

/// Dimitriadis' `(alpha0, beta0)` for Poisson's ratio `nu` on `base`.
pub fn dimitriadis_coefficients(nu: f64, base: Base) -> (f64, f64) {
    match base {
        Base::Bonded => (
            -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu),
            (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu),
        ),
        Base::Frictionless => (
            -0.347 * (3.0 - 2.0 * nu) / (1.0 - nu),
            0.056 * (5.0 - 2.0 * nu) / (1.0 - nu),
        ),
    }
}

/// The P-wave (confined) modulus \[Pa\] of the layer, `M = E (1 - nu) / ((1 + nu)(1 - 2 nu))
/// = E* (1 - nu)^2 / (1 - 2 nu)`: infinite when incompressible.
pub fn p_wave_modulus(e_star: f64, nu: f64) -> f64 {
    e_star * (1.0 - nu).powi(2) / (1.0 - 2.0 * nu)
}

/// The thin compressible bonded layer's load \[N\] at approach `delta` \[m\] (the Winkler
/// limit, contact radius much larger than `h`): each point sinks as a spring of stiffness
/// `M / h`, so `a^2 = 2 R delta` and `P = pi M R delta^2 / h`.
pub fn winkler_load(delta: f64, r: f64, h: f64, e_star: f64, nu: f64) -> f64 {
    PI * p_wave_modulus(e_star, nu) * r * delta.max(0.0).powi(2) / h
}

/// The Winkler limit's contact radius \[m\] at approach `delta` \[m\]: `sqrt(2 R delta)`.
pub fn winkler_radius(delta: f64, r: f64) -> f64 {
    (2.0 * r * delta.max(0.0)).sqrt()
}

/// A rigid sphere in frictionless contact with a body whose surface compliance is the
/// half-space's (plane-strain modulus `e_star` \[Pa\]) times `ratio(q h)`, `h` \[m\] the layer's
/// thickness: Hertz's and JKR's problems on a layer solved exactly, to quadrature, where the
/// functions above are fits and limits.
///
/// The pressure inside the contact radius `a` is written through a function `g` on `[0, a]`
/// (Sneddon's representation: load `2 int_0^a g`, edge stress-intensity factor
/// `g(a) / sqrt(pi a)`), which obeys Lebedev and Ufliand's (1958) Fredholm equation
/// `g(t) + int_0^a K(t, s) g(s) ds = E* (delta - t^2 / R)` with
/// `K(t, s) = (1/pi) int_0^oo (ratio(q h) - 1) (cos q(t - s) + cos q(t + s)) dq`.
/// Hertz's edge has `g(a) = 0`; Griffith's balance with work of adhesion `w` gives
/// `g(a) = -sqrt(2 pi a E* w)` (JKR on the layer, the balance Shull's (2002) thin-layer
/// corrections fit). `ratio = 1` is the half-space, Hertz and JKR exactly. Contact radii up to
/// [`REACH`] thicknesses are evaluated.
pub struct LayerContact<F> {
    h: f64,
    e_star: f64,
    ratio: F,
}

/// The contact of a [`LayerContact`] at one contact radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereContact {
    /// Contact radius `a` \[m\].
    pub radius: f64,
    /// Approach of the sphere's apex into the undeformed surface \[m\].
    pub approach: f64,
    /// Load \[N\], compressive positive.
    pub load: f64,
}

/// The widest contact [`LayerContact`] evaluates, in layer thicknesses: its Gauss points (24 +
/// 4 a/h, at most 200) resolve the layer's edge there (the load moves by 4e-10 when they are
/// quadrupled; at 100 thicknesses by 3e-3). Wider contacts are the thin-layer limits' (Winkler's
/// bed within 0.4 % at 50 thicknesses, nu = 0.45 bonded); there its results are not numbers.
pub const REACH: f64 = 50.0;

/// `ratio(q h) - 1` is below 1e-15 beyond this many `q h` on the layers of `elastic`.
const KERNEL_CUT: f64 = 40.0;

impl<F: Fn(f64) -> f64> LayerContact<F> {
    /// The body: layer thickness `h` \[m\], the surface material's `e_star` \[Pa\], and its
    /// compliance over the half-space's as a function of `q h` (1 as `q h -> oo`).
    pub fn new(h: f64, e_star: f64, ratio: F) -> Self {
        LayerContact { h, e_star, ratio }
    }

    /// The sphere of radius `r` \[m\] at contact radius `a` \[m\] with work of adhesion `w`
    /// [J/m^2] (0: Hertz on the layer).
    pub fn sphere(&self, a: f64, r: f64, w: f64) -> SphereContact {
        if a > REACH * self.h {
            return SphereContact {
                radius: a,
                approach: f64::NAN,
                load: f64::NAN,
            };
        }
        let (punch, cap) = self.edge_and_load(a, r);
        // g = delta g_punch + g_cap; the edge condition fixes delta.
        let edge = -(2.0 * PI * a * self.e_star * w).sqrt();
        let approach = (edge - cap.0) / punch.0;
        SphereContact {
            radius: a,
            approach,
            load: approach * punch.1 + cap.1,
        }
    }

    /// The flat punch's stiffness \[N/m\] at radius `a` \[m\] (the half-space's `2 E* a`; not
    /// a number beyond [`REACH`]).
    pub fn punch_stiffness(&self, a: f64) -> f64 {
        if a > REACH * self.h {
            return f64::NAN;
        }
        self.edge_and_load(a, f64::INFINITY).0.1
    }

    /// Hertz on the layer at approach `delta` \[m\] of a sphere of radius `r` \[m\]: the contact
    /// radius where the edge pressure vanishes (Illinois' regula falsi to 1e-12 of it, from a
    /// bracket around the half-space's radius; not a number where none brackets it).
    pub fn hertz(&self, delta: f64, r: f64) -> SphereContact {
        let miss = |a: f64| self.sphere(a, r, 0.0).approach / delta - 1.0;
        let a0 = (r * delta).sqrt();
        let (mut lo, mut hi) = (0.5 * a0, 2.0 * a0);
        let (mut f_lo, mut f_hi) = (miss(lo), miss(hi));
        // The bracket widens by halves and doubles, 20 of each at most (a million-fold).
        for _ in 0..20 {
            if f_lo <= 0.0 {
                break;
            }
            (hi, f_hi, lo) = (lo, f_lo, 0.5 * lo);
            f_lo = miss(lo);
        }
        for _ in 0..20 {
            if f_hi >= 0.0 {
                break;
            }
            (lo, f_lo, hi) = (hi, f_hi, 2.0 * hi);
            f_hi = miss(hi);
        }
        if !(f_lo <= 0.0 && f_hi >= 0.0) {
            return SphereContact {
                radius: f64::NAN,
                approach: delta,
                load: f64::NAN,
            };
        }
        let mut side = 0;
        for _ in 0..100 {
            let a = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            let f = miss(a);
            if f.abs() < 1e-12 || hi - lo < 1e-12 * a0 {
                break;
            }
            if f < 0.0 {
                (lo, f_lo) = (a, f);
                if side == -1 {
                    f_hi *= 0.5;
                }
                side = -1;
            } else {
                (hi, f_hi) = (a, f);
                if side == 1 {
                    f_lo *= 0.5;
                }
                side = 1;
            }
        }
        let a = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        self.sphere(a, r, 0.0)
    }

    /// JKR's pull-off on the layer: the most tensile load over the contact radius (a scan
    /// from a third to three times the half-space's radius at pull-off, widened if the least
    /// load sits at an end, then golden sections to 1e-5 of that radius); not a number where
    /// it lies beyond [`REACH`].
    pub fn pull_off(&self, r: f64, w: f64) -> SphereContact {
        let a_half = (9.0 * PI * w * r * r / (8.0 * self.e_star)).cbrt();
        let load = |a: f64| self.sphere(a, r, w).load;
        let mut scan: Vec<(f64, f64)> = (0..=12)
            .map(|k| a_half / 3.0 * 1.2f64.powi(k))
            .map(|a| (a, load(a)))
            .collect();
        let least = |scan: &[(f64, f64)]| {
            (0..scan.len())
                .min_by(|&i, &j| scan[i].1.total_cmp(&scan[j].1))
                .expect("a non-empty scan")
        };
        let mut k = least(&scan);
        while k == 0 && scan[0].0 > 1e-6 * a_half {
            let a = scan[0].0 / 1.2;
            scan.insert(0, (a, load(a)));
            k = least(&scan);
        }
        while k == scan.len() - 1 && scan[k].0 < 1e3 * a_half {
            let a = scan[k].0 * 1.2;
            scan.push((a, load(a)));
            k = least(&scan);
        }
        // The least load at the widest contact evaluated: the pull-off lies beyond REACH.
        if scan.get(k + 1).is_none_or(|&(_, p)| p.is_nan()) {
            return SphereContact {
                radius: f64::NAN,
                approach: f64::NAN,
                load: f64::NAN,
            };
        }
        let (mut lo, mut hi) = (scan[k.max(1) - 1].0, scan[k + 1].0);
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        let (mut x1, mut x2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
        let (mut f1, mut f2) = (load(x1), load(x2));
        while hi - lo > 1e-5 * a_half {
            if f1 < f2 {
                (hi, x2, f2) = (x2, x1, f1);
                x1 = hi - golden * (hi - lo);
                f1 = load(x1);
            } else {
                (lo, x1, f1) = (x1, x2, f2);
                x2 = lo + golden * (hi - lo);
                f2 = load(x2);
            }
        }
        self.sphere(0.5 * (lo + hi), r, w)
    }

    /// `(g(a), load)` of the flat punch at unit approach and of the cap `-t^2 / r` alone.
    fn edge_and_load(&self, a: f64, r: f64) -> ((f64, f64), (f64, f64)) {
        // The layer's boundary layer at the edge is h wide: more nodes on thin layers (the
        // load moves by 1e-13 when the nodes and the panels are doubled, a = 0.2-20 h; the
        // cap: REACH).
        let n = (24 + 4 * (a / self.h).ceil() as usize).min(200);
        let (t, wt) = gauss_legendre(n, 0.0, a);
        // K(t, s) = (2/pi) int (ratio - 1) cos(q t) cos(q s) dq = sum_k d_k c_k(t) c_k(s):
        // a cosine a node and a point (the last point the edge), not one a pair.
        let (q, d) = self.quadrature(2.0 * a);
        let cosines: Vec<Vec<f64>> = t
            .iter()
            .chain([&a])
            .map(|&ti| q.iter().map(|&qk| (qk * ti).cos()).collect())
            .collect();
        let weighted: Vec<Vec<f64>> = cosines
            .iter()
            .map(|row| row.iter().zip(&d).map(|(c, d)| c * d).collect())
            .collect();
        let kernel =
            |i: usize, j: usize| -> f64 { weighted[i].iter().zip(&cosines[j]).map(|(x, y)| x * y).sum() };
        let mut m = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in i..n {
                // K is symmetric; the weights are not.
                let k = kernel(i, j);
                m[i][j] = k * wt[j];
                m[j][i] = k * wt[i];
            }
            m[i][i] += 1.0;
        }
        let punch = solve(m.clone(), vec![self.e_star; n]);
        let cap_rhs = t.iter().map(|&ti| -self.e_star * ti * ti / r).collect();
        let cap = solve(m, cap_rhs);
        // Nystrom's interpolation at the edge, and the load 2 int g.
        let edge = |g: &[f64], f: f64| f - (0..n).map(|j| kernel(n, j) * wt[j] * g[j]).sum::<f64>();
        let load = |g: &[f64]| 2.0 * (0..n).map(|j| wt[j] * g[j]).sum::<f64>();
        (
            (edge(&punch, self.e_star), load(&punch)),
            (edge(&cap, -self.e_star * a * a / r), load(&cap)),
        )
    }

    /// Nodes `q` \[1/m\] and weights `2 (ratio(q h) - 1) / pi` of `int_0^oo dq` for
    /// `cos(q t) cos(q s)`, `t + s <= reach` \[m\]: composite Gauss-Legendre in `x = q h` over
    /// panels at most half a period of `cos(x reach / h)` wide.
    fn quadrature(&self, reach: f64) -> (Vec<f64>, Vec<f64>) {
        let width = (PI * self.h / reach).min(0.5);
        let panels = (KERNEL_CUT / width).ceil() as usize;
        let (x, wx) = gauss_legendre(8, 0.0, width);
        (0..panels)
            .flat_map(|p| x.iter().zip(&wx).map(move |(xi, wi)| (p as f64 * width + xi, wi)))
            .map(|(xk, wi)| (xk / self.h, 2.0 * wi / self.h * ((self.ratio)(xk) - 1.0) / PI))
            .unzip()
    }
}

/// `n`-point Gauss-Legendre nodes and weights on `[lo, hi]` (Newton on Legendre's `P_n`).
fn gauss_legendre(n: usize, lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
            let step = p1 / dp;
            z -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        x[i] = 0.5 * (lo + hi) - 0.5 * (hi - lo) * z;
        w[i] = (hi - lo) / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

/// Solves `m x = b` by Gaussian elimination with partial pivoting (`m` is the identity plus a
/// smooth kernel: well conditioned).
fn solve(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))
            .expect("a non-empty column");
        m.swap(c, p);
        b.swap(c, p);
        let (pivot, below) = m.split_at_mut(c + 1);
        let pivot = &pivot[c];
        for (offset, row) in below.iter_mut().enumerate() {
            let f = row[c] / pivot[c];
            for (x, p) in row[c..].iter_mut().zip(&pivot[c..]) {
                *x -= f * p;
            }
            b[c + 1 + offset] -= f * b[c];
        }
    }
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|j| m[c][j] * b[j]).sum();
        b[c] = (b[c] - s) / m[c][c];
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_incompressible_bonded_polynomial_is_the_quoted_one_with_its_sign() {
        let (a0, b0) = dimitriadis_coefficients(0.5, Base::Bonded);
        let c = [
            -2.0 * a0 / PI,
            4.0 * a0 * a0 / (PI * PI),
            -8.0 / PI.powi(3) * (a0.powi(3) + 4.0 * PI * PI * b0 / 15.0),
            16.0 * a0 / PI.powi(4) * (a0.powi(3) + 3.0 * PI * PI * b0 / 5.0),
        ];
        for (got, want) in c.iter().zip([1.133, 1.283, 0.769, -0.0974]) {
            assert!((got - want).abs() < 1.5e-3, "{c:?}");
        }
        // chi -> 0: Hertz.
        let hertz = crate::hertz::load_of_approach(1e-9, 1e-3, 1e6);
        let thick = dimitriadis_load(1e-9, 1e-3, 1e3, 1e6, 0.3, Base::Bonded);
        assert!((thick / hertz - 1.0).abs() < 1e-6);
    }
}
