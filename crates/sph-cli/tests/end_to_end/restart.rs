//! Nothing lost when a run is stopped: SIGINT/SIGTERM leave a last snapshot and a
//! restart file, `--restart` continues bit for bit, and a killed run leaves only
//! complete snapshots.

use crate::common::{cli, cli_within, scratch, small_case};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A dam break at Δx = 0.03 m (800 fluid particles) long enough to be interrupted.
fn long_case(dir: &Path, end: f64) -> String {
    let case = small_case(dir, "");
    let text = std::fs::read_to_string(&case)
        .unwrap()
        .replace("spacing = 0.05 ", "spacing = 0.03 ")
        .replace("end = 0.05", &format!("end = {end}"));
    std::fs::write(&case, text).unwrap();
    case
}

fn spawn(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sph-cli starts")
}

/// Waits (at most a minute) until `file` exists.
fn wait_for(file: &Path) {
    let start = Instant::now();
    while !file.exists() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{file:?} never came"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn send(child: &Child, signal: &str) {
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

/// The snapshot files of a run folder, in order.
fn snapshots(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            name.starts_with("particles_") && name.ends_with(".h5")
        })
        .collect();
    files.sort();
    files
}

/// Asserts that the binary succeeded (showing its error otherwise).
fn succeeded(out: std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The simulated time of a snapshot.
fn snapshot_time(file: &Path) -> f64 {
    let h5 = hdf5::File::open(file).unwrap();
    h5.attr("time").unwrap().read_scalar().unwrap()
}

fn dataset(file: &hdf5::File, name: &str) -> Vec<f64> {
    file.dataset(name).unwrap().read_raw().unwrap()
}

/// Asserts that two snapshots hold the same state, bit for bit.
fn assert_same_state(a: &Path, b: &Path) {
    let (fa, fb) = (hdf5::File::open(a).unwrap(), hdf5::File::open(b).unwrap());
    assert_eq!(snapshot_time(a).to_bits(), snapshot_time(b).to_bits());
    for name in ["position", "velocity", "density", "pressure"] {
        let (va, vb) = (dataset(&fa, name), dataset(&fb, name));
        assert_eq!(va.len(), vb.len(), "{name}");
        let differ = va
            .iter()
            .zip(&vb)
            .filter(|(x, y)| x.to_bits() != y.to_bits());
        assert_eq!(differ.count(), 0, "{name} differs between {a:?} and {b:?}");
    }
    let ids = |f: &hdf5::File| -> Vec<u32> { f.dataset("id").unwrap().read_raw().unwrap() };
    assert_eq!(ids(&fa), ids(&fb));
}

#[test]
fn a_run_stopped_by_sigterm_continues_bit_for_bit() {
    let dir = scratch("restart");
    let case = long_case(&dir, 1.0);
    let (whole, parts) = (dir.join("whole"), dir.join("parts"));
    let out = cli(&["run", &case, "--out", whole.to_str().unwrap(), "--quiet"]);
    succeeded(out);

    let child = spawn(&["run", &case, "--out", parts.to_str().unwrap(), "--quiet"]);
    wait_for(&parts.join("particles_000003.h5"));
    send(&child, "-TERM");
    let stopped = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&stopped.stderr);
    assert_eq!(stopped.status.code(), Some(143), "{err}");
    assert!(
        err.starts_with("error: interrupted by SIGTERM at t = "),
        "{err}"
    );
    let restart = parts.join("restart.h5");
    assert!(
        err.contains(&format!("--restart {}", restart.display())),
        "{err}"
    );
    let last = snapshots(&parts).pop().unwrap();
    let stopped_at: f64 = snapshot_time(&last);
    assert!(
        stopped_at < 1.0,
        "the signal came after the end ({stopped_at} s)"
    );

    let resumed = cli_within(
        &["run", "--restart", restart.to_str().unwrap(), "--quiet"],
        Duration::from_secs(60),
    );
    succeeded(resumed);
    assert_same_state(
        snapshots(&whole).last().unwrap(),
        snapshots(&parts).last().unwrap(),
    );
    // The time series carries on where it stopped: the same rows as the whole run.
    let rows = |d: &Path| std::fs::read_to_string(d.join("timeseries.csv")).unwrap();
    assert_eq!(rows(&whole).lines().count(), rows(&parts).lines().count());
    // Every snapshot of both legs is in the index.
    let xmf = std::fs::read_to_string(parts.join("particles.xmf")).unwrap();
    assert_eq!(xmf.matches("<Time ").count(), snapshots(&parts).len());
}

#[test]
fn a_finished_run_extends_with_until_and_never_overwrites_later_output() {
    let dir = scratch("extend");
    let case = long_case(&dir, 0.1);
    let run = dir.join("run");
    let out = cli(&["run", &case, "--out", run.to_str().unwrap(), "--quiet"]);
    succeeded(out);
    let restart = run.join("restart.h5");
    let kept = dir.join("restart_at_0.1.h5");
    std::fs::copy(&restart, &kept).unwrap();
    let n_before = snapshots(&run).len();

    let early = cli(&[
        "run",
        "--restart",
        kept.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "--until",
        "0.05",
    ]);
    assert_eq!(early.status.code(), Some(2));
    let err = String::from_utf8_lossy(&early.stderr);
    assert!(
        err.starts_with("error: time.end = 0.05: expected a time after the restart time"),
        "{err}"
    );

    let more = cli(&[
        "run",
        "--restart",
        restart.to_str().unwrap(),
        "--until",
        "0.2",
        "--quiet",
    ]);
    succeeded(more);
    let files = snapshots(&run);
    assert!(files.len() > n_before);
    let t_end = snapshot_time(files.last().unwrap());
    assert!((t_end - 0.2).abs() < 1e-12, "{t_end}");

    // The copy from t = 0.1 would write over the snapshots after it: refused ...
    let stale = cli(&[
        "run",
        "--restart",
        kept.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(stale.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&stale.stderr).contains("--force"));
    assert_eq!(snapshots(&run), files);
    // ... unless forced, which replaces them and drops the later time-series rows.
    let forced = cli(&[
        "run",
        "--restart",
        kept.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "--force",
        "--quiet",
        "--until",
        "0.15",
    ]);
    succeeded(forced);
    let series = std::fs::read_to_string(run.join("timeseries.csv")).unwrap();
    let times: Vec<f64> = series
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(
        times.windows(2).all(|w| w[1] > w[0]),
        "rows in time order, none repeated"
    );
    assert!((times.last().unwrap() - 0.15).abs() < 1e-9);
}

#[test]
fn a_killed_run_leaves_only_complete_snapshots() {
    let dir = scratch("killed");
    let case = long_case(&dir, 1.0);
    let run = dir.join("run");
    let child = spawn(&["run", &case, "--out", run.to_str().unwrap(), "--quiet"]);
    wait_for(&run.join("particles_000004.h5"));
    send(&child, "-KILL");
    child.wait_with_output().unwrap();
    let files = snapshots(&run);
    assert!(files.len() >= 5);
    for f in &files {
        let h5 = hdf5::File::open(f).unwrap_or_else(|e| panic!("{f:?}: {e}"));
        assert_eq!(dataset(&h5, "density").len(), 800 + 699, "{f:?}");
    }
    let xmf = std::fs::read_to_string(run.join("particles.xmf")).unwrap();
    assert!(xmf.trim_end().ends_with("</Xdmf>"), "the index is whole");
}

/// The same case with a restart file every 0.1 s of simulated time, and a filtered
/// face sensor on the left wall, under the collapsing column (its filter's state goes
/// into the restart file).
fn checkpointed_case(dir: &Path, end: f64) -> String {
    let case = long_case(dir, end);
    let text = std::fs::read_to_string(&case).unwrap()
        + "\n[output]\nrestart_interval = 0.1\n\
           [[diagnostics.sensors]]\nname = \"left\"\ncentre = [0.0, 0.12]\n\
           normal = [1.0, 0.0]\nsize = 0.09\ncutoff = 50.0\n";
    std::fs::write(&case, text).unwrap();
    case
}

#[test]
fn a_run_killed_after_its_second_restart_file_continues_bit_for_bit() {
    let dir = scratch("sigkill");
    let case = checkpointed_case(&dir, 0.5);
    let (whole, parts) = (dir.join("whole"), dir.join("parts"));
    succeeded(cli(&[
        "run",
        &case,
        "--out",
        whole.to_str().unwrap(),
        "--quiet",
    ]));

    let child = spawn(&["run", &case, "--out", parts.to_str().unwrap(), "--quiet"]);
    // restart.prev.h5 appears with the second periodic restart file
    wait_for(&parts.join("restart.prev.h5"));
    send(&child, "-KILL");
    let killed = child.wait_with_output().unwrap();
    assert_eq!(killed.status.code(), None, "killed by the signal");
    let newest = parts.join("restart.h5");
    let at = |f: &Path| -> f64 {
        let h5 = hdf5::File::open(f).unwrap();
        h5.attr("time").unwrap().read_scalar().unwrap()
    };
    let (t_new, t_prev) = (at(&newest), at(&parts.join("restart.prev.h5")));
    assert!(
        t_prev >= 0.1 && t_new > t_prev && t_new < 0.5,
        "{t_prev} {t_new}"
    );

    // --force replaces what the killed run wrote after its restart file
    let resumed = cli_within(
        &[
            "run",
            "--restart",
            newest.to_str().unwrap(),
            "--quiet",
            "--force",
        ],
        Duration::from_secs(60),
    );
    succeeded(resumed);
    assert_same_state(
        snapshots(&whole).last().unwrap(),
        snapshots(&parts).last().unwrap(),
    );
    let rows = |d: &Path| std::fs::read_to_string(d.join("timeseries.csv")).unwrap();
    assert_eq!(
        rows(&whole),
        rows(&parts),
        "the same time series, row for row"
    );
    assert!(rows(&whole)
        .lines()
        .next()
        .unwrap()
        .contains("left_filtered"));
}

#[test]
fn scheduler_signals_stop_a_run_like_sigterm() {
    for (signal, code) in [("-HUP", 129), ("-USR1", 138)] {
        let dir = scratch(&format!("signal{code}"));
        let case = long_case(&dir, 1.0);
        let run = dir.join("run");
        let child = spawn(&["run", &case, "--out", run.to_str().unwrap(), "--quiet"]);
        wait_for(&run.join("particles_000002.h5"));
        send(&child, signal);
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{signal}: {err}");
        assert!(err.starts_with("error: interrupted by SIG"), "{err}");
        assert!(run.join("restart.h5").is_file(), "{signal}");
        let resumed = cli_within(
            &[
                "run",
                "--restart",
                run.join("restart.h5").to_str().unwrap(),
                "--quiet",
            ],
            Duration::from_secs(60),
        );
        succeeded(resumed);
    }
}

#[test]
fn checkpoint_every_writes_restart_files_while_the_run_goes_on() {
    let dir = scratch("wallclock");
    let case = long_case(&dir, 1.0);
    let run = dir.join("run");
    let child = spawn(&[
        "run",
        &case,
        "--out",
        run.to_str().unwrap(),
        "--quiet",
        "--checkpoint-every",
        "50ms",
    ]);
    wait_for(&run.join("restart.prev.h5"));
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let bad = cli(&["run", &case, "--checkpoint-every", "soon"]);
    let err = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(2), "{err}");
    assert!(err.contains("expected a duration such as 30min"), "{err}");
}

#[test]
fn a_damaged_restart_file_is_an_error_not_a_panic() {
    let dir = scratch("damaged");
    let case = long_case(&dir, 0.05);
    let run = dir.join("run");
    succeeded(cli(&[
        "run",
        &case,
        "--out",
        run.to_str().unwrap(),
        "--quiet",
    ]));
    let original = run.join("restart.h5");
    for (name, damage) in [
        ("short", "position"),
        ("kinds", "kind"),
        ("budget", "case_toml"),
    ] {
        let copy = dir.join(format!("{name}.h5"));
        std::fs::copy(&original, &copy).unwrap();
        // No HDF5 lock: a `flock` taken here is inherited by any CLI that a test
        // running beside this one spawns meanwhile, and outlives `close` in that child.
        let h5 = hdf5::File::with_options()
            .with_fapl(|fapl| fapl.file_locking(false))
            .open_rw(&copy)
            .unwrap();
        h5.unlink(damage).unwrap();
        match damage {
            "position" => {
                h5.new_dataset::<f64>()
                    .shape((3, 2))
                    .create("position")
                    .unwrap();
            }
            "kind" => {
                let n = h5.dataset("id").unwrap().size();
                let kinds = vec![7u8; n];
                h5.new_dataset::<u8>()
                    .shape(n)
                    .create("kind")
                    .unwrap()
                    .write_raw(&kinds)
                    .unwrap();
            }
            _ => {}
        }
        h5.close().unwrap();
        let out = cli(&[
            "run",
            "--restart",
            copy.to_str().unwrap(),
            "--out",
            dir.join(name).to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.contains("damaged restart file"), "{name}: {err}");
    }
}

/// A disk that fills up during the run (a tmpfs in a private mount namespace, sized
/// two snapshots short of what the same run writes on the real disk): the write that
/// does not fit is dropped, the older restart file makes room for a new one, and the
/// run stops with exit code 2 and a one-line message. Continued from that file
/// elsewhere, the run ends in the state of the run that had room, bit for bit.
#[test]
fn a_full_disk_stops_the_run_after_writing_a_restart_file() {
    let dir = scratch("full");
    let case = checkpointed_case(&dir, 0.3);
    let whole = dir.join("whole");
    succeeded(cli(&[
        "run",
        &case,
        "--out",
        whole.to_str().unwrap(),
        "--quiet",
    ]));
    let page = |b: u64| b.div_ceil(4096) * 4096;
    let files: Vec<(String, u64)> = std::fs::read_dir(&whole)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                e.metadata().unwrap().len(),
            )
        })
        .collect();
    let snapshot = files
        .iter()
        .find(|(f, _)| f == "particles_000001.h5")
        .unwrap()
        .1;
    let capacity = files.iter().map(|(_, b)| page(*b)).sum::<u64>() - 2 * page(snapshot);
    let (mnt, kept) = (dir.join("disk"), dir.join("kept"));
    std::fs::create_dir_all(&mnt).unwrap();
    std::fs::create_dir_all(&kept).unwrap();
    let script = format!(
        "mount -t tmpfs -o size={capacity} none {mnt} || exit 90\n\
         {bin} run {case} --out {mnt}/run --quiet > {kept}/stdout 2> {kept}/stderr\n\
         echo $? > {kept}/code\n\
         cp {mnt}/run/restart.h5 {kept}/restart.h5\n\
         ls {mnt}/run > {kept}/listing\n",
        mnt = mnt.display(),
        kept = kept.display(),
        bin = env!("CARGO_BIN_EXE_sph-cli"),
    );
    let status = Command::new("unshare")
        .args(["--user", "--map-root-user", "--mount", "sh", "-c", &script])
        .status()
        .expect("unshare (util-linux) runs");
    assert!(
        status.success(),
        "a private tmpfs could not be mounted: {status}"
    );
    let read = |name: &str| std::fs::read_to_string(kept.join(name)).unwrap();
    let err = read("stderr");
    assert_eq!(read("code").trim(), "2", "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("No space left on device"), "{err}");
    assert!(err.contains("restart file written at t = "), "{err}");
    assert!(
        !read("listing").contains(".partial"),
        "no partial file is left"
    );

    let cont = dir.join("continued");
    succeeded(cli_within(
        &[
            "run",
            "--restart",
            kept.join("restart.h5").to_str().unwrap(),
            "--out",
            cont.to_str().unwrap(),
            "--quiet",
        ],
        Duration::from_secs(60),
    ));
    assert_same_state(
        snapshots(&whole).last().unwrap(),
        snapshots(&cont).last().unwrap(),
    );
}
