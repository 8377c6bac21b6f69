//! MPI ranks sharing a study's runs (feature `mpi`, under `mpirun -n K`): rank 0 hands out
//! the runs one at a time to whichever rank asks (its own included) and merges at the end; a
//! rank asks again when its run is done.

use super::{Outcome, Run, Study, execute};
use mpi::traits::*;
use std::path::Path;
use std::sync::mpsc;
use std::time::{Duration, Instant};

const ASK: i32 = 1;
const GIVE: i32 = 2;
/// The answer that there is nothing left.
const DONE: u64 = u64::MAX;

pub struct Ranks {
    _universe: mpi::environment::Universe,
    world: mpi::topology::SimpleCommunicator,
}

impl Ranks {
    /// MPI, when this process is one of several ranks (`None` alone: the study runs as
    /// on one machine).
    pub fn start() -> Option<Ranks> {
        let universe = mpi::initialize()?;
        let world = universe.world();
        (world.size() > 1).then_some(Ranks {
            _universe: universe,
            world,
        })
    }

    /// Runs `runs` across the ranks, `threads` threads each; whether this is rank 0 (which
    /// then merges).
    pub fn share(
        &self,
        study: &Study,
        runs: &[&Run],
        runs_dir: &Path,
        threads: usize,
        starts_until: Option<Instant>,
    ) -> bool {
        crate::set_quiet(true);
        let root = self.world.process_at_rank(0);
        if self.world.rank() != 0 {
            loop {
                root.send_with_tag(&0u64, ASK);
                let (k, _) = root.receive_with_tag::<u64>(GIVE);
                if k == DONE {
                    return false;
                }
                let run = runs[k as usize];
                if let Outcome::Failed(e) = execute(study, run, &runs_dir.join(&run.name), threads) {
                    crate::note_err(format_args!("run {} failed: {e}", run.name));
                }
            }
        }
        // Rank 0: its own runs on a thread that never calls MPI; this one answers the others.
        let mut next = 0usize;
        let mut hand_out = || {
            let k = next;
            next += 1;
            let late = starts_until.is_some_and(|t| Instant::now() >= t);
            (k < runs.len() && !late).then_some(k)
        };
        let (give, take) = mpsc::channel::<Option<usize>>();
        let (finished, done) = mpsc::channel::<()>();
        std::thread::scope(|s| {
            s.spawn(move || {
                while let Ok(Some(k)) = take.recv() {
                    let run = runs[k];
                    if let Outcome::Failed(e) = execute(study, run, &runs_dir.join(&run.name), threads) {
                        crate::note_err(format_args!("run {} failed: {e}", run.name));
                    }
                    if finished.send(()).is_err() {
                        break;
                    }
                }
            });
            let (mut busy, mut local_done, mut others) = (false, false, self.world.size() - 1);
            while others > 0 || !local_done || busy {
                let mut idle = true;
                if !busy && !local_done {
                    let k = hand_out();
                    local_done = k.is_none();
                    busy = k.is_some();
                    let _ = give.send(k);
                    idle = false;
                }
                if busy && done.try_recv().is_ok() {
                    busy = false;
                    idle = false;
                }
                if let Some(status) = self.world.any_process().immediate_probe_with_tag(ASK) {
                    let from = self.world.process_at_rank(status.source_rank());
                    let _ = from.receive_with_tag::<u64>(ASK);
                    let k = hand_out().map_or(DONE, |k| k as u64);
                    others -= usize::from(k == DONE) as i32;
                    from.send_with_tag(&k, GIVE);
                    idle = false;
                }
                if idle {
                    std::thread::sleep(Duration::from_millis(2));
                }
            }
        });
        crate::set_quiet(false);
        true
    }
}
