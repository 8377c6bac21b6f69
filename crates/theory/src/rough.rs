//! Contact-area and stickiness formulas for rough surfaces (docs/method.md sections 6 and 8).

use std::f64::consts::PI;

/// Persson's relative contact area `erf(sqrt(2) p / (E* g_bar))` for the reduced pressure
/// `reduced = p / (E* g_bar)`; its small-load slope is `sqrt(8/pi)`.
pub fn persson_area(reduced: f64) -> f64 {
    erf(2f64.sqrt() * reduced)
}

/// Persson's (2001) elastoplastic contact: the elastic and the plastic relative contact areas
/// `(a_el, a_pl)` at the reduced pressure `reduced = p / (E* g_bar)` and reduced hardness
/// `hardness = H / (E* g_bar)`. The pressure distribution diffuses from `p` with absorbing walls
/// at 0 and `H`, over the variance `G = E*^2 g_bar^2 / 8`:
/// `a_el = sum_(n odd) 4/(n pi) sin(n pi p/H) exp(-s_n^2 G)`, `s_n = n pi / H`, and the plastic
/// area carries the rest of the load at `H`, `a_pl = (p - integral s P(s) ds) / H`. Without a
/// hardness (large `hardness`) `a_el` is [`persson_area`]; as `hardness -> 0`, `a_pl -> p / H`,
/// the bearing area. Closed forms after Xu, Li & Mulvihill (arXiv 2208.02665).
pub fn persson_elastoplastic(reduced: f64, hardness: f64) -> (f64, f64) {
    if reduced <= 0.0 {
        return (0.0, 0.0);
    }
    if reduced >= hardness {
        // The whole surface at the hardness carries the load.
        return (0.0, 1.0);
    }
    let variance = 1.0 / 8.0;
    // Terms until the exponential is below 1e-17: n pi / H > sqrt(40 / G).
    let terms = ((40.0f64 / variance).sqrt() * hardness / PI).ceil() as usize + 1;
    if terms > 1_000_000 {
        // The walls are too far apart to matter: the elastic theory.
        return (persson_area(reduced), 0.0);
    }
    let (mut elastic, mut carried) = (0.0, 0.0);
    for n in 1..=terms {
        let s = n as f64 * PI / hardness;
        let weight = (s * reduced).sin() * (-s * s * variance).exp();
        if n % 2 == 1 {
            elastic += 4.0 / (n as f64 * PI) * weight;
            carried += 2.0 * hardness / (n as f64 * PI) * weight;
        } else {
            carried -= 2.0 * hardness / (n as f64 * PI) * weight;
        }
    }
    (elastic.max(0.0), ((reduced - carried) / hardness).clamp(0.0, 1.0))
}

/// Müser's relative contact area (the paper's Eq. 14 with its bracket corrected) of a
/// nominally flat surface at reduced pressure `reduced = p / (E* g_bar)`:
/// `a_r = (1 - 1/(2x^2)) erf(x) + exp(-x^2)/(sqrt(pi) x)`, `x = k (3 sqrt(pi)/4) reduced`.
/// At small load `a_r -> k reduced`; at large load `a_r -> 1`.
pub fn muser_area(reduced: f64, k: f64) -> f64 {
    let x = k * 0.75 * PI.sqrt() * reduced;
    if x < 1e-4 {
        // Series: (4/(3 sqrt pi)) x (1 - x^2/10 + ...), avoiding the cancellation of the closed form.
        return 4.0 / (3.0 * PI.sqrt()) * x * (1.0 - x * x / 10.0);
    }
    (1.0 - 1.0 / (2.0 * x * x)) * erf(x) + (-x * x).exp() / (PI.sqrt() * x)
}

/// Modified Johnson parameter (Li, Pohrt & Popov 2019; the paper's Eq. 15):
/// `alpha* = (4 w0 q1^(0.8H - 1) / (pi E* h^2 q0^(0.8H)))^2`, with the RMS roughness `h` \[m\],
/// smallest and largest wavevectors `q0`, `q1` [rad/m] and Hurst exponent `hurst`.
pub fn johnson_parameter(w0: f64, e_star: f64, h: f64, q0: f64, q1: f64, hurst: f64) -> f64 {
    (4.0 * w0 * q1.powf(0.8 * hurst - 1.0) / (PI * e_star * h * h * q0.powf(0.8 * hurst))).powi(2)
}

/// Ciavarella's (2019) plotting variable `Rq^2 E* / (lambda_L w0)` (the paper's Eq. 16).
pub fn ciavarella_variable(rq: f64, e_star: f64, lambda_l: f64, w0: f64) -> f64 {
    rq * rq * e_star / (lambda_l * w0)
}

/// Ciavarella's criterion: sticky when `Rq < sqrt(beta lambda_L w0 / E*)`, `beta = 0.6`.
pub fn ciavarella_sticky(rq: f64, e_star: f64, lambda_l: f64, w0: f64) -> bool {
    ciavarella_variable(rq, e_star, lambda_l, w0) < 0.6
}

/// The error function, to about 1e-15 (series below 2.5, continued fraction above).
pub fn erf(x: f64) -> f64 {
    if x < 0.0 {
        return -erf(-x);
    }
    if x < 2.5 {
        // erf x = 2/sqrt(pi) exp(-x^2) sum_n 2^n x^(2n+1) / (1 3 5 ... (2n+1))
        let mut term = x;
        let mut sum = x;
        let x2 = x * x;
        let mut n = 0.0;
        while term.abs() > 1e-17 * sum.abs() {
            n += 1.0;
            term *= 2.0 * x2 / (2.0 * n + 1.0);
            sum += term;
        }
        2.0 / PI.sqrt() * (-x2).exp() * sum
    } else {
        // erfc x = exp(-x^2)/sqrt(pi) * 1/(x + 1/2/(x + 1/(x + 3/2/(x + ...)))), Lentz-free form.
        let mut f = 0.0;
        for k in (1..60).rev() {
            f = (k as f64 / 2.0) / (x + f);
        }
        1.0 - (-x * x).exp() / (PI.sqrt() * (x + f))
    }
}

/// The isotropic self-affine power spectrum of the paper's Eq. 13, normalised to an RMS height:
/// `C(q) = C0` for `q_long <= q < q_rolloff`, `C0 (q/q_rolloff)^(-2(1+H))` up to `q_short`,
/// zero elsewhere. Wavevectors in rad/m, heights in m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SelfAffineSpectrum {
    pub hurst: f64,
    pub q_long: f64,
    pub q_rolloff: f64,
    pub q_short: f64,
    pub rms_height: f64,
}

impl SelfAffineSpectrum {
    /// `integral d^2q q^n C(q) / C0 = 2 pi integral q^(n+1) C(q)/C0 dq`.
    fn shape_moment(&self, n: f64) -> f64 {
        let (ql, qr, qs, h) = (self.q_long, self.q_rolloff, self.q_short, self.hurst);
        let plateau = (qr.powf(n + 2.0) - ql.powf(n + 2.0)) / (n + 2.0);
        let e = n - 2.0 * h;
        let tail = qr.powf(2.0 + 2.0 * h)
            * if e.abs() < 1e-12 {
                (qs / qr).ln()
            } else {
                (qs.powf(e) - qr.powf(e)) / e
            };
        2.0 * PI * (plateau + tail)
    }

    /// The spectral moment `integral d^2q |q|^n C(q)`: `Rq^2` for `n = 0`, the mean square
    /// gradient for `n = 2`, and for `n = 1` the integral of the elastic energy of full contact
    /// (Persson & Tosatti) [m^(2-n)].
    pub fn moment(&self, n: f64) -> f64 {
        self.rms_height * self.rms_height * self.shape_moment(n) / self.shape_moment(0.0)
    }
}

/// Persson & Tosatti's (2001) effective work of adhesion [J/m^2]: the adhesion gained over the
/// true (larger) area in full contact, `w0 (1 + g_bar^2 / 2)`, minus the elastic energy per
/// nominal area stored by flattening the roughness, `(E*/4) integral d^2q |q| C(q)`
/// (`moment_1` \[m\], e.g. [`SelfAffineSpectrum::moment`]`(1.0)`). The surfaces stick
/// (full contact holds without load) when it is positive.
pub fn persson_tosatti_work(w0: f64, e_star: f64, moment_1: f64, rms_gradient: f64) -> f64 {
    w0 * (1.0 + 0.5 * rms_gradient * rms_gradient) - 0.25 * e_star * moment_1
}
