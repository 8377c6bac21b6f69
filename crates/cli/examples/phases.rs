use std::time::Instant;
use surfgen::*;
fn main() {
    let grid = Grid::square(4096, 1e-4).unwrap();
    let spec = SurfaceSpec {
        grid,
        psd: Psd::self_affine(0.8, 2e-5, 4.0 * grid.dx()),
        normalization: Normalization::RmsGradient(1.0),
        amplitudes: Amplitudes::Exact,
        seed: 0,
    };
    let t = Instant::now();
    let g = generate(&spec).unwrap();
    println!("generate {:?}", t.elapsed());
    let t = Instant::now();
    let a = g.analysis.clone();
    println!("analysis {:?}", t.elapsed());
    let t = Instant::now();
    let _s = surfgen::stats::statistics_with(g.heights.view(), &a, true, None);
    println!("rest of stats {:?}", t.elapsed());
    let s = Surface::new(g.heights, grid, true).unwrap();
    let t = Instant::now();
    io::write(&s, std::path::Path::new("/tmp/rc/x.npy"), None).unwrap();
    println!("write {:?}", t.elapsed());
}
