//! The problem as a library object: the builder against the geometry it is made of, its
//! refusals, the automatic method, and layouts.

use elastic::{Domain, Free};
use ljadhesion::{DugdaleLaw, ExponentialLaw, LennardJones, LineLaw, NoAdhesion, PointLaw, SurfaceLaw};
use ndarray::{Array2, ShapeBuilder};
use solver::geometry::{SphereProfile, sphere};
use solver::{ContactProblem, Control, Method, Settings, SolverError, Start};

const Z0: f64 = 1e-9;

fn lj() -> LennardJones {
    LennardJones::new(0.05, Z0).unwrap()
}

#[test]
fn the_builder_makes_the_problem_of_its_parts() {
    let (n, side, radius) = (32, 2e-7, 1e-6);
    let heights = Array2::from_shape_fn((n, n), |(j, i)| 1e-10 * ((i * 7 + j * 3) % 5) as f64);
    let built = ContactProblem::builder()
        .roughness(heights.clone(), side, side)
        .sphere(radius)
        .modulus(1e9)
        .law(SurfaceLaw(lj()))
        .build()
        .unwrap();
    let domain = Domain {
        nx: n,
        ny: n,
        dx: side / n as f64,
        dy: side / n as f64,
        periodic: false,
    };
    assert_eq!(built.domain(), domain);
    assert_eq!(built.e_star(), 1e9);
    let g0 = sphere(&domain, radius, SphereProfile::Paraboloid, Some(heights.view())).unwrap();
    assert_eq!(built.initial_gap, g0);
    // The box's edge stands at a gap of 4.7 z0: the attraction beyond it is cut off, warned.
    assert!(
        built.warnings.iter().any(|w| w.contains("grid's edge")),
        "{:?}",
        built.warnings
    );
    // The same from parts.
    let parts = ContactProblem::new(Free::new(domain, 1e9).unwrap(), g0, SurfaceLaw(lj())).unwrap();
    assert_eq!(parts.warnings, built.warnings);
}

#[test]
fn the_builder_refuses_what_is_missing_or_inconsistent() {
    let base = || ContactProblem::builder().grid(16, 16, 1e-7, 1e-7);
    let missing = base().sphere(1e-6).build().unwrap_err();
    assert!(matches!(missing, SolverError::Incomplete(what) if what.contains("modulus")));
    let nothing = base().modulus(1e9).build().unwrap_err();
    assert!(matches!(nothing, SolverError::Incomplete(_)), "{nothing}");
    let bad = base().modulus(f64::NAN).sphere(1e-6).build().unwrap_err();
    assert!(bad.to_string().contains("modulus"), "{bad}");
    let wave = base()
        .modulus(1e9)
        .wave(1e-8)
        .periodic(false)
        .build()
        .unwrap_err();
    assert!(matches!(wave, SolverError::Unsupported(_)), "{wave}");
    let shape = ContactProblem::builder()
        .roughness(Array2::zeros((8, 16)), 1e-7, 1e-7)
        .grid(16, 16, 1e-7, 1e-7)
        .modulus(1e9)
        .build()
        .unwrap_err();
    assert!(matches!(shape, SolverError::ShapeMismatch { .. }), "{shape}");
    let length = base().grid(16, 16, -1.0, 1e-7).modulus(1e9).sphere(1e-6).build();
    assert!(length.is_err());
}

#[test]
fn auto_takes_the_tested_method_for_each_law_and_control() {
    let approach = Control::Approach(0.0);
    let load = Control::MeanPressure(0.0);
    let cases: [(&dyn ljadhesion::AdhesionLaw, Control, Method); 10] = [
        (&PointLaw(lj()), approach, Method::EnergyDescent),
        (
            &ExponentialLaw::new(0.05, Z0).unwrap(),
            approach,
            Method::EnergyDescent,
        ),
        (&SurfaceLaw(lj()), approach, Method::Newton),
        (&LineLaw(lj()), approach, Method::Newton),
        (&DugdaleLaw::equivalent_to(&lj()), approach, Method::Accelerated),
        (&NoAdhesion, approach, Method::Accelerated),
        (&SurfaceLaw(lj()), load, Method::Flow),
        (&LineLaw(lj()), load, Method::Flow),
        (&PointLaw(lj()), load, Method::Accelerated),
        (&PointLaw(lj()), Control::CentralGap(Z0), Method::Accelerated),
    ];
    // Cells of 1 nm on a half-space of 1 GPa, about as stiff as the law at its stiffest (w0 =
    // 50 mJ/m^2, z0 = 1 nm), and 30 times coarser ones.
    let e_star = 1e9;
    let grid = |dx: f64, periodic: bool| Domain {
        nx: 64,
        ny: 64,
        dx,
        dy: dx,
        periodic,
    };
    let fine = grid(1e-9, true);
    let cell_stiffness = 1.0 / fine.cell_compliance(e_star);
    assert!(
        ljadhesion::AdhesionLaw::stiffness_bound(&SurfaceLaw(lj())) < Method::FLOW_ABOVE * cell_stiffness
    );
    for (law, control, expected) in cases {
        assert_eq!(
            Method::Auto.resolve(
                law,
                control,
                &fine,
                fine.cell_compliance(e_star),
                &Default::default()
            ),
            expected,
            "{} {control:?}",
            law.name()
        );
        // A chosen method stays chosen.
        assert_eq!(
            Method::DualLoop.resolve(
                law,
                control,
                &fine,
                fine.cell_compliance(e_star),
                &Default::default()
            ),
            Method::DualLoop
        );
        // Loads on free domains: the flow takes the approach only there.
        if expected == Method::Flow {
            let free = grid(1e-9, false);
            assert_eq!(
                Method::Auto.resolve(
                    law,
                    control,
                    &free,
                    free.cell_compliance(e_star),
                    &Default::default()
                ),
                Method::Accelerated
            );
        }
        // On cells coarser than the process zone by far, where each holds on or lets go alone,
        // the flow takes the approach for the laws Newton takes on fine cells.
        if expected == Method::Newton {
            for periodic in [true, false] {
                let coarse = grid(3e-8, periodic);
                assert_eq!(
                    Method::Auto.resolve(
                        law,
                        control,
                        &coarse,
                        coarse.cell_compliance(e_star),
                        &Default::default()
                    ),
                    Method::Flow
                );
            }
        }
    }
    for &m in Method::ALL {
        assert_eq!(m.name().parse::<Method>(), Ok(m));
    }
}

#[test]
fn any_layout_of_the_initial_gap_gives_the_same_solution() {
    let n = 24;
    let problem = ContactProblem::builder()
        .grid(n, n, 1.2e-7, 1.2e-7)
        .sphere(1e-6)
        .modulus(1e9)
        .law(PointLaw(LennardJones::new(0.02, Z0).unwrap()))
        .build()
        .unwrap();
    // The same gap stored column by column.
    let mut fortran = Array2::zeros((n, n).f());
    fortran.assign(&problem.initial_gap);
    assert!(!fortran.is_standard_layout());
    let transposed = ContactProblem {
        initial_gap: fortran,
        ..problem.clone()
    };
    for method in [Method::EnergyDescent, Method::Newton, Method::Accelerated] {
        let settings = Settings::with_method(method);
        let control = Control::Approach(0.5 * Z0);
        let (a, ra) = problem
            .solve(control, &settings, Start::Loading, &mut ())
            .unwrap();
        let (b, rb) = transposed
            .solve(control, &settings, Start::Loading, &mut ())
            .unwrap();
        assert!(ra.converged() && rb.converged(), "{method}");
        assert_eq!(ra.load, rb.load, "{method}");
        assert_eq!(a, b, "{method}");
        // And a warm start stored column by column.
        let mut warm = a.clone();
        warm.contact.gap = {
            let mut f = Array2::zeros((n, n).f());
            f.assign(&a.contact.gap);
            f
        };
        let (c, _) = problem
            .solve(control, &settings, Start::Warm(&warm), &mut ())
            .unwrap();
        assert!((c.contact.gap.sum() - a.contact.gap.sum()).abs() < 1e-6 * Z0 * (n * n) as f64);
    }
}
