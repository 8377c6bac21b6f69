//! The edge of an adhesive contact on a viscoelastic solid as a crack: the energy release rate
//! `G` it needs to recede at speed `v`, `G / w0 = ratio(v)`, rising from 1 (slow) to `E_0/E_inf`
//! (fast), and the pull-off of a sphere drawn back at a constant speed whose edge obeys it.
//!
//! Both models take the far field as relaxed (`E_inf`) and put all dissipation in the material
//! that the crack tip's stress field sweeps past, a cohesive zone of peak stress `sigma0` whose
//! length follows the applied `K` (so it grows with `G`): the models hold where the contact is
//! much larger than that zone and the loading slow next to the relaxation times. The solid is a
//! [`Maxwell`] of creep compliance `J(t) = J_inf - sum_j c_j exp(-t / lambda_j)`; `K` and `G`
//! of the edge of a rigid sphere on it: `G = K^2 / (2 E*)` (JKR's edge field).
//!
//! - Greenwood & Johnson (Phil. Mag. A 43, 1981), in the averaged form of Greenwood (J. Phys.
//!   D 37, 2004): a Dugdale zone of length
//!   `alpha = pi E_inf G / (4 sigma0^2)`, crossed in `T = alpha / v`. The zone's tip opening
//!   under the moving stress field is the elastic one with the compliance averaged over the
//!   transit, weighted by the Dugdale opening profile's slope `artanh(sqrt xi)`:
//!   `w0 / G = E_inf int_0^1 J(T (1 - xi)) artanh(sqrt xi) d xi`.
//! - Persson & Brener (Phys. Rev. E 71, 2005): the dissipation of the stress field outside a
//!   process zone of radius `a = E_inf G / (pi sigma0^2)` (where `K / sqrt(2 pi a) = sigma0`),
//!   `w0 / G = 1 - (2/pi) E_inf int_0^{2 pi v / a} |Im 1/E(omega)| sqrt(1 - (omega a / 2 pi
//!   v)^2) d omega / omega`, which for a Prony series is
//!   `1 - E_inf sum_j c_j (sqrt(1 + k_j^2) - 1) / k_j`, `k_j = 2 pi v lambda_j / a`.

pub use elastic::viscoelastic::Maxwell;
use std::f64::consts::PI;

/// The effective-adhesion model of a receding edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// Greenwood & Johnson's Dugdale zone (see the module docs).
    GreenwoodJohnson,
    /// Persson & Brener's process zone (see the module docs).
    PerssonBrener,
}

impl Model {
    /// Its authors, for tables and legends.
    pub fn name(self) -> &'static str {
        match self {
            Model::GreenwoodJohnson => "Greenwood & Johnson",
            Model::PerssonBrener => "Persson & Brener",
        }
    }
}

/// One model's ratio `G / w0` against crack speed, tabulated for a solid, a work of adhesion
/// `w0` [J/m^2] and a peak cohesive stress `sigma0` \[Pa\].
#[derive(Clone, Debug)]
pub struct EdgeLaw {
    /// `(G / w0, v [m/s])`, both rising.
    table: Vec<(f64, f64)>,
    /// `E_0 / E_inf`: the ratio the fastest edge tends to.
    pub limit: f64,
}

impl EdgeLaw {
    /// The law of `model` on `solid` (a solid without branches has ratio 1 at every speed).
    pub fn new(model: Model, solid: &Maxwell, w0: f64, sigma0: f64) -> EdgeLaw {
        let spectrum = solid.retardation();
        let relaxed = solid.relaxed;
        let limit = solid.glassy() / relaxed;
        // The zone's length per unit ratio [m]: it grows as G.
        let zone = match model {
            Model::GreenwoodJohnson => PI * relaxed * w0 / (4.0 * sigma0 * sigma0),
            Model::PerssonBrener => relaxed * w0 / (PI * sigma0 * sigma0),
        };
        let fastest = spectrum.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
        let slowest = spectrum.iter().map(|s| s.1).fold(0.0, f64::max);
        let mut table = Vec::new();
        if spectrum.is_empty() {
            return EdgeLaw { table, limit };
        }
        // Walk a time scale s (the transit time, or 2 pi / omega_max) from far above the
        // slowest retardation time to far below the fastest: the ratio rises monotonically.
        let (hi, lo) = ((slowest * 1e12).ln(), (fastest * 1e-12).ln());
        let n = 4000;
        for i in 0..=n {
            let s = (hi + (lo - hi) * i as f64 / n as f64).exp();
            let (ratio, v) = match model {
                Model::GreenwoodJohnson => {
                    let averaged: f64 = spectrum
                        .iter()
                        .map(|&(c, lambda)| c * unrelaxed(s / lambda))
                        .sum();
                    let ratio = 1.0 / (1.0 - relaxed * averaged);
                    (ratio, zone * ratio / s)
                }
                Model::PerssonBrener => {
                    let lost: f64 = spectrum
                        .iter()
                        .map(|&(c, lambda)| {
                            let k = 2.0 * PI * lambda / s;
                            c * ((1.0 + k * k).sqrt() - 1.0) / k
                        })
                        .sum();
                    let ratio = 1.0 / (1.0 - relaxed * lost);
                    // omega_max = 2 pi v / a = 2 pi / s.
                    (ratio, zone * ratio / s)
                }
            };
            if table.last().is_none_or(|&(r, u): &(f64, f64)| ratio > r && v > u) {
                table.push((ratio, v));
            }
        }
        EdgeLaw { table, limit }
    }

    /// The speed \[m/s\] at which the edge recedes under `G / w0 = ratio`: 0 at or below 1,
    /// `None` at or beyond the table's fastest (the edge runs away: `ratio` near `E_0/E_inf`).
    pub fn speed(&self, ratio: f64) -> Option<f64> {
        if ratio <= 1.0 {
            return Some(0.0);
        }
        // An elastic solid (no table): any excess runs the edge away.
        let (first, last) = (*self.table.first()?, *self.table.last()?);
        if ratio >= last.0 {
            return None;
        }
        if ratio <= first.0 {
            // Below the table, slower than its slowest: linear to zero at ratio 1.
            return Some(first.1 * (ratio - 1.0) / (first.0 - 1.0));
        }
        let k = self.table.partition_point(|&(r, _)| r <= ratio);
        let ((r0, v0), (r1, v1)) = (self.table[k - 1], self.table[k]);
        let t = (ratio - r0) / (r1 - r0);
        Some((v0.ln() + t * (v1.ln() - v0.ln())).exp())
    }

    /// `G / w0` at crack speed `v` \[m/s\] (the inverse of [`EdgeLaw::speed`]).
    pub fn ratio(&self, v: f64) -> f64 {
        if v <= 0.0 || self.table.is_empty() {
            return 1.0;
        }
        let (first, last) = (self.table[0], self.table[self.table.len() - 1]);
        if v <= first.1 {
            return 1.0 + (first.0 - 1.0) * v / first.1;
        }
        if v >= last.1 {
            return last.0;
        }
        let k = self.table.partition_point(|&(_, u)| u <= v);
        let ((r0, v0), (r1, v1)) = (self.table[k - 1], self.table[k]);
        r0 + (r1 - r0) * (v.ln() - v0.ln()) / (v1.ln() - v0.ln())
    }
}

/// `int_0^1 exp(-beta (1 - xi)) artanh(sqrt xi) d xi`: the share of a retardation of `beta`
/// transit times that is still to come when the zone's opening is complete (1 at 0, 0 for a
/// long transit). By parts and `xi = 1 - s^2`:
/// `(1/beta) int_0^1 (1 - exp(-beta (1 - s^2))) / (1 - s^2) ds`, smooth on `[0, 1]` but with a
/// layer `1/beta` wide at `s = 1`, so the pieces halve towards it.
fn unrelaxed(beta: f64) -> f64 {
    let f = |s: f64| {
        let x = beta * (1.0 - s * s);
        // (1 - e^-x) / (1 - s^2) = beta (1 - e^-x) / x.
        if x > 0.0 { -(-x).exp_m1() / x * beta } else { beta }
    };
    let mut edges = vec![0.0];
    let mut gap: f64 = 0.5;
    while gap > 1e-3 / beta.max(1.0) {
        edges.push(1.0 - gap);
        gap *= 0.5;
    }
    edges.push(1.0);
    let sum: f64 = edges.windows(2).map(|w| gauss(&f, w[0], w[1])).sum();
    sum / beta
}

/// Ten-point Gauss-Legendre on `[a, b]`.
fn gauss(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const X: [f64; 5] = [
        0.148_874_338_981_631_2,
        0.433_395_394_129_247_2,
        0.679_409_568_299_024_4,
        0.865_063_366_688_984_5,
        0.973_906_528_517_171_7,
    ];
    const W: [f64; 5] = [
        0.295_524_224_714_752_9,
        0.269_266_719_309_996_4,
        0.219_086_362_515_982_1,
        0.149_451_349_150_580_6,
        0.066_671_344_308_688_1,
    ];
    let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
    X.iter()
        .zip(W)
        .map(|(&x, w)| w * (f(m - h * x) + f(m + h * x)))
        .sum::<f64>()
        * h
}

/// A rigid sphere drawn back from a relaxed adhesive contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Retraction {
    /// The least load on the way \[N\] (negative: tensile).
    pub pull_off: f64,
    /// The approach there \[m\].
    pub approach: f64,
    /// The contact radius there \[m\].
    pub radius: f64,
}

/// A sphere of radius `r` \[m\] held at approach `from` \[m\] until its JKR contact (relaxed
/// modulus, work `w0` [J/m^2]) has settled, then drawn back at `speed` \[m/s\]: the edge
/// recedes at the speed `law` gives for the JKR energy release rate
/// `G = E_inf (a^2/R - delta)^2 / (2 pi a)`, the load `P = 2 E_inf a delta - 2 E_inf a^3 / (3R)`
/// (JKR with `G` for `w0`). Backward Euler in time, `steps` steps across the approach from
/// `from` to the relaxed JKR's fixed-grip separation, and on as long as the contact lasts. `None`
/// when `from` is too shallow for a contact.
pub fn retraction(
    law: &EdgeLaw,
    relaxed: f64,
    r: f64,
    w0: f64,
    from: f64,
    speed: f64,
    steps: usize,
) -> Option<Retraction> {
    let c = (2.0 * PI * w0 / relaxed).sqrt();
    let delta_of = |a: f64| a * a / r - c * a.sqrt();
    // delta(a) falls to its least at a_m, then rises: the stable branch is beyond.
    let a_m = (c * r / 4.0).powf(2.0 / 3.0);
    if from < delta_of(a_m) {
        return None;
    }
    let mut hi = 2.0 * a_m;
    while delta_of(hi) < from {
        hi *= 2.0;
    }
    let mut a = last_where(a_m, hi, |x| delta_of(x) < from);
    let release = |a: f64, delta: f64| relaxed * (a * a / r - delta).powi(2) / (2.0 * PI * a);
    let load = |a: f64, delta: f64| 2.0 * relaxed * a * delta - 2.0 * relaxed * a.powi(3) / (3.0 * r);
    let dt = (from - delta_of(a_m)) / steps as f64 / speed;
    let (mut t, mut delta) = (0.0, from);
    let mut least = Retraction {
        pull_off: load(a, delta),
        approach: delta,
        radius: a,
    };
    let floor = 1e-6 * a;
    while a > floor {
        t += dt;
        delta = from - speed * t;
        // a' + dt v(G(a', delta) / w0) = a: the left side rises with a' (G does on the
        // adhesive branch), so bisect between the edge's least radius and a.
        let residual = |x: f64| law.speed(release(x, delta) / w0).map(|v| x + dt * v - a);
        // An edge beyond the fastest ratio runs (a residual of None counts as too large) to
        // where G allows a finite speed, if anywhere on the stable side.
        match residual(a) {
            Some(rest) if rest <= 0.0 => {} // G <= w0: the edge holds
            _ => {
                // G is least at a^2 = R delta (delta > 0) or 3 a^2 = -R delta (delta < 0);
                // beyond, it rises with a. No root there: the sphere is off.
                let lo = (r * delta.max(-delta / 3.0)).sqrt();
                let holds = |x: f64| residual(x).is_some_and(|rest| rest <= 0.0);
                if !holds(lo) {
                    break;
                }
                a = last_where(lo, a, holds);
            }
        }
        let p = load(a, delta);
        if p < least.pull_off {
            least = Retraction {
                pull_off: p,
                approach: delta,
                radius: a,
            };
        }
    }
    Some(least)
}

/// The end of the stretch of `[lo, hi]` from `lo` where `holds` (true at `lo`, false beyond
/// some point), by bisection to round-off.
fn last_where(mut lo: f64, mut hi: f64, holds: impl Fn(f64) -> bool) -> f64 {
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return lo;
        }
        if holds(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}
