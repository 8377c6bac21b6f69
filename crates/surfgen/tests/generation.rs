//! Generated surfaces against their specification: spectrum, normalisation, slopes, Hurst
//! exponent and reproducibility.

use fft2::Complex64;
use fft2::Fft2;
use ndarray::Array2;
use surfgen::{Amplitudes, Grid, Normalization, Psd, RadialPsd, SurfaceSpec, generate, statistics};

fn spec(n: usize, psd: Psd, normalization: Normalization, amplitudes: Amplitudes, seed: u64) -> SurfaceSpec {
    SurfaceSpec {
        grid: Grid::square(n, 1e-4).unwrap(),
        psd,
        normalization,
        amplitudes,
        seed,
    }
}

/// The radial PSD of the target spectrum itself, binned exactly like a measured one.
fn target_radial(s: &SurfaceSpec, prefactor: f64, bins: usize) -> RadialPsd {
    let g = s.grid;
    let fft = Fft2::new(g.nx, g.ny);
    let to_dft = (g.len() as f64).powi(2) * (2.0 * std::f64::consts::PI).powi(2) / g.area();
    let (nkx, ny) = fft.spectrum_shape();
    let spectrum = Array2::from_shape_fn((nkx, ny), |(kx, ky)| {
        let qx = 2.0 * std::f64::consts::PI * kx as f64 / g.length_x;
        let jy = if ky <= ny / 2 {
            ky as f64
        } else {
            ky as f64 - ny as f64
        };
        let qy = 2.0 * std::f64::consts::PI * jy / g.length_y;
        Complex64::new((prefactor * s.psd.shape(qx, qy) * to_dft).sqrt(), 0.0)
    });
    RadialPsd::from_spectrum(spectrum.view(), &g, bins)
}

fn measured_radial(h: &Array2<f64>, g: &Grid, bins: usize) -> RadialPsd {
    let spectrum = Fft2::new(g.nx, g.ny).forward(h.view());
    RadialPsd::from_spectrum(spectrum.view(), g, bins)
}

#[test]
fn exact_amplitudes_reproduce_the_target_psd_in_every_bin() {
    let psd = Psd::self_affine(0.8, 2.5e-5, 4e-6);
    for (n, seed) in [(128, 3), (90, 4)] {
        let s = spec(n, psd, Normalization::RmsHeight(1e-6), Amplitudes::Exact, seed);
        let surf = generate(&s).unwrap();
        let measured = measured_radial(&surf.heights, &s.grid, 10);
        let target = target_radial(&s, surf.prefactor, 10);
        assert_eq!(measured.q.len(), target.q.len());
        for (m, t) in measured.psd.iter().zip(&target.psd) {
            assert!(
                (m - t).abs() <= 1e-9 * t.max(1e-40) + 1e-40,
                "bin PSD {m} vs target {t}"
            );
        }
    }
}

#[test]
fn rayleigh_amplitudes_follow_the_target_psd_within_statistical_error() {
    let psd = Psd::self_affine(0.5, 2.5e-5, 4e-6);
    let seeds = 24;
    let mut sums: Vec<f64> = Vec::new();
    let mut sq: Vec<f64> = Vec::new();
    let mut target = None;
    for seed in 0..seeds {
        let s = spec(
            96,
            psd,
            Normalization::Prefactor(1e-30),
            Amplitudes::Rayleigh,
            seed,
        );
        let surf = generate(&s).unwrap();
        assert!((surf.prefactor / 1e-30 - 1.0).abs() < 1e-12);
        let m = measured_radial(&surf.heights, &s.grid, 8);
        if sums.is_empty() {
            sums = vec![0.0; m.psd.len()];
            sq = vec![0.0; m.psd.len()];
            target = Some(target_radial(&s, 1e-30, 8));
        }
        for (i, c) in m.psd.iter().enumerate() {
            sums[i] += c;
            sq[i] += c * c;
        }
    }
    let target = target.unwrap();
    let n = seeds as f64;
    let mut checked = 0;
    for i in 0..sums.len() {
        let mean = sums[i] / n;
        let t = target.psd[i];
        if t == 0.0 {
            // Beyond the cut-off only round-off remains (C ~ 1e-63 against 1e-30).
            assert!(
                mean < 1e-20 * target.psd[0],
                "bin {i} must be empty of roughness: {mean:e}"
            );
            continue;
        }
        let se = ((sq[i] / n - mean * mean) / (n - 1.0)).sqrt();
        assert!(
            (mean - t).abs() <= 4.0 * se,
            "bin {i}: mean {mean:e}, target {t:e}, standard error {se:e}"
        );
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} bins with roughness");
}

#[test]
fn requested_scale_is_met_to_1e_12() {
    let psd = Psd::self_affine(0.8, 2e-5, 2e-6);
    let rq = 0.76e-6;
    let s = spec(128, psd, Normalization::RmsHeight(rq), Amplitudes::Rayleigh, 11);
    let h = generate(&s).unwrap().heights;
    let mean = h.mean().unwrap();
    let measured = h.mapv(|v| (v - mean).powi(2)).mean().unwrap().sqrt();
    assert!((measured / rq - 1.0).abs() < 1e-12, "Rq {measured}");
    assert!(mean.abs() < 1e-12 * rq);

    let s = spec(128, psd, Normalization::RmsGradient(1.0), Amplitudes::Exact, 12);
    let g = generate(&s).unwrap();
    let st = statistics(g.heights.view(), &s.grid, true, None);
    assert!(
        (st.rms_gradient - 1.0).abs() < 1e-12,
        "gradient {}",
        st.rms_gradient
    );
    assert!((g.analysis.moments.rms_gradient() - 1.0).abs() < 1e-12);
    // The analysis that comes with the surface is that of its heights.
    let measured = surfgen::Analysis::new(g.heights.view(), &s.grid, 10);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * a.abs().max(b.abs());
    let (m, e) = (measured.moments, g.analysis.moments);
    assert!(close(m.m0, e.m0) && close(m.m2, e.m2) && close(m.m4, e.m4) && close(m.m4_xx, e.m4_xx));
    let (m, e) = (&measured.radial_psd, &g.analysis.radial_psd);
    assert_eq!(m.count, e.count);
    assert!(
        m.psd
            .iter()
            .zip(&e.psd)
            .all(|(a, b)| close(*a, *b) || a.max(*b) < 1e-20 * e.psd[0])
    );
    // Log-means compare where no bin straddles the cut-off (past it, round-off is not zero).
    let inside = (0..m.q.len()).filter(|&i| m.q[i] < 0.7 * s.psd.q_cutoff());
    assert!(
        inside
            .into_iter()
            .all(|i| (m.mean_ln_psd[i] - e.mean_ln_psd[i]).abs() < 1e-8)
    );

    let s = spec(
        128,
        psd,
        Normalization::PeakToValley(5.642e-6),
        Amplitudes::Exact,
        13,
    );
    let h = generate(&s).unwrap().heights;
    let pv = h.fold(f64::NEG_INFINITY, |a, &b| a.max(b)) - h.fold(f64::INFINITY, |a, &b| a.min(b));
    assert!((pv / 5.642e-6 - 1.0).abs() < 1e-12, "pv {pv}");
}

/// Mean squares of the finite-difference slope, Laplacian and h_xx predicted from the spectrum:
/// a forward difference multiplies each mode by `2 sin(q a / 2) / a` in magnitude, a 3-point
/// second difference by `(2 sin(q a / 2) / a)^2`.
fn filtered_moments(h: &Array2<f64>, g: &Grid) -> [f64; 3] {
    let spec = Fft2::new(g.nx, g.ny).forward(h.view());
    let (nkx, ny) = spec.dim();
    let mut s = [0.0; 3];
    for kx in 0..nkx {
        let w = if kx == 0 || (g.nx.is_multiple_of(2) && kx == g.nx / 2) {
            1.0
        } else {
            2.0
        };
        let sx = 2.0 * (std::f64::consts::PI * kx as f64 / g.nx as f64).sin() / g.dx();
        for ky in 0..ny {
            let sy = 2.0 * (std::f64::consts::PI * ky as f64 / ny as f64).sin() / g.dy();
            let p = w * spec[(kx, ky)].norm_sqr();
            s[0] += p * (sx * sx + sy * sy);
            s[1] += p * (sx * sx + sy * sy).powi(2);
            s[2] += p * sx.powi(4);
        }
    }
    s.map(|v| v / (g.len() as f64).powi(2))
}

#[test]
fn finite_differences_agree_with_spectral_slopes_only_when_resolved() {
    let n = 256;
    let a = 1e-4 / n as f64;
    let check = |cutoff_cells: f64| {
        let s = spec(
            n,
            Psd::self_affine(0.8, 2.5e-5, cutoff_cells * a),
            Normalization::RmsGradient(1.0),
            Amplitudes::Exact,
            5,
        );
        let h = generate(&s).unwrap().heights;
        let st = statistics(h.view(), &s.grid, true, None);
        // Both estimates are exact for what they measure: FD = the sinc-filtered spectrum.
        let [g2, lap2, xx2] = filtered_moments(&h, &s.grid);
        assert!((st.rms_gradient_fd / g2.sqrt() - 1.0).abs() < 1e-10);
        assert!((st.curvature_fd.laplacian / lap2.sqrt() - 1.0).abs() < 1e-10);
        assert!((st.curvature_fd.profile_x / xx2.sqrt() - 1.0).abs() < 1e-10);
        assert!(st.rms_gradient_fd <= st.rms_gradient);
        st
    };
    let resolved = check(32.0);
    assert!(
        (resolved.rms_gradient_fd / resolved.rms_gradient - 1.0).abs() < 0.005,
        "{resolved:?}"
    );
    assert!((resolved.curvature_fd.laplacian / resolved.curvature.laplacian - 1.0).abs() < 0.01);
    assert!((resolved.curvature_fd.profile_x / resolved.curvature.profile_x - 1.0).abs() < 0.01);
    // Cut off at the Nyquist wavelength: the shortest waves lose up to 1 - 2/pi of their
    // slope and 1 - 4/pi^2 of their curvature.
    let unresolved = check(2.0);
    assert!(
        unresolved.rms_gradient_fd < 0.95 * unresolved.rms_gradient,
        "{unresolved:?}"
    );
    assert!(
        unresolved.curvature_fd.laplacian < 0.8 * unresolved.curvature.laplacian,
        "{unresolved:?}"
    );
}

#[test]
fn hurst_fit_recovers_h() {
    for hurst in [0.3, 0.5, 0.8] {
        for (n, amplitudes, tolerance) in [(256, Amplitudes::Exact, 1e-3), (1024, Amplitudes::Rayleigh, 0.03)]
        {
            let s = spec(
                n,
                Psd::self_affine(hurst, 2.5e-5, 4.0 * 1e-4 / n as f64),
                Normalization::RmsHeight(1e-6),
                amplitudes,
                21,
            );
            let h = generate(&s).unwrap().heights;
            let st = statistics(h.view(), &s.grid, true, None);
            let fit = st.hurst_fit.expect("a fit");
            assert!(
                (fit - hurst).abs() < tolerance,
                "H = {hurst}, {amplitudes:?}: fitted {fit:?}"
            );
            // The explicit range [2 q_r, q_s / 2] works as well.
            let range = (2.0 * s.psd.q_rolloff(), 0.5 * s.psd.q_cutoff());
            let st = statistics(h.view(), &s.grid, true, Some(range));
            assert!((st.hurst_fit.unwrap() - hurst).abs() < tolerance);
        }
    }
}

#[test]
fn a_seed_fixes_the_surface_bit_for_bit_on_any_thread_count() {
    let s = spec(
        192,
        Psd::self_affine(0.7, 3e-5, 2e-6),
        Normalization::RmsGradient(0.5),
        Amplitudes::Rayleigh,
        42,
    );
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| generate(&s).unwrap().heights)
    };
    let one = run(1);
    let two = run(2);
    let three = run(3);
    assert!(
        one.iter()
            .zip(two.iter())
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
    assert!(
        one.iter()
            .zip(three.iter())
            .all(|(a, b)| a.to_bits() == b.to_bits())
    );
    let other = generate(&SurfaceSpec { seed: 43, ..s }).unwrap().heights;
    assert!(one.iter().zip(other.iter()).any(|(a, b)| a != b));
}

#[test]
fn anisotropic_surfaces_are_smoother_along_the_stretch() {
    let mut psd = Psd::self_affine(0.8, 2.5e-5, 4e-6);
    psd.anisotropy = surfgen::Anisotropy {
        ratio: 4.0,
        angle: 0.0,
    };
    let s = spec(256, psd, Normalization::RmsHeight(1e-6), Amplitudes::Exact, 8);
    let h = generate(&s).unwrap().heights;
    let a = s.grid.dx();
    let mean_sq = |dxn: usize, dyn_: usize| {
        let (ny, nx) = h.dim();
        let mut acc = 0.0;
        for y in 0..ny {
            for x in 0..nx {
                acc += (h[((y + dyn_) % ny, (x + dxn) % nx)] - h[(y, x)]).powi(2);
            }
        }
        (acc / (nx * ny) as f64).sqrt() / a
    };
    // Correlation is 4 times longer along x, so slopes along x are much smaller.
    assert!(
        mean_sq(1, 0) < 0.5 * mean_sq(0, 1),
        "{} vs {}",
        mean_sq(1, 0),
        mean_sq(0, 1)
    );
}

#[test]
fn bad_parameters_are_refused() {
    let psd = Psd::self_affine(0.8, 2e-5, 1e-7);
    // 1e-7 m is below two spacings of a 256^2 grid over 0.1 mm.
    assert!(
        generate(&spec(
            256,
            psd,
            Normalization::RmsHeight(1e-6),
            Amplitudes::Exact,
            1
        ))
        .is_err()
    );
    let psd = Psd::self_affine(0.8, 2e-5, 2e-6);
    assert!(
        generate(&spec(
            256,
            psd,
            Normalization::RmsHeight(-1.0),
            Amplitudes::Exact,
            1
        ))
        .is_err()
    );
    assert!(
        generate(&spec(
            256,
            psd,
            Normalization::RmsHeight(f64::NAN),
            Amplitudes::Exact,
            1
        ))
        .is_err()
    );
    let warned = generate(&spec(
        256,
        Psd::self_affine(0.8, 2e-4, 2e-6),
        Normalization::RmsHeight(1e-6),
        Amplitudes::Exact,
        1,
    ))
    .unwrap();
    assert!(warned.warnings.iter().any(|w| w.contains("longer than the box")));
}
