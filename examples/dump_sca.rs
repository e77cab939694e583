use shade_sim::eval::layout_features;
use shade_sim::scene::Scene;
fn main() {
    for dir in std::env::args().skip(1) {
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
        files.sort();
        for f in files {
            let Ok(s) = Scene::load(&f) else { continue };
            let v = layout_features(&s, 0.05, 0.05);
            println!("{}\t{}", dir, v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" "));
        }
    }
}
