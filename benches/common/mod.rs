//! Helpers shared by the benches: medians and best times for the ratios printed at the end of a
//! run, and the repository's scene folders. (Each bench uses some of them.)
#![allow(dead_code)]

use shade_sim::scene::Scene;

/// The scenes of a folder of the repository (`scenes/examples`, `scenes/reference`), sorted by
/// file name, with their file stems.
pub fn named_scenes(folder: &str) -> Vec<(String, Scene)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut files: Vec<_> = std::fs::read_dir(&dir).expect("a scene folder").map(|e| e.unwrap().path()).collect();
    files.sort();
    files
        .into_iter()
        .map(|f| (f.file_stem().unwrap().to_string_lossy().into_owned(), Scene::load(&f).expect("a valid scene")))
        .collect()
}

/// Seconds of each of `n` runs of `f`, sorted.
fn times(n: usize, mut f: impl FnMut()) -> Vec<f64> {
    let mut t: Vec<f64> = (0..n)
        .map(|_| {
            let start = std::time::Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t
}

/// Median seconds of `f` over `n` runs.
pub fn median(n: usize, f: impl FnMut()) -> f64 {
    times(n, f)[n / 2]
}

/// The fastest of `n` runs of `f`, in seconds: on a shared machine other work only ever slows a
/// run down, so the best time is the least disturbed one.
pub fn fastest(n: usize, f: impl FnMut()) -> f64 {
    times(n, f)[0]
}
