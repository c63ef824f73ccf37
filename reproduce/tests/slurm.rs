//! The cluster workflow on a real Slurm: the project's own `docs/slurm/driftbench.sbatch`
//! submitted as a 4-task job array to a private single-node cluster, one task requeued while
//! its slow run is in flight, the shards merged, and the merge equal to one process (every cell
//! but the timing columns, traces byte for byte).
//!
//! The cluster is this test's alone: its own munge key, socket and daemon, its own
//! `slurm.conf`, state and spool directories, all in a temporary directory; the daemons listen
//! on loopback at ports picked free at start, and the clients find the cluster through
//! `SLURM_CONF` set on each command (never in this process's environment). The daemons run in
//! the foreground as this test's children and are stopped by their ids when the [`Cluster`] is
//! dropped, also when the test panics, after the job is cancelled; nothing system-wide (no
//! systemctl, no /etc, no /run) is read or written. Slurm's own defaults that do not fit a
//! container are replaced: processes tracked through /proc (`proctrack/linuxproc`), no task
//! plugin, no cgroups, and more CPUs declared than the machine has (`config_overrides`), so
//! that the four tasks of 2 CPUs each run at once.
//!
//! What happens, in order: the sweep (`common::RESUME_EXPERIMENT`'s slow run and twelve quick
//! ones) is submitted with `sbatch --array=1-4 --cpus-per-task=2` and `--experiment`, as
//! docs/cluster.md says; once the task holding the slow run has checkpointed its quick runs,
//! `scontrol requeue` kills it and puts it back in the queue (Slurm holds a requeued job for
//! about two minutes, `Reason=BeginTime`; the test releases it at once with `scontrol update
//! StartTime=now`); the task runs again, says it is resuming, and finishes; `reproduce merge`
//! of the four shard directories is compared with `reproduce` run once over the sweep.
//!
//! Debian's `slurmctld`, `slurmd`, `slurm-client` and `munge` provide the daemons and clients
//! (`.ci/run` installs them). Where they are missing or the cluster does not come up, the test
//! says it is skipped, and why, and passes, except where `DRIFTBENCH_REQUIRE_SLURM` is set
//! (`.ci/run` sets it): there it fails, so CI cannot pass vacuously. About 20 s here (a
//! 2-core machine), well within the 3 minutes [`RUN_TIMEOUT`] and [`START_TIMEOUT`] allow.

use crate::common;

use common::{ok, reproduce};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The programs the cluster needs, by name (looked up on PATH and in the sbin directories,
/// which a non-root PATH may lack).
const PROGRAMS: [&str; 6] = [
    "munged",
    "slurmctld",
    "slurmd",
    "sbatch",
    "scontrol",
    "squeue",
];
/// Shards of the array.
const SHARDS: usize = 4;
/// CPUs per task (`--cpus-per-task`, hence `--threads`: the quick runs of the slow run's task
/// finish while the slow one is in flight).
const CPUS_PER_TASK: usize = 2;
/// The quick runs: kong2019's ZNN scheme swept over mu (the slow run is the experiment's first).
const QUICK_MU: [u32; 12] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];
/// The longest the cluster may take to come up, and the array to finish.
const START_TIMEOUT: Duration = Duration::from_secs(30);
const RUN_TIMEOUT: Duration = Duration::from_secs(150);

/// Where each program is, or the first one missing.
fn find_programs() -> Result<Vec<PathBuf>, String> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut dirs: Vec<PathBuf> = std::env::split_paths(&path).collect();
    dirs.extend(["/usr/sbin", "/sbin", "/usr/local/sbin"].map(PathBuf::from));
    PROGRAMS
        .iter()
        .map(|name| {
            dirs.iter()
                .map(|d| d.join(name))
                .find(|p| p.is_file())
                .ok_or_else(|| format!("`{name}` is not installed"))
        })
        .collect()
}

/// A private single-node Slurm cluster: munged, slurmctld and slurmd as children of this
/// process, configured under `dir`.
struct Cluster {
    dir: PathBuf,
    bin: Vec<PathBuf>,
    /// The daemons, in the order they were started.
    daemons: Vec<Child>,
    /// The job arrays submitted (cancelled before the daemons stop).
    jobs: Vec<String>,
}

impl Cluster {
    /// Writes the key and configuration under `dir` and starts the daemons; `Err` says why the
    /// cluster could not come up (what was started is stopped on drop).
    fn start(dir: &Path, bin: Vec<PathBuf>) -> Result<Self, String> {
        let mut c = Cluster {
            dir: dir.to_path_buf(),
            bin,
            daemons: Vec::new(),
            jobs: Vec::new(),
        };
        let munge = dir.join("munge");
        for d in ["munge", "state", "spool", "log"] {
            std::fs::create_dir_all(dir.join(d)).map_err(|e| e.to_string())?;
        }
        set_mode(&munge, 0o700)?;
        let key = munge.join("munge.key");
        let mut bytes = [0u8; 1024];
        std::fs::File::open("/dev/urandom")
            .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut bytes))
            .and_then(|()| std::fs::write(&key, bytes))
            .map_err(|e| format!("no munge key: {e}"))?;
        set_mode(&key, 0o400)?;
        let socket = munge.join("munge.socket");
        c.spawn(
            "munged",
            Command::new(&c.bin[0])
                .args(["--foreground", "--force"])
                .arg(format!("--key-file={}", key.display()))
                .arg(format!("--socket={}", socket.display()))
                .arg(format!("--pid-file={}", munge.join("munged.pid").display()))
                .arg(format!(
                    "--log-file={}",
                    dir.join("log/munged.log").display()
                ))
                .arg(format!(
                    "--seed-file={}",
                    munge.join("munged.seed").display()
                )),
        )?;
        c.wait_for("munged's socket", |_| socket.exists())?;

        let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map(|h| h.trim().to_string())
            .map_err(|e| format!("no host name: {e}"))?;
        let user = String::from_utf8_lossy(
            &Command::new("id")
                .arg("-un")
                .output()
                .map_err(|e| e.to_string())?
                .stdout,
        )
        .trim()
        .to_string();
        let (ctld_port, node_port) = (free_port()?, free_port()?);
        let d = dir.display();
        std::fs::write(dir.join("plugstack.conf"), "").map_err(|e| e.to_string())?;
        std::fs::write(
            c.conf(),
            format!(
                "ClusterName=driftbench-test
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={node_port}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/munge
AuthInfo=socket={socket}
CredType=cred/munge
StateSaveLocation={d}/state
SlurmdSpoolDir={d}/spool
SlurmctldPidFile={d}/slurmctld.pid
SlurmdPidFile={d}/slurmd.pid
SlurmctldLogFile={d}/log/slurmctld.log
SlurmdLogFile={d}/log/slurmd.log
PlugStackConfig={d}/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
KillWait=2
NodeName=driftbench-node NodeAddr=127.0.0.1 CPUs={cpus} RealMemory=4000 State=UNKNOWN
PartitionName=test Nodes=driftbench-node Default=YES MaxTime=INFINITE State=UP
",
                socket = socket.display(),
                cpus = SHARDS * CPUS_PER_TASK,
            ),
        )
        .map_err(|e| e.to_string())?;
        let conf = c.conf();
        c.spawn(
            "slurmctld",
            Command::new(&c.bin[1]).args(["-D", "-i", "-f"]).arg(&conf),
        )?;
        c.spawn(
            "slurmd",
            Command::new(&c.bin[2])
                .args(["-D", "-N", "driftbench-node", "-f"])
                .arg(&conf),
        )?;
        c.wait_for("the node to be idle", |c| {
            c.client("sinfo")
                .args(["-h", "-o", "%t"])
                .output()
                .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "idle")
        })?;
        Ok(c)
    }

    fn conf(&self) -> PathBuf {
        self.dir.join("slurm.conf")
    }

    /// Starts one daemon in the foreground, its output in `log/<name>.out`.
    fn spawn(&mut self, name: &str, cmd: &mut Command) -> Result<(), String> {
        let out = std::fs::File::create(self.dir.join(format!("log/{name}.out")))
            .map_err(|e| e.to_string())?;
        let err = out.try_clone().map_err(|e| e.to_string())?;
        let child = cmd
            .env("SLURM_CONF", self.conf())
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err)
            .spawn()
            .map_err(|e| format!("{name} does not start: {e}"))?;
        self.daemons.push(child);
        Ok(())
    }

    /// Waits until `ready()` or a daemon exits or [`START_TIMEOUT`] passes (then `Err`, with
    /// the daemons' logs).
    fn wait_for(&mut self, what: &str, ready: impl Fn(&Self) -> bool) -> Result<(), String> {
        let started = Instant::now();
        while !ready(self) {
            let exited = self
                .daemons
                .iter_mut()
                .any(|d| !matches!(d.try_wait(), Ok(None)));
            if exited || started.elapsed() > START_TIMEOUT {
                return Err(format!(
                    "waited {:.0} s for {what}{}:\n{}",
                    started.elapsed().as_secs_f64(),
                    if exited { ", but a daemon exited" } else { "" },
                    self.logs()
                ));
            }
            std::thread::sleep(Duration::from_millis(200));
        }
        Ok(())
    }

    /// A Slurm client (`sbatch`, `scontrol`, ...) of this cluster.
    fn client(&self, name: &str) -> Command {
        let dir = self.bin[3].parent().expect("sbatch is in a directory");
        let mut c = Command::new(dir.join(name));
        c.env("SLURM_CONF", self.conf());
        c
    }

    /// The ends of the daemons' logs, for a failure message.
    fn logs(&self) -> String {
        let mut out = String::new();
        for name in [
            "munged.log",
            "slurmctld.log",
            "slurmd.log",
            "munged.out",
            "slurmctld.out",
            "slurmd.out",
        ] {
            let text = std::fs::read_to_string(self.dir.join("log").join(name)).unwrap_or_default();
            let tail: Vec<&str> = text.lines().rev().take(15).collect();
            out.push_str(&format!("--- log/{name}\n"));
            for l in tail.iter().rev() {
                out.push_str(l);
                out.push('\n');
            }
        }
        out
    }

    /// `scontrol <args>`, which must succeed.
    fn scontrol(&self, args: &[&str]) {
        let o = self.client("scontrol").args(args).output().unwrap();
        assert!(
            o.status.success(),
            "scontrol {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&o.stderr)
        );
    }

    /// The state of array task `task` (`PENDING BeginTime`, `RUNNING None`, ...; empty once it
    /// has left the queue).
    fn state(&self, task: &str) -> String {
        let o = self
            .client("squeue")
            .args(["-h", "-o", "%T %r", "-j", task])
            .output()
            .unwrap();
        String::from_utf8_lossy(&o.stdout).trim().to_string()
    }
}

impl Drop for Cluster {
    /// Cancels the jobs (their processes are slurmd's, not ours), gives them a moment to end,
    /// then stops the daemons, last started first.
    fn drop(&mut self) {
        for job in &self.jobs {
            let _ = self.client("scancel").arg(job).output();
        }
        let started = Instant::now();
        while self.jobs.iter().any(|j| !self.state(j).is_empty())
            && started.elapsed() < Duration::from_secs(10)
        {
            std::thread::sleep(Duration::from_millis(200));
        }
        for d in self.daemons.iter_mut().rev() {
            let _ = d.kill();
            let _ = d.wait();
        }
    }
}

fn set_mode(path: &Path, mode: u32) -> Result<(), String> {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).map_err(|e| e.to_string())
}

/// A loopback TCP port free at this moment.
fn free_port() -> Result<u16, String> {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .map_err(|e| format!("no free loopback port: {e}"))
}

/// The experiment file: the slow run, then the quick sweep.
fn sweep_experiment() -> String {
    let mu: Vec<String> = QUICK_MU.iter().map(u32::to_string).collect();
    format!(
        r#"{}[[experiment.variant]]
label = "ZNN"
exact = false
scheme = {{ kind = "kong2019-znn", k_p = 1.0 }}
solvers = [{{ kind = "znn", gamma = 1.0 }}]
sweep = {{ "scheme.mu" = [{}] }}
"#,
        common::RESUME_EXPERIMENT,
        mu.join(", ")
    )
}

/// The shard of the slow run, and how many quick runs it holds.
fn slow_shard(root: &Path) -> (usize, usize) {
    let files = reproduce::load_experiments(&root.join("experiments")).unwrap();
    let keys: Vec<String> = files
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .map(|j| j.key().to_string())
        .collect();
    assert_eq!(keys.len(), 1 + QUICK_MU.len());
    // Run i of the selection is shard i mod N + 1's (store::shard).
    let shard = store::shard::Shard::of_index(0, SHARDS);
    let quick = (1..keys.len())
        .filter(|&i| store::shard::Shard::of_index(i, SHARDS) == shard)
        .count();
    assert!(
        quick > 0,
        "the slow run's shard {shard}/{SHARDS} has no quick run to checkpoint: change QUICK_MU"
    );
    (shard, quick)
}

/// Rows in the journal of shard directory `dir` (after its header).
fn journal_rows(dir: &Path) -> usize {
    std::fs::read_to_string(store::journal::path(dir))
        .map(|t| t.lines().count().saturating_sub(1))
        .unwrap_or(0)
}

fn shard_dir(root: &Path, k: usize) -> PathBuf {
    root.join(format!("results-shard-{k}-of-{SHARDS}"))
}

#[test]
fn a_slurm_array_with_a_requeued_task_merges_equal_to_one_process() {
    let required = std::env::var_os("DRIFTBENCH_REQUIRE_SLURM").is_some();
    let skip = |why: String| {
        assert!(!required, "DRIFTBENCH_REQUIRE_SLURM is set, but {why}");
        eprintln!(
            "skipped: {why} (Debian: apt-get install slurmctld slurmd slurm-client munge; .ci/run installs them)"
        );
    };
    let bin = match find_programs() {
        Ok(bin) => bin,
        Err(why) => return skip(why),
    };
    let base = inputs::Scratch::unmade("slurm");
    let (root, cluster_dir) = (base.join("project"), base.join("cluster"));
    std::fs::create_dir_all(root.join("experiments")).unwrap();
    std::fs::write(root.join("experiments/kong2019.toml"), sweep_experiment()).unwrap();
    let (slow, quick) = slow_shard(&root);
    let started = Instant::now();
    let mut cluster = match Cluster::start(&cluster_dir, bin) {
        Ok(c) => c,
        Err(why) => return skip(format!("the private Slurm cluster did not come up: {why}")),
    };
    eprintln!("cluster up in {:.1} s", started.elapsed().as_secs_f64());

    let template = common::repo_root().join("docs/slurm/driftbench.sbatch");
    let out: Output = cluster
        .client("sbatch")
        .current_dir(&root)
        .env("DRIFTBENCH_BIN", env!("CARGO_BIN_EXE_reproduce"))
        .env("DRIFTBENCH_ROOT", &root)
        .arg("--parsable")
        .arg(format!("--array=1-{SHARDS}"))
        .arg(format!("--cpus-per-task={CPUS_PER_TASK}"))
        .arg(&template)
        .args(["--experiment", "kong2019-resume"])
        .output()
        .unwrap();
    let jid = String::from_utf8_lossy(&ok(out).stdout).trim().to_string();
    cluster.jobs.push(jid.clone());
    let task = format!("{jid}_{slow}");

    // Requeue the slow run's task once its quick runs are checkpointed (the slow one in flight).
    let dir = shard_dir(&root, slow);
    while journal_rows(&dir) < quick {
        assert!(
            started.elapsed() < RUN_TIMEOUT,
            "task {task} checkpointed {} of its {quick} quick runs:\n{}",
            journal_rows(&dir),
            cluster.logs()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(
        !dir.join("shard.toml").exists(),
        "task {task} finished before it could be requeued"
    );
    cluster.scontrol(&["requeue", &task]);
    eprintln!(
        "requeued {task} after {:.1} s",
        started.elapsed().as_secs_f64()
    );

    // Slurm holds a requeued job (BeginTime, ~2 minutes): release it, then wait for the array.
    let mut released = false;
    loop {
        let state = cluster.state(&jid);
        if state.is_empty() {
            break;
        }
        if !released && cluster.state(&task).starts_with("PENDING") {
            cluster.scontrol(&["update", &format!("JobId={task}"), "StartTime=now"]);
            released = true;
        }
        assert!(
            started.elapsed() < RUN_TIMEOUT,
            "the array is not done after {RUN_TIMEOUT:?}: {state}\n{}",
            cluster.logs()
        );
        std::thread::sleep(Duration::from_millis(200));
    }
    assert!(
        released,
        "task {task} was never seen pending after its requeue"
    );
    eprintln!("array done after {:.1} s", started.elapsed().as_secs_f64());
    drop(cluster);

    let log = std::fs::read_to_string(root.join(format!("driftbench-{jid}_{slow}.out")))
        .unwrap_or_default();
    assert!(
        log.contains(&format!(
            "resuming: {quick} of the selected runs already done"
        )),
        "the requeued task did not resume its {quick} checkpointed runs:\n{log}"
    );
    // Both attempts in the task's output (the template appends: --open-mode=append).
    assert_eq!(
        log.matches(&format!("shard {slow}/{SHARDS}:")).count(),
        2,
        "{log}"
    );
    let dirs: Vec<PathBuf> = (1..=SHARDS).map(|k| shard_dir(&root, k)).collect();
    for (k, d) in dirs.iter().enumerate() {
        let log = std::fs::read_to_string(root.join(format!("driftbench-{jid}_{}.out", k + 1)))
            .unwrap_or_default();
        assert!(
            d.join("shard.toml").exists(),
            "shard {} unfinished:\n{log}",
            k + 1
        );
    }

    let merged = root.join("merged");
    ok(reproduce()
        .current_dir(&root)
        .arg("merge")
        .args(&dirs)
        .arg("--results-dir")
        .arg(&merged)
        .output()
        .unwrap());
    let whole = root.join("whole");
    ok(reproduce()
        .current_dir(&root)
        .args([
            "--experiment",
            "kong2019-resume",
            "--skip-explain",
            "--results-dir",
        ])
        .arg(&whole)
        .output()
        .unwrap());
    common::assert_same_results(&merged, &whole, 1 + QUICK_MU.len());
    eprintln!(
        "merged and compared after {:.1} s",
        started.elapsed().as_secs_f64()
    );
}
