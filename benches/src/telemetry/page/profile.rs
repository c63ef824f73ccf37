//! Where the time goes: the sampling profiles of each paper's reproduction
//! (`benches/results/profile.csv`, [`crate::telemetry::profile`]) and of the hot-started
//! active-set solve (`benches/results/profile-active-set.csv`,
//! [`crate::telemetry::profile_active_set`]). What is computed from them is
//! [`crate::telemetry::judged::profile`]'s; this module formats.

use crate::telemetry::judged::profile::{matlab_over_simulation, rhs_dominates};
use crate::telemetry::profile::ProfileRow;
use crate::telemetry::profile_active_set::HotSolveRow;
use analysis::papers::Papers;
use analysis::performance::whole_runs::TARGET_SIMULATION_SPEEDUP;
use presentation::report::markdown::{percent, sci, Table, MISSING};

/// Where each profiled paper's reproduction spends its time, from `benches/results/profile.csv`
/// ([`crate::telemetry::profile`]): the method once, then per paper (in file order) every part and
/// category with its share and CPU time per pass, the simulation's ratio to its floor (RHS,
/// Jacobian and LU work) and, for a paper that publishes compute times, the MATLAB times over
/// the simulation's CPU time.
pub fn where_time_goes(profile: &[ProfileRow], papers: &Papers) -> String {
    let Some(first) = profile.first() else {
        return format!(
            "### Where the time goes\n\n`benches/results/{}` is absent: `benches/profile/paper.sh PAPER` \
             (perf over the release binary) measures it.\n\n",
            crate::telemetry::profile::FILE
        );
    };
    let profiled = records::table::distinct(profile, |r| &r.paper);
    let mut out = format!(
        "### Where the time goes\n\nA sampling profile of `reproduce --paper PAPER \
         --skip-explain --threads 1 --dry-run` for each of {}, {} passes pinned to one CPU at {} \
         Hz, revision `{}` (`benches/profile/paper.sh {}` writes `benches/results/{}`; perf with call \
         graphs over the `profiling` build's debug info (release optimisation), each sample sorted by the innermost frame \
         that names a category). The *simulation* is the network runs' integration (diffsol's \
         BDF around the arm and the network); the *exact column* integrates the exact optimum; \
         the *observer* scores every accepted step against the exact optimum and keeps metrics \
         and the trace; *other* is start-up, the experiment files and output. The floor is the \
         work the runs' counts require: RHS evaluations (network and QP assembly), network \
         Jacobians, LU factorisations and solves of the Newton matrix.\n\n",
        profiled.join(", "),
        first.passes,
        first.frequency_hz,
        first.git_rev,
        profiled.join(" "),
        crate::telemetry::profile::FILE,
    );
    let timed = papers.timed_papers();
    for paper in profiled {
        let rows = crate::telemetry::profile::of_paper(profile, paper);
        out.push_str(&paper_profile(&rows, timed.contains(&paper), papers));
    }
    out
}

/// One paper's profile table and what it says (`timed`: the paper publishes compute times).
fn paper_profile(profile: &[ProfileRow], timed: bool, papers: &Papers) -> String {
    let mut t = Table::new([
        "part",
        "category",
        "floor",
        "share of the process",
        "share of the simulation",
        "CPU ms per pass",
    ]);
    for r in profile {
        t.push([
            r.part.clone(),
            r.category.clone(),
            if r.in_floor() { "yes" } else { "no" }.to_string(),
            percent(r.share_of_process, 1),
            r.share_of_simulation
                .map_or(MISSING.to_string(), |v| percent(v, 1)),
            format!("{:.1}", r.ms_per_pass),
        ]);
    }
    let ratio = crate::telemetry::profile::floor_ratio(profile)
        .map_or(MISSING.to_string(), |v| format!("{v:.2}"));
    let mut said = String::new();
    if let Some(m) = matlab_over_simulation(profile, papers).filter(|_| timed) {
        said.push_str(&format!(
            " Over the {} runs the papers time, together, the MATLAB times ({} s) are {} times \
             the simulation's CPU time per pass ({} s); the target of {}x applies to each run's \
             simulation.",
            m.runs,
            sci(m.matlab_s),
            sci(m.ratio),
            sci(m.simulation_s),
            TARGET_SIMULATION_SPEEDUP
        ));
    }
    if timed && rhs_dominates(profile) {
        said.push_str(
            " The RHS is the larger part of it: VP-RNN-PF's RHS forms and solves its (nx + n_eq) \
             system W at every evaluation, several times LVI-PDNN's RHS, so a floor priced at \
             LVI-PDNN's per-call cost understates it.",
        );
    }
    format!(
        "#### {}\n\n{}\nThe simulation takes {ratio} times its floor (the target: within 2).\
         {said}\n\n",
        profile[0].paper,
        t.render()
    )
}

/// Where the hot solve's time goes (`benches/results/profile-active-set.csv`,
/// [`crate::telemetry::profile_active_set`]), and what the solve without its certification would cost
/// in RHS evaluations (`ratio` × the share outside certification).
pub fn hot_solve_profile(hot: &[HotSolveRow], ratio: f64, network: &str) -> String {
    let Some(first) = hot.first() else {
        return format!(
            "`benches/results/{}` is absent: `benches/profile/active_set.sh` (perf over the bench) \
             measures where the hot solve's time goes.\n\n",
            crate::telemetry::profile_active_set::FILE
        );
    };
    let mut t = Table::new(["category", "share of the hot solve"]);
    for r in hot {
        t.push([r.category.clone(), percent(r.share, 1)]);
    }
    let without =
        crate::telemetry::profile_active_set::certification_share(hot).map_or(String::new(), |c| {
            format!(
                " The certification (every answer's KKT residuals, so that the exact column is \
                 exact by proof, not by trust) takes {} of it: the rest would take {} times \
                 one {network} RHS evaluation.",
                percent(c, 1),
                sci(analysis::performance::instant::uncertified_over_rhs(
                    ratio, c
                ))
            )
        });
    format!(
        "Where the hot solve's time goes: a sampling profile of the criterion bench `{}` ({} s \
         at {} Hz, one pinned CPU, revision `{}`; \
         `benches/profile/active_set.sh` writes `benches/results/{}`), each sample by the function it \
         was in, the bench harness left out.{without}\n\n{}\n",
        first.bench,
        first.seconds,
        first.frequency_hz,
        first.git_rev,
        crate::telemetry::profile_active_set::FILE,
        t.render()
    )
}
