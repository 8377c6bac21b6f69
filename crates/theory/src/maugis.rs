//! The Maugis-Dugdale model (Maugis 1992) in its dimensionless units (docs/method.md section 8.3):
//! `A = a / (pi w0 R^2 / K)^(1/3)`, `P = load / (pi w0 R)`,
//! `D = delta / (pi^2 w0^2 R / K^2)^(1/3)`, `K = 4 E*/3`, with the transition parameter
//! `lambda = 2 sigma0 (R / (pi w0 K^2))^(1/3)`. The curve is parameterised by `m = c/a > 1`,
//! the ratio of the cohesive-zone radius to the contact radius.

/// One point of the Maugis-Dugdale curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// `m = c/a` [-].
    pub m: f64,
    /// Contact radius `A` [-].
    pub radius: f64,
    /// Load `P` [-] (units of `pi w0 R`).
    pub load: f64,
    /// Approach `D` [-].
    pub approach: f64,
}

/// The model at one value of Maugis' parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaugisDugdale {
    pub lambda: f64,
}

impl MaugisDugdale {
    /// The model at `lambda > 0`.
    ///
    /// # Panics
    /// If `lambda` is not finite and positive.
    pub fn new(lambda: f64) -> Self {
        assert!(
            lambda.is_finite() && lambda > 0.0,
            "lambda must be finite and > 0"
        );
        MaugisDugdale { lambda }
    }

    /// The point at `m > 1`: `A` from Maugis' equation
    /// `(lambda A^2/2)[s + (m^2 - 2) atan s] + (4 lambda^2 A/3)[s atan s - m + 1] = 1`,
    /// `s = sqrt(m^2 - 1)` (a quadratic in `A`), then
    /// `P = A^3 - lambda A^2 [s + m^2 atan s]` and `D = A^2 - (4/3) A lambda s`.
    pub fn point(&self, m: f64) -> Point {
        self.point_from_excess(m - 1.0)
    }

    /// [`MaugisDugdale::point`] at `m = 1 + e`, given `e` itself: near the JKR limit the
    /// cohesive zone is so thin that `m` rounds to 1.
    pub fn point_from_excess(&self, e: f64) -> Point {
        let l = self.lambda;
        let m = 1.0 + e;
        let s = (e * (2.0 + e)).sqrt();
        let at = s.atan();
        let alpha = 0.5 * l * (s + (m * m - 2.0) * at);
        // s atan s - (m - 1), accurate for small s by its series s^2 - s^4/3 - (s^2/2 - s^4/8).
        let bracket = if s < 1e-3 {
            let s2 = s * s;
            s2 / 2.0 - 5.0 * s2 * s2 / 24.0
        } else {
            s * at - e
        };
        let beta = 4.0 * l * l / 3.0 * bracket;
        // alpha A^2 + beta A - 1 = 0, positive root written without cancellation.
        let a = 2.0 / (beta + (beta * beta + 4.0 * alpha).sqrt());
        Point {
            m,
            radius: a,
            load: a.powi(3) - l * a * a * (s + m * m * at),
            approach: a * a - 4.0 / 3.0 * a * l * s,
        }
    }

    /// Points for `m` from just above 1 (large contact) to large `m` (vanishing contact),
    /// `count` of them, spaced evenly in `ln(m - 1)`.
    pub fn curve(&self, count: usize) -> Vec<Point> {
        let (lo, hi) = self.m_range();
        (0..count)
            .map(|k| {
                let t = k as f64 / (count.max(2) - 1) as f64;
                self.point_from_excess((lo + t * (hi - lo)).exp())
            })
            .collect()
    }

    /// Points from contact radius `a_max` (in compression) to separation, `count` of them,
    /// spaced evenly in `ln(m - 1)`: the part of the curve worth plotting.
    pub fn curve_to_radius(&self, count: usize, a_max: f64) -> Vec<Point> {
        let (mut lo, hi) = self.m_range();
        // The contact radius falls as m grows: bisect ln(m - 1) for A = a_max.
        let (mut a, mut b) = (lo, hi);
        if self.point_from_excess(a.exp()).radius > a_max {
            for _ in 0..200 {
                let c = 0.5 * (a + b);
                if self.point_from_excess(c.exp()).radius > a_max {
                    a = c;
                } else {
                    b = c;
                }
            }
            lo = b;
        }
        (0..count)
            .map(|k| {
                let t = k as f64 / (count.max(2) - 1) as f64;
                self.point_from_excess((lo + t * (hi - lo)).exp())
            })
            .collect()
    }

    /// The range of `ln(m - 1)` that covers the curve from deep compression to separation.
    fn m_range(&self) -> (f64, f64) {
        let l = self.lambda;
        // The cohesive zone is ~ 1/lambda^2 of the contact at large lambda, and m ~ 1/lambda
        // at small lambda: cover both generously.
        ((1e-10 / (1.0 + l * l)).ln(), (1e4 * (1.0 + 1.0 / l)).ln())
    }

    /// Minimum over the curve of `f(point)`, by a scan in `ln(m - 1)` refined by golden sections.
    fn minimum(&self, f: impl Fn(&Point) -> f64) -> Point {
        let (lo, hi) = self.m_range();
        let n = 4000;
        let at = |x: f64| self.point_from_excess(x.exp());
        let xs: Vec<f64> = (0..=n).map(|k| lo + (hi - lo) * k as f64 / n as f64).collect();
        let k = (0..=n)
            .min_by(|&i, &j| f(&at(xs[i])).total_cmp(&f(&at(xs[j]))))
            .expect("non-empty scan");
        let (mut a, mut b) = (xs[k.saturating_sub(1)], xs[(k + 1).min(n)]);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if f(&at(c)) < f(&at(d)) {
                b = d;
            } else {
                a = c;
            }
        }
        at(0.5 * (a + b))
    }

    /// Pull-off force under load control [-] (units of `pi w0 R`): the minimum load.
    pub fn pull_off_load_control(&self) -> f64 {
        self.minimum(|p| p.load).load
    }

    /// Pull-off force under displacement control [-]: the load where the approach is smallest
    /// (where a rigid grip loses stability). Where the curve has no such fold (lambda below
    /// about 0.94: the approach falls until the contact vanishes, and separation is
    /// continuous) the load-control value, as Greenwood's curves report it.
    pub fn pull_off_displacement_control(&self) -> f64 {
        self.fold()
            .map_or_else(|| self.pull_off_load_control(), |p| p.load)
    }

    /// Whether the approach has a minimum before the contact vanishes (a jump out under
    /// displacement control).
    pub fn has_fold(&self) -> bool {
        self.fold().is_some()
    }

    /// The point of least approach, if it lies before the contact vanishes.
    fn fold(&self) -> Option<Point> {
        let (_, hi) = self.m_range();
        let fold = self.minimum(|p| p.approach);
        let end = self.point_from_excess(hi.exp());
        (fold.approach < end.approach - 1e-9 * end.approach.abs().max(1.0)).then_some(fold)
    }
}
