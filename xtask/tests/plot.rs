//! The figures' charts draw a point whose solve did not converge hollow, and count it.

use xtask::plot::{Chart, Curve, Mark, PALETTE};
use xtask::report::FigureReport;

/// The circles of radius `r` [px] filled with `fill` in an SVG.
fn circles(svg: &str, r: u32, fill: &str) -> usize {
    svg.split("<circle")
        .skip(1)
        .map(|c| &c[..c.find("/>").unwrap_or(c.len())])
        .filter(|c| c.contains(&format!("r=\"{r}\"")) && c.contains(&format!("fill=\"{fill}\"")))
        .count()
}

fn draw(curves: Vec<Curve>) -> (FigureReport, String) {
    let dir = std::env::temp_dir().join(format!("xtask-plot-{}-{}", std::process::id(), curves.len()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut chart = Chart::new("test", "x", "y");
    chart.curves = curves;
    let mut report = FigureReport::new(0, "test");
    report.save(&[chart], &dir, "chart").unwrap();
    let svg = std::fs::read_to_string(dir.join("chart.svg")).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    (report, svg)
}

#[test]
fn an_unconverged_point_is_drawn_hollow_and_counted() {
    let points = vec![
        (1.0, 1.0, true),
        (2.0, 3.0, false),
        (3.0, 2.0, true),
        (4.0, 5.0, true),
    ];
    let (report, svg) = draw(vec![
        Curve::solved("dots", points.clone(), Mark::Dots, PALETTE[0]),
        Curve::solved(
            "line",
            points.iter().map(|p| (p.0, p.1 + 1.0, p.2)).collect(),
            Mark::Line,
            PALETTE[1],
        ),
    ]);
    assert_eq!(report.unconverged_points, 2);
    // One hollow circle per unconverged point, white inside; three filled dots and the legend's.
    assert_eq!(circles(&svg, 5, "#FFFFFF"), 2);
    assert_eq!(circles(&svg, 4, "#1F77B4"), 4);
    assert!(svg.contains("hollow: not converged"));
}

#[test]
fn converged_points_are_never_hollow() {
    let (report, svg) = draw(vec![Curve::solved(
        "dots",
        vec![(1.0, 1.0, true), (2.0, 3.0, true)],
        Mark::Dots,
        PALETTE[0],
    )]);
    assert_eq!(report.unconverged_points, 0);
    assert_eq!(circles(&svg, 5, "#FFFFFF"), 0);
    assert!(!svg.contains("not converged"));
}
