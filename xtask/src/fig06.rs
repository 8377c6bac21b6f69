//! Fig. 6: load-approach of a smooth sphere at Tabor parameters 1, 2, 3: the loading and
//! unloading branches with their jumps, and the unstable middle of each S-curve, which the
//! paper could not trace, by prescribing the central gap.

use crate::{Context, FigureReport};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    crate::sphere::figure(ctx, 6, &[1.0, 2.0, 3.0], true)
}
