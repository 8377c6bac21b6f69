//! An observer stops a solve where it stands (a user's Ctrl-C): every method reports
//! `Termination::Interrupted` after the iteration it was asked at, not converged, and a sweep
//! ends after the step it interrupted.

mod common;

use common::*;
use ljadhesion::{LennardJones, NoAdhesion, PointLaw};
use solver::{
    AdhesiveState, ContactOptions, Control, Method, Observer, Settings, Start, SweepPoint, Termination,
};

/// Asks to stop once `after` iterations have been seen; counts the iterations and steps.
struct StopAfter {
    after: usize,
    seen: usize,
    steps: usize,
}

impl Observer for StopAfter {
    fn iteration(&mut self, _step: usize, _iteration: usize, _residual: f64) {
        self.seen += 1;
    }

    fn interrupted(&mut self) -> bool {
        self.seen >= self.after
    }

    fn step(&mut self, _index: usize, _point: &SweepPoint, _state: &AdhesiveState) -> bool {
        self.steps += 1;
        true
    }
}

fn stop_after(after: usize) -> StopAfter {
    StopAfter {
        after,
        seen: 0,
        steps: 0,
    }
}

#[test]
fn every_adhesive_method_stops_when_its_observer_asks() {
    pool().install(|| {
        let (op, g0, law, w0) = sphere_case(3.0, 32, 40.0);
        let point = PointLaw(LennardJones::new(w0, Z0).unwrap());
        for method in [
            Method::DualLoop,
            Method::Accelerated,
            Method::EnergyDescent,
            Method::Newton,
            Method::Flow,
        ] {
            let problem = if method == Method::EnergyDescent {
                problem(&op, &point, g0.view())
            } else {
                problem(&op, &law, g0.view())
            };
            let settings = Settings {
                tolerance: 1e-14,
                ..Settings::with_method(method)
            };
            let mut observer = stop_after(3);
            let (_, report) = problem
                .solve(Control::Approach(Z0), &settings, Start::Loading, &mut observer)
                .unwrap();
            assert_eq!(report.termination, Termination::Interrupted, "{method:?}");
            assert!(!report.converged(), "{method:?}");
            assert_eq!(
                observer.seen, 3,
                "{method:?}: the solve went on after it was asked to stop"
            );
        }
    });
}

#[test]
fn a_sweep_ends_after_the_step_it_interrupted() {
    pool().install(|| {
        let (op, g0, law, _) = sphere_case(3.0, 32, 40.0);
        let problem = problem(&op, &law, g0.view());
        let path = approaches([-2.0, -1.0, 0.0, 1.0].into_iter().map(|a| a * Z0));
        // Enough iterations for the first steps, not for all four.
        let mut full = stop_after(usize::MAX);
        let whole = problem
            .sweep(&path, None, &Settings::default(), None, &mut full)
            .unwrap();
        assert_eq!(whole.len(), 4);
        let mut observer = stop_after(full.seen / 2);
        let points = problem
            .sweep(&path, None, &Settings::default(), None, &mut observer)
            .unwrap();
        let last = points.last().unwrap();
        assert_eq!(last.report.termination, Termination::Interrupted);
        assert!(points.len() < 4 && observer.steps == points.len());
        assert_eq!(last.retries, 0, "an interrupted step is not retried");
        assert!(points[..points.len() - 1].iter().all(|p| p.report.converged()));
    });
}

#[test]
fn the_non_adhesive_solver_stops_when_its_observer_asks() {
    let (op, g0) = rough(64);
    let problem = problem(&op, &NoAdhesion, g0.view());
    let options = ContactOptions {
        tolerance: 1e-13,
        ..ContactOptions::default()
    };
    let mut observer = stop_after(4);
    let (_, report) = problem
        .solve_without_adhesion(Control::MeanPressure(1e6), &options, None, &mut observer)
        .unwrap();
    assert_eq!(report.termination, Termination::Interrupted);
    assert!(!report.converged());
    assert_eq!(observer.seen, 4);
}
