//! Greenwood (1997): a smooth elastic sphere against a rigid flat with the full Lennard-Jones
//! 9-3 law (repulsion included), solved on an axisymmetric grid of rings.
//!
//! Dimensionless units: separations `h = z / z0`; radii `rho = r / sqrt(R z0)`; pressures
//! `P = p z0 / w0` with `P(h) = (8/3)(h^-9 - h^-3)` (> 0 repulsive); load `W / (2 pi R w0)`;
//! approach `alpha / z0`. The separation is
//! `h(rho) = 1 + rho^2/2 - alpha + theta sum_j C(rho, ring j) P(h_j)`, `theta = (4/pi) mu^(3/2)`,
//! with `C` the exact displacement of a uniformly loaded ring (difference of two discs,
//! Johnson's Contact Mechanics eq. 3.39, through complete elliptic integrals). So the approach
//! is zero when the undeformed apex sits at the Lennard-Jones equilibrium `z = z0` (the
//! boundary-element model's zero: gap `g = z - z0 = 0` at first touch) and positive pushing
//! together. Equilibria are found by Newton iterations at a prescribed central separation
//! `h(0)`, which traces the S-shaped curves of `mu > 1` whole.

use std::f64::consts::PI;

/// Complete elliptic integrals `K(k)` and `E(k)` of modulus `0 <= k < 1`, by the
/// arithmetic-geometric mean (to round-off).
pub fn elliptic_ke(k: f64) -> (f64, f64) {
    elliptic_ke_complementary(k, ((1.0 - k) * (1.0 + k)).sqrt())
}

/// [`elliptic_ke`] given the complementary modulus `kp = sqrt(1 - k^2)` as well, which keeps
/// its precision where `k` rounds to 1 (`K` grows as `ln(4 / kp)`).
pub fn elliptic_ke_complementary(k: f64, kp: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0, kp);
    let mut c = k;
    let mut sum = 0.5 * c * c;
    let mut power = 0.5;
    for _ in 0..40 {
        if c.abs() < 1e-17 {
            break;
        }
        let an = 0.5 * (a + b);
        c = 0.5 * (a - b);
        b = (a * b).sqrt();
        a = an;
        power *= 2.0;
        sum += power * c * c;
    }
    let kk = PI / (2.0 * a);
    (kk, kk * (1.0 - sum))
}

/// Displacement at radius `r` under unit pressure on the disc of radius `a`, in units of
/// `4 / (pi E*)`: `a E(r/a)` inside, `r [E(a/r) - (1 - a^2/r^2) K(a/r)]` outside.
fn disc(r: f64, a: f64) -> f64 {
    if a == 0.0 {
        0.0
    } else if r <= a {
        a * elliptic_ke(r / a).1
    } else {
        let k = a / r;
        let (kk, ee) = elliptic_ke(k);
        r * (ee - (1.0 - k * k) * kk)
    }
}

/// `P(h)` and `dP/dh`.
fn lj(h: f64) -> (f64, f64) {
    let h3 = h.powi(-3);
    let h9 = h3 * h3 * h3;
    (8.0 / 3.0 * (h9 - h3), 8.0 / 3.0 * (-9.0 * h9 + 3.0 * h3) / h)
}

/// The ring grid: uniform rings of width `spacing` out to `uniform_to`, then rings growing
/// geometrically (by 5 %) to `outer` (all in units of `sqrt(R z0)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mesh {
    pub spacing: f64,
    pub uniform_to: f64,
    pub outer: f64,
}

impl Default for Mesh {
    /// Fine enough that halving the spacing moves the pull-off by less than 1e-4 for
    /// `0.1 <= mu <= 3` (tested).
    fn default() -> Self {
        Mesh {
            spacing: 0.02,
            uniform_to: 6.0,
            outer: 40.0,
        }
    }
}

/// One equilibrium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Central separation `h(0) = z(0)/z0` [-].
    pub central_separation: f64,
    /// Approach `alpha/z0` [-].
    pub approach: f64,
    /// Load `W / (2 pi R w0)` [-], > 0 compressive.
    pub load: f64,
    /// Radius of the repulsive zone (`h < 1`) in units of `sqrt(R z0)` [-].
    pub contact_radius: f64,
}

/// A traced curve and its characteristic points.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Equilibria from far apart into compression (central separation decreasing).
    pub points: Vec<Point>,
    /// Index of the jump into contact under displacement control (local maximum of the
    /// approach), if the curve is S-shaped.
    pub jump_in: Option<usize>,
    /// Index of the jump out of contact (local minimum of the approach after `jump_in`).
    pub jump_out: Option<usize>,
    /// The most negative load: pull-off under load control [2 pi R w0].
    pub pull_off_load_control: f64,
    /// The load at the jump out under displacement control, or the load-control value when
    /// the curve has no S (separation is then continuous) [2 pi R w0].
    pub pull_off_displacement_control: f64,
}

/// The axisymmetric Lennard-Jones sphere at one Tabor parameter.
pub struct Greenwood {
    mu: f64,
    theta: f64,
    centres: Vec<f64>,
    /// Ring areas over 2 pi: `(b^2 - a^2)/2`.
    weights: Vec<f64>,
    /// Outer radius of the grid.
    outer: f64,
    /// `influence[i * n + j]`: displacement at ring i under unit pressure on ring j
    /// (units of `4/(pi E*)`, lengths in `sqrt(R z0)`).
    influence: Vec<f64>,
}

/// A Newton solve that failed, at this central separation \[z0\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoConvergence {
    pub central_separation: f64,
}

impl std::fmt::Display for NoConvergence {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Newton iterations did not converge at central separation {} z0",
            self.central_separation
        )
    }
}

impl std::error::Error for NoConvergence {}

impl Greenwood {
    /// The model at Tabor parameter `mu > 0` on `mesh`.
    ///
    /// # Panics
    /// If `mu` or the mesh sizes are not finite and positive.
    pub fn new(mu: f64, mesh: Mesh) -> Self {
        assert!(mu.is_finite() && mu > 0.0, "mu must be finite and > 0");
        assert!(
            mesh.spacing > 0.0 && mesh.uniform_to > mesh.spacing && mesh.outer >= mesh.uniform_to,
            "bad mesh {mesh:?}"
        );
        let mut edges = vec![0.0];
        while *edges.last().unwrap() < mesh.uniform_to - 1e-12 {
            edges.push(edges.len() as f64 * mesh.spacing);
        }
        let mut width = mesh.spacing;
        while *edges.last().unwrap() < mesh.outer {
            width *= 1.05;
            edges.push(edges.last().unwrap() + width);
        }
        let n = edges.len() - 1;
        let centres: Vec<f64> = (0..n).map(|j| 0.5 * (edges[j] + edges[j + 1])).collect();
        let weights = (0..n)
            .map(|j| 0.5 * (edges[j + 1] * edges[j + 1] - edges[j] * edges[j]))
            .collect();
        let mut influence = vec![0.0; n * n];
        for (i, &r) in centres.iter().enumerate() {
            let discs: Vec<f64> = edges.iter().map(|&a| disc(r, a)).collect();
            for j in 0..n {
                influence[i * n + j] = discs[j + 1] - discs[j];
            }
        }
        Greenwood {
            mu,
            theta: 4.0 / PI * mu.powf(1.5),
            centres,
            weights,
            outer: *edges.last().unwrap(),
            influence,
        }
    }

    /// Tabor parameter.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    fn n(&self) -> usize {
        self.centres.len()
    }

    /// The load of a separation field, with the attraction of the undeformed sphere beyond the
    /// grid added analytically: `-(4/3) (1 - alpha + rho_max^2/2)^-2`.
    fn load(&self, h: &[f64], alpha: f64) -> f64 {
        let inside: f64 = h.iter().zip(&self.weights).map(|(&h, &w)| lj(h).0 * w).sum();
        let c = 1.0 - alpha + 0.5 * self.outer * self.outer;
        inside - 4.0 / 3.0 / (c * c)
    }

    /// The equilibrium at central separation `hc`, starting Newton from `(alpha, h)`.
    /// Returns the new `(alpha, h)`.
    fn newton(&self, hc: f64, mut alpha: f64, mut h: Vec<f64>) -> Result<(f64, Vec<f64>), NoConvergence> {
        let n = self.n();
        h[0] = hc;
        let residual = |alpha: f64, h: &[f64]| -> Vec<f64> {
            let p: Vec<f64> = h.iter().map(|&x| lj(x).0).collect();
            (0..n)
                .map(|i| {
                    let row = &self.influence[i * n..(i + 1) * n];
                    let u: f64 = row.iter().zip(&p).map(|(c, p)| c * p).sum();
                    h[i] - 1.0 - 0.5 * self.centres[i] * self.centres[i] + alpha - self.theta * u
                })
                .collect()
        };
        let norm = |f: &[f64]| f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut f = residual(alpha, &h);
        // Chord iterations: the Jacobian is factored again only when the residual stops
        // falling fast (continuation gives good starts, so one factorisation per point is usual).
        let mut lu: Option<Lu> = None;
        let mut last_norm = f64::INFINITY;
        for _ in 0..60 {
            let current = norm(&f);
            if current < 1e-11 {
                return Ok((alpha, h));
            }
            if lu.is_none() || current > 0.25 * last_norm {
                // Unknowns: alpha (column 0) and h_1..h_(n-1).
                let dp: Vec<f64> = h.iter().map(|&x| lj(x).1).collect();
                let mut jac = vec![0.0; n * n];
                for i in 0..n {
                    let row = &self.influence[i * n..(i + 1) * n];
                    let out = &mut jac[i * n..(i + 1) * n];
                    out[0] = 1.0;
                    for j in 1..n {
                        out[j] = -self.theta * row[j] * dp[j];
                    }
                    if i > 0 {
                        out[i] += 1.0;
                    }
                }
                lu = Some(Lu::new(jac, n).ok_or(NoConvergence {
                    central_separation: hc,
                })?);
            }
            last_norm = current;
            let step = lu
                .as_ref()
                .expect("factored above")
                .solve(f.iter().map(|v| -v).collect());
            // Damped: keep every separation positive and the residual falling.
            let mut t = 1.0;
            loop {
                let trial_alpha = alpha + t * step[0];
                let mut trial = h.clone();
                for j in 1..n {
                    trial[j] += t * step[j];
                }
                if trial.iter().all(|&x| x > 0.2) {
                    let ft = residual(trial_alpha, &trial);
                    if norm(&ft) < norm(&f) || t < 1e-3 {
                        alpha = trial_alpha;
                        h = trial;
                        f = ft;
                        break;
                    }
                }
                t *= 0.5;
                if t < 1e-6 {
                    return Err(NoConvergence {
                        central_separation: hc,
                    });
                }
            }
        }
        if norm(&f) < 1e-9 {
            Ok((alpha, h))
        } else {
            Err(NoConvergence {
                central_separation: hc,
            })
        }
    }

    fn point(&self, alpha: f64, h: &[f64]) -> Point {
        let contact = h
            .iter()
            .zip(&self.centres)
            .filter(|(h, _)| **h < 1.0)
            .map(|(_, r)| *r)
            .fold(0.0, f64::max);
        Point {
            central_separation: h[0],
            approach: alpha,
            load: self.load(h, alpha),
            contact_radius: contact,
        }
    }

    /// The equilibrium at central separation `hc` (cold start from the undeformed sphere).
    pub fn at(&self, hc: f64) -> Result<Point, NoConvergence> {
        let alpha = 1.0 - hc;
        let h: Vec<f64> = self.centres.iter().map(|r| hc + 0.5 * r * r).collect();
        let (alpha, h) = self.newton(hc, alpha, h)?;
        Ok(self.point(alpha, &h))
    }

    /// Traces the curve from central separation `from` (far apart, e.g. 5) down until the
    /// approach exceeds `max_approach` (or the separation reaches 0.3), with steps adapted
    /// so that consecutive points differ by about `resolution` in approach or load.
    pub fn curve(&self, from: f64, max_approach: f64, resolution: f64) -> Result<Curve, NoConvergence> {
        let mut hc = from;
        let mut alpha = 1.0 - hc;
        let mut h: Vec<f64> = self.centres.iter().map(|r| hc + 0.5 * r * r).collect();
        let mut points = Vec::new();
        // Each point's (alpha, profile): the warm starts of the folds' refinement.
        let mut states: Vec<(f64, Vec<f64>)> = Vec::new();
        let mut dh = 0.02;
        let mut previous: Option<(f64, Vec<f64>)> = None;
        loop {
            // Predictor: the secant through the last two solutions.
            let (guess_alpha, guess_h) = match &previous {
                Some((pa, ph)) if !points.is_empty() => {
                    let last: &Point = points.last().unwrap();
                    let ratio = dh / (ph[0] - last.central_separation).abs().max(1e-12);
                    let ga = alpha + (alpha - pa) * ratio;
                    let gh: Vec<f64> = h.iter().zip(ph).map(|(x, p)| x + (x - p) * ratio).collect();
                    (ga, gh)
                }
                _ => (alpha, h.clone()),
            };
            let target = hc - if points.is_empty() { 0.0 } else { dh };
            match self.newton(target, guess_alpha, guess_h) {
                Ok((a, hn)) => {
                    let p = self.point(a, &hn);
                    if let Some(last) = points.last() {
                        let last: &Point = last;
                        let change = (p.approach - last.approach)
                            .abs()
                            .max((p.load - last.load).abs() / p.load.abs().max(1.0));
                        if change > 2.0 * resolution && dh > 1e-5 {
                            dh *= 0.5;
                            continue;
                        }
                        if change < 0.5 * resolution {
                            dh = (dh * 1.5).min(0.2);
                        }
                    }
                    states.push((a, hn.clone()));
                    previous = Some((alpha, std::mem::replace(&mut h, hn)));
                    alpha = a;
                    hc = target;
                    points.push(p);
                    if p.approach > max_approach || hc < 0.3 {
                        break;
                    }
                }
                Err(e) => {
                    if dh > 1e-6 {
                        dh *= 0.5;
                    } else {
                        return Err(e);
                    }
                }
            }
        }
        let mut curve = characterise(points);
        // The sampled turning points are up to a step off the folds: solve at the folds (where
        // a warm-started Newton solve fails, the sampled point stays, within `resolution`).
        for k in [curve.jump_in, curve.jump_out].into_iter().flatten() {
            if let Ok(p) = self.turning_point(&curve.points[k - 1..=k + 1], &states[k]) {
                curve.points[k] = p;
            }
        }
        if let Some(k) = curve.jump_out {
            curve.pull_off_displacement_control = curve.points[k].load;
        }
        Ok(curve)
    }

    /// The fold of the approach (a local extremum against the central separation) bracketed by
    /// three traced points, the middle one the extreme: by successive parabolic interpolation
    /// through the best three, solving at each vertex, until the separation moves less than
    /// 1e-9; each solve starts from `start` (the middle point's alpha and profile).
    fn turning_point(&self, around: &[Point], start: &(f64, Vec<f64>)) -> Result<Point, NoConvergence> {
        let sign = if around[1].approach > around[0].approach {
            -1.0
        } else {
            1.0
        };
        let f = |p: &Point| sign * p.approach;
        let (lo, hi) = (
            around[0].central_separation.min(around[2].central_separation),
            around[0].central_separation.max(around[2].central_separation),
        );
        let mut best: Vec<Point> = around.to_vec();
        for _ in 0..20 {
            best.sort_by(|a, b| f(a).total_cmp(&f(b)));
            let [a, b, c] = [best[0], best[1], best[2]].map(|p| (p.central_separation, f(&p)));
            let den = (b.0 - a.0) * (b.1 - c.1) - (b.0 - c.0) * (b.1 - a.1);
            if den == 0.0 {
                break;
            }
            let num = (b.0 - a.0).powi(2) * (b.1 - c.1) - (b.0 - c.0).powi(2) * (b.1 - a.1);
            let h = (b.0 - 0.5 * num / den).clamp(lo, hi);
            if best.iter().any(|p| (p.central_separation - h).abs() < 1e-9) {
                break;
            }
            let shift = h - start.1[0];
            let guess = start.1.iter().map(|x| x + shift).collect();
            let (alpha, profile) = self.newton(h, start.0 - shift, guess)?;
            best[2] = self.point(alpha, &profile);
        }
        best.sort_by(|a, b| f(a).total_cmp(&f(b)));
        Ok(best[0])
    }
}

/// Finds the turning points and pull-offs of a traced curve.
pub fn characterise(points: Vec<Point>) -> Curve {
    let mut jump_in = None;
    let mut jump_out = None;
    for k in 1..points.len().saturating_sub(1) {
        let (a, b, c) = (points[k - 1].approach, points[k].approach, points[k + 1].approach);
        if jump_in.is_none() && b > a && b >= c {
            jump_in = Some(k);
        } else if jump_in.is_some() && jump_out.is_none() && b < a && b <= c {
            jump_out = Some(k);
        }
    }
    let pull_off_load_control = points.iter().map(|p| p.load).fold(f64::INFINITY, f64::min);
    let pull_off_displacement_control = jump_out.map_or(pull_off_load_control, |k| points[k].load);
    Curve {
        points,
        jump_in,
        jump_out,
        pull_off_load_control,
        pull_off_displacement_control,
    }
}

/// A dense LU factorisation with partial pivoting (row-major, `n x n`).
struct Lu {
    a: Vec<f64>,
    pivots: Vec<usize>,
    n: usize,
}

impl Lu {
    /// Factors `a`; `None` if it is singular.
    fn new(mut a: Vec<f64>, n: usize) -> Option<Lu> {
        let mut pivots = Vec::with_capacity(n);
        for k in 0..n {
            let p = (k..n).max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))?;
            if a[p * n + k] == 0.0 {
                return None;
            }
            pivots.push(p);
            if p != k {
                for j in 0..n {
                    a.swap(k * n + j, p * n + j);
                }
            }
            let pivot = a[k * n + k];
            let (top, rest) = a.split_at_mut((k + 1) * n);
            let row_k = &top[k * n..(k + 1) * n];
            for row in rest.chunks_mut(n) {
                let f = row[k] / pivot;
                row[k] = f;
                if f != 0.0 {
                    for (x, y) in row[k + 1..].iter_mut().zip(&row_k[k + 1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        Some(Lu { a, pivots, n })
    }

    fn solve(&self, mut b: Vec<f64>) -> Vec<f64> {
        let (a, n) = (&self.a, self.n);
        for (k, &p) in self.pivots.iter().enumerate() {
            b.swap(k, p);
        }
        for i in 0..n {
            let s: f64 = (0..i).map(|j| a[i * n + j] * b[j]).sum();
            b[i] -= s;
        }
        for k in (0..n).rev() {
            let s: f64 = ((k + 1)..n).map(|j| a[k * n + j] * b[j]).sum();
            b[k] = (b[k] - s) / a[k * n + k];
        }
        b
    }
}
