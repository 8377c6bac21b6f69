//! Fig. 5: load-approach of a smooth sphere at Tabor parameters 0.1, 0.2, 0.3 (DMT side, no
//! jumps), BEM against Greenwood's Lennard-Jones sphere.

use crate::{Context, FigureReport};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    crate::sphere::figure(ctx, 5, &[0.1, 0.2, 0.3], false)
}
