fn main() {
    let root = std::path::Path::new("/work/wt-control");
    let t0 = std::time::Instant::now();
    let s = control::reproduce(
        &root.join("experiments"),
        &root.join("results"),
        &control::Budget::default(),
        |m| eprintln!("[{:.1}s] {m}", t0.elapsed().as_secs_f64()),
    )
    .unwrap();
    eprintln!("{s:?} in {:.1}s", t0.elapsed().as_secs_f64());
}
