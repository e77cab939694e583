//! The SHADE model end to end at tiny size: training, exact resumption, checkpoints, generation,
//! bad checkpoints, and the demo on the shipped models.

use crate::{root, shade_sim, stderr, stdout};
use shade_sim::data::{SynthConfig, synthesize};
use shade_sim::generator::train::{LogLine, read_log};
use shade_sim::generator::{
    Checkpoint, Engine, FloorMeasure, Generator, ModelConfig, SeenRoom, TrainObserver, TrainOptions, shipped_rooms,
    train,
};
use shade_sim::scene::{RoomType, Scene};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

fn dataset(dir: &Path, room: RoomType) -> PathBuf {
    let data = dir.join(format!("{room}-data"));
    let cfg = SynthConfig { room, scenes: 12, seed: 4, spacing: Default::default(), command: "test".into() };
    synthesize(&cfg, &data, None, &|_| {}).expect("synth writes");
    data
}

fn options(data: &Path, out: &Path) -> TrainOptions {
    let mut o = TrainOptions::new(data.to_path_buf(), out.to_path_buf(), ModelConfig::tiny(RoomType::Bedroom));
    o.steps = 6;
    o.batch = 4;
    o.warmup = 2;
    o.log_every = 2;
    o.val_every = 2;
    o.checkpoint_every = Duration::from_secs(3600);
    o
}

/// Stops the run after the log line of `at`.
struct StopAt<'a>(u64, &'a AtomicBool);

impl TrainObserver for StopAt<'_> {
    fn logged(&mut self, line: &LogLine) {
        if line.step >= self.0 {
            self.1.store(true, Ordering::Relaxed);
        }
    }
}

#[test]
fn a_stopped_and_resumed_run_ends_with_the_same_weights_as_an_uninterrupted_one() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let straight = dir.path().join("straight");
    let outcome = train(&options(&data, &straight), &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!((outcome.step, outcome.stopped), (6, false));

    let split = dir.path().join("split");
    let stop = AtomicBool::new(false);
    // Stop is noticed right after step 3; the run logs and checkpoints there.
    let first = train(&options(&data, &split), &stop, &mut StopAt(2, &stop)).unwrap();
    assert_eq!((first.step, first.stopped), (3, true));
    let mut resume = options(&data, &split);
    resume.resume = true;
    let second = train(&resume, &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!((second.step, second.stopped), (6, false));

    let a = std::fs::read(straight.join("model.safetensors")).unwrap();
    let b = std::fs::read(split.join("model.safetensors")).unwrap();
    assert!(a == b, "EMA weights differ after resuming");
    let losses =
        |d: &Path| read_log(&d.join("log.jsonl")).unwrap().iter().map(|l| (l.step, l.loss)).collect::<Vec<_>>();
    assert_eq!(losses(&straight).last(), losses(&split).last());
    assert_eq!(outcome.val_loss, second.val_loss);

    // A checkpoint from another dataset is refused.
    let other = dir.path().join("other-data");
    synthesize(
        &SynthConfig { room: RoomType::Bedroom, scenes: 12, seed: 5, spacing: Default::default(), command: "x".into() },
        &other,
        None,
        &|_| {},
    )
    .unwrap();
    let mut wrong = options(&other, &split);
    wrong.resume = true;
    let err = train(&wrong, &AtomicBool::new(false), &mut ()).unwrap_err().to_string();
    assert!(err.contains("train_state.json") && err.contains("different dataset"), "{err}");

    // So is resuming with another category balance than the run had (recorded in config.json).
    let mut rebalanced = options(&data, &split);
    (rebalanced.resume, rebalanced.category_balance) = (true, 0.5);
    let err = train(&rebalanced, &AtomicBool::new(false), &mut ()).unwrap_err().to_string();
    assert!(err.contains("config.json") && err.contains("--category-balance 0, not 0.5"), "{err}");
}

#[test]
fn the_fused_and_candle_engines_follow_the_same_loss_curve_and_share_checkpoints() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let run = |engine: Engine, name: &str, steps: u64| {
        let mut o = options(&data, &dir.path().join(name));
        (o.engine, o.steps, o.batch, o.warmup, o.log_every, o.val_every, o.lr) = (engine, steps, 8, 5, 5, 10, 1e-3);
        o
    };
    let fused = train(&run(Engine::Fused, "fused", 40), &AtomicBool::new(false), &mut ()).unwrap();
    let candle = train(&run(Engine::Candle, "candle", 40), &AtomicBool::new(false), &mut ()).unwrap();
    let curve = |name: &str| read_log(&dir.path().join(name).join("log.jsonl")).unwrap();
    let (a, b) = (curve("fused"), curve("candle"));
    assert_eq!(a.len(), 8);
    // The loss falls, and both engines see the same values along the way.
    assert!(a[7].loss < 0.8 * a[0].loss, "{a:?}");
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.step, y.step);
        assert!((x.loss - y.loss).abs() < 0.01 * y.loss, "step {}: fused {} candle {}", x.step, x.loss, y.loss);
    }
    let (va, vb) = (fused.val_loss.unwrap(), candle.val_loss.unwrap());
    assert!((va - vb).abs() < 0.01 * vb, "val {va} vs {vb}");

    // A run started on one engine resumes on the other (the state is the same named tensors).
    let mut more = run(Engine::Fused, "candle", 50);
    more.resume = true;
    let resumed = train(&more, &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!((resumed.step, resumed.stopped), (50, false));
}

/// A run started from a trained model (fine-tuning) starts from its weights, encodes its rooms in
/// that model's token bounds, takes its sampler, records where it started, and keeps all of it
/// when resumed; a model of another architecture is refused, a low-noise expert of the same
/// network is not.
#[test]
fn a_run_started_from_a_model_takes_its_weights_and_bounds_and_records_it() {
    use shade_sim::generator::checkpoint::{fnv1a_hex, read_tensors};
    use shade_sim::generator::{InitialWeights, data_bounds};
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let other = dir.path().join("other-data");
    let synth =
        SynthConfig { room: RoomType::Bedroom, scenes: 12, seed: 5, spacing: Default::default(), command: "x".into() };
    synthesize(&synth, &other, None, &|_| {}).unwrap();
    assert_ne!(data_bounds(&data).unwrap(), data_bounds(&other).unwrap(), "the test needs other bounds");
    let start = dir.path().join("start");
    let mut first = options(&data, &start);
    (first.seed, first.sampling) = (1, Some(shade_sim::generator::SamplingDefaults { geometry_eta: 1.5 }));
    train(&first, &AtomicBool::new(false), &mut ()).unwrap();

    // At a learning rate of 1e-12 the weights cannot move: what the run ends with is where it began.
    let run = |name: &str, init: Option<&Path>| {
        let mut o = options(&other, &dir.path().join(name));
        (o.lr, o.steps, o.init) = (1e-12, 2, init.map(Path::to_path_buf));
        o
    };
    train(&run("tuned", Some(&start)), &AtomicBool::new(false), &mut ()).unwrap();
    train(&run("fresh", None), &AtomicBool::new(false), &mut ()).unwrap();
    let weights = |name: &str| {
        let path = dir.path().join(name).join("model.safetensors");
        let tensors = read_tensors(&std::fs::read(&path).unwrap(), &path).unwrap();
        let mut names: Vec<_> = tensors.keys().cloned().collect();
        names.sort();
        names.iter().flat_map(|n| tensors[n].flatten_all().unwrap().to_vec1::<f32>().unwrap()).collect::<Vec<f32>>()
    };
    let largest_change = |a: &[f32], b: &[f32]| a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0f32, f32::max);
    let (begun, tuned, fresh) = (weights("start"), weights("tuned"), weights("fresh"));
    assert!(largest_change(&begun, &tuned) < 1e-6, "{}", largest_change(&begun, &tuned));
    assert!(largest_change(&begun, &fresh) > 1e-2, "another seed's random weights are far from the start's");

    let meta = Checkpoint::load(&dir.path().join("tuned")).unwrap().meta;
    let started = Checkpoint::load(&start).unwrap().meta;
    assert_eq!(meta.bounds, started.bounds, "the start's bounds, not the data's");
    assert_eq!(meta.sampling, started.sampling, "the start's sampler");
    let hash = fnv1a_hex(&std::fs::read(start.join("model.safetensors")).unwrap());
    let record = InitialWeights { model: start.display().to_string(), weights_hash: hash };
    assert_eq!(meta.training.init.as_ref(), Some(&record));
    assert_eq!(Checkpoint::load(&dir.path().join("fresh")).unwrap().meta.training.init, None);

    // Resumed, the run keeps its start's bounds and record.
    let mut more = run("tuned", None);
    (more.resume, more.steps) = (true, 4);
    assert_eq!(train(&more, &AtomicBool::new(false), &mut ()).unwrap().step, 4);
    let resumed = Checkpoint::load(&dir.path().join("tuned")).unwrap().meta;
    assert_eq!((resumed.bounds, resumed.training.init), (started.bounds, Some(record)));
    assert_eq!(resumed.sampling, started.sampling);

    // A model of another architecture has other tensors: refused, naming its config.
    let mut wider = run("wider", Some(&start));
    wider.model.d_model *= 2;
    let err = train(&wider, &AtomicBool::new(false), &mut ()).unwrap_err().to_string();
    assert!(err.contains("start/config.json") && err.contains("model config differs"), "{err}");
    assert!(!dir.path().join("wider").exists(), "nothing written");
    // A low-noise expert fine-tuned from it has its network, trained on the least noisy steps.
    let mut expert = run("expert", Some(&start));
    expert.model.expert_below = Some(3);
    train(&expert, &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!(Checkpoint::load(&dir.path().join("expert")).unwrap().meta.model.expert_below, Some(3));
}

fn train_cli(data: &Path, out: &Path) -> std::process::Output {
    train_cli_with(data, out, &[])
}

fn train_cli_with(data: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let (d, o) = (data.to_str().unwrap(), out.to_str().unwrap());
    let args =
        ["train", "--data", d, "--out", o, "--steps", "3", "--batch", "4", "--preset", "tiny", "--log-every", "1"];
    shade_sim(&[&args[..], extra].concat())
}

/// `shade-sim -q generate --input INPUT --out OUT --model MODEL EXTRA…`.
fn generate_cli(input: &Path, out: &Path, model: &Path, extra: &[&str]) -> std::process::Output {
    let (i, o, m) = (input.to_str().unwrap(), out.to_str().unwrap(), model.to_str().unwrap());
    shade_sim(&[&["-q", "generate", "--input", i, "--out", o, "--model", m][..], extra].concat())
}

#[test]
fn a_model_with_slot_roles_world_features_relation_values_and_the_relation_loss_trains_loads_and_generates() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let model = dir.path().join("model");
    let flags =
        ["--slot-roles", "true", "--world-features", "true", "--relation-values", "true", "--relation-loss", "1"];
    let o = train_cli_with(&data, &model, &flags);
    assert!(o.status.success(), "{}", stderr(&o));
    let meta = Checkpoint::load(&model).unwrap().meta;
    assert!(meta.model.slot_roles && meta.model.world_features, "recorded in config.json");
    assert!(meta.model.relation_values, "recorded in config.json");
    let out = dir.path().join("out");
    let input = root().join("scenes/examples/bedroom_rect.json");
    let o = generate_cli(&input, &out, &model, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("bedroom_rect_0.json").exists());
    // The relation loss is the fused engine's alone.
    let o = train_cli_with(&data, &dir.path().join("candle"), &["--relation-loss", "1", "--engine", "candle"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("error: --relation-loss: needs --engine fused"), "{}", stderr(&o));
}

#[test]
fn extra_data_joins_the_training_set_and_must_be_of_the_same_room_type() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let extra_dir = dir.path().join("extra");
    let extra = dataset(&extra_dir, RoomType::Bedroom);
    let count = |d: &Path, split: &str| std::fs::read_dir(d.join(split)).unwrap().count();
    let mut o = options(&data, &dir.path().join("model"));
    o.steps = 2;
    o.extra_data = vec![extra.clone()];
    let outcome = train(&o, &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!(outcome.step, 2);
    let ckpt = Checkpoint::load(&dir.path().join("model")).unwrap();
    let all_extra = count(&extra, "train") + count(&extra, "val") + count(&extra, "test");
    assert_eq!(ckpt.meta.training.train_scenes, count(&data, "train") + all_extra);
    // A living-room dataset cannot teach a bedroom model.
    let living = dataset(&extra_dir, RoomType::Living);
    o.out = dir.path().join("model2");
    o.extra_data = vec![living.clone()];
    let err = train(&o, &AtomicBool::new(false), &mut ()).unwrap_err().to_string();
    assert!(err.contains("living") && err.contains(living.to_str().unwrap()), "{err}");
}

#[test]
fn joint_data_adds_its_train_split_and_a_room_token_model_generates_both_room_types() {
    let dir = tempfile::tempdir().unwrap();
    let living = dataset(dir.path(), RoomType::Living);
    let dining = dataset(dir.path(), RoomType::Dining);
    let count = |d: &Path, split: &str| std::fs::read_dir(d.join(split)).unwrap().count();
    let mut o = options(&living, &dir.path().join("model"));
    o.steps = 2;
    o.joint_data = vec![dining.clone()];
    // Without a room token the model is a living-room model alone.
    o.model = ModelConfig::tiny(RoomType::Living);
    let err = train(&o, &AtomicBool::new(false), &mut ()).unwrap_err().to_string();
    assert!(err.contains("dining") && err.contains(dining.to_str().unwrap()), "{err}");
    o.model.room_token = true;
    let outcome = train(&o, &AtomicBool::new(false), &mut ()).unwrap();
    assert_eq!(outcome.step, 2);
    let model = dir.path().join("model");
    let ckpt = Checkpoint::load(&model).unwrap();
    // Only the dining train split joins: its val and test rooms stay out.
    assert!(count(&dining, "val") + count(&dining, "test") > 0);
    assert_eq!(ckpt.meta.training.train_scenes, count(&living, "train") + count(&dining, "train"));
    // One model generates living and dining rooms in one call; a bedroom is refused.
    let inputs = dir.path().join("inputs");
    std::fs::create_dir_all(&inputs).unwrap();
    for (data, name) in [(&living, "a_living.json"), (&dining, "b_dining.json")] {
        let first = std::fs::read_dir(data.join("test")).unwrap().next().unwrap().unwrap().path();
        let mut scene = Scene::load(&first).unwrap();
        scene.objects.clear();
        scene.save(inputs.join(name)).unwrap();
    }
    let (i, m) = (inputs.to_str().unwrap(), model.to_str().unwrap());
    let out = dir.path().join("out");
    let o = shade_sim(&["-q", "generate", "--input", i, "--out", out.to_str().unwrap(), "--model", m, "--no-repair"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (name, room) in [("a_living_0.json", RoomType::Living), ("b_dining_0.json", RoomType::Dining)] {
        assert_eq!(Scene::load(out.join(name)).unwrap().room_type, room);
    }
    let bedroom = root().join("scenes/examples/bedroom_rect.json");
    let o =
        shade_sim(&["generate", "--input", bedroom.to_str().unwrap(), "--out", out.to_str().unwrap(), "--model", m]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("is a bedroom but the model generates living or dining"), "{}", stderr(&o));
}

#[test]
fn a_count_conditioned_model_keeps_its_training_rooms_make_ups_and_draws_from_them() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let model = dir.path().join("model");
    let mut o = options(&data, &model);
    o.steps = 2;
    o.model.count_condition = true;
    train(&o, &AtomicBool::new(false), &mut ()).unwrap();
    let ckpt = Checkpoint::load(&model).unwrap();
    let prior = ckpt.meta.count_prior.clone().expect("a count prior");
    // One row per training room, its pieces counted by category in the model's class order.
    let mut want: Vec<Vec<u8>> = std::fs::read_dir(data.join("train"))
        .unwrap()
        .map(|f| {
            let scene = Scene::load(f.unwrap().path()).unwrap();
            let n = |c| scene.objects.iter().filter(|o| o.category == c).count() as u8;
            ckpt.meta.categories.iter().map(|&c| n(c)).collect()
        })
        .collect();
    let mut got: Vec<Vec<u8>> = prior.rooms.iter().map(|r| r.3.clone()).collect();
    want.sort();
    got.sort();
    assert_eq!(got, want);
    assert_eq!(prior.rooms.len(), ckpt.meta.training.train_scenes);

    // Each sample's counts are a training room's, the same for the same seed; the layouts come.
    let input = Scene::load(root().join("scenes/examples/bedroom_rect.json")).unwrap();
    let generator = Generator::new(ckpt.clone());
    let drawn: Vec<Vec<u8>> = (0..6).map(|k| generator.counts_of(&input, 0, k, 3).unwrap().unwrap()).collect();
    assert!(drawn.iter().all(|c| got.contains(c)), "{drawn:?}");
    assert_eq!(drawn[2], generator.counts_of(&input, 0, 2, 3).unwrap().unwrap());
    assert_eq!(generator.generate(std::slice::from_ref(&input), 2, 3).unwrap()[0].len(), 2);
    // With the input's own counts: its pieces per category, whatever the seed.
    let furnished = Scene::load(std::fs::read_dir(data.join("test")).unwrap().next().unwrap().unwrap().path()).unwrap();
    let own: Vec<u8> = ckpt
        .meta
        .categories
        .iter()
        .map(|&c| furnished.objects.iter().filter(|o| o.category == c).count() as u8)
        .collect();
    let with_own = Generator::new(ckpt.clone()).with_input_counts();
    assert!(own.iter().any(|&n| n > 0));
    for k in 0..3 {
        assert_eq!(with_own.counts_of(&furnished, 0, k, k as u64).unwrap().unwrap(), own);
    }
    let (f, m) = (furnished.clone(), model.to_str().unwrap());
    let input_file = dir.path().join("furnished.json");
    f.save(&input_file).unwrap();
    // `generate --model M --input-counts` on `input` into `out`, with `more` flags.
    let with_counts = |input: &Path, out: &Path, more: &[&str]| {
        let args = ["generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap(), "--model", m];
        shade_sim(&[&args[..], &["--input-counts"], more].concat())
    };
    let out = dir.path().join("own");
    let o = with_counts(&input_file, &out, &["-q", "--no-repair", "--guidance", "none"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The count projection brings even a two-step model's make-up nearer the pieces asked for.
    let raw = dir.path().join("raw");
    assert!(
        with_counts(&input_file, &raw, &["-q", "--no-repair", "--guidance", "none", "--no-empty-projection"])
            .status
            .success()
    );
    let pieces_off = |file: PathBuf| {
        let made = Scene::load(file).unwrap();
        let counts = made.room_type.category_counts(&made.objects);
        counts.iter().zip(&own).map(|(&c, &n)| c.abs_diff(usize::from(n))).sum::<usize>()
    };
    let (projected, unprojected) = (pieces_off(out.join("furnished_0.json")), pieces_off(raw.join("furnished_0.json")));
    assert!(projected < unprojected, "{projected} pieces off with the projection, {unprojected} without");
    // An input without pieces has nothing to count: refused, nothing written.
    let bare_file = dir.path().join("bare.json");
    Scene { objects: Vec::new(), ..furnished.clone() }.save(&bare_file).unwrap();
    let bare_out = dir.path().join("bare");
    let o = with_counts(&bare_file, &bare_out, &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bare.json: --input-counts: the input has no bedroom pieces to count"),
        "{}",
        stderr(&o)
    );
    assert!(!bare_out.exists());
    // The shipped models have no count conditioning: the flag is refused, not ignored.
    let o = shade_sim(&[
        "generate",
        "--input",
        input_file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--input-counts",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--input-counts: the bedroom model has no count conditioning"), "{}", stderr(&o));

    // A count-conditioned config without its prior, with a row of another width or a row that
    // does not parse is a bad checkpoint, named as such; nothing is written.
    let config = model.join("config.json");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&config).unwrap()).unwrap();
    let first = prior.rooms[0].clone();
    let short = String::from(shade_sim::generator::count_prior::PriorRoom(first.0, first.1, first.2, vec![1]));
    let bad_rows: [(Option<serde_json::Value>, &str); 3] = [
        (None, "count conditioning needs a count_prior"),
        (Some(serde_json::json!({ "rooms": [short] })), "counts"),
        (Some(serde_json::json!({ "rooms": ["bedroom 1 0 0 12"] })), "is not \"ROOM SIT LIE TOUCH AREA: COUNTS"),
    ];
    let input = root().join("scenes/examples/bedroom_rect.json");
    for (value, message) in bad_rows {
        let mut json = json.clone();
        match value {
            Some(v) => json["count_prior"] = v,
            None => drop(json.as_object_mut().unwrap().remove("count_prior")),
        }
        std::fs::write(&config, serde_json::to_string_pretty(&json).unwrap()).unwrap();
        let out = dir.path().join("out");
        let m = model.to_str().unwrap();
        let o =
            shade_sim(&["generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap(), "--model", m]);
        assert_eq!(o.status.code(), Some(2));
        assert!(stderr(&o).starts_with("error: ") && stderr(&o).contains("config.json"), "{}", stderr(&o));
        assert!(stderr(&o).contains(message), "{message}: {}", stderr(&o));
        assert!(!out.exists(), "nothing written");
    }
}

#[test]
fn train_writes_a_checkpoint_and_generate_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let model = dir.path().join("model");
    let out = train_cli(&data, &model);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("done: step 3 of 3"), "{}", stdout(&out));
    let ckpt = Checkpoint::load(&model).unwrap();
    assert_eq!(ckpt.meta.format, "shade-model/1");
    assert_eq!(ckpt.meta.model, ModelConfig::tiny(RoomType::Bedroom));
    assert_eq!(ckpt.meta.categories, RoomType::Bedroom.categories());
    assert_eq!(ckpt.meta.training.steps, 3);
    assert!(ckpt.meta.training.command.starts_with("shade-sim train --data"), "{}", ckpt.meta.training.command);
    assert_eq!(ckpt.meta.training.dataset_seed, 4);
    assert_eq!(read_log(&model.join("log.jsonl")).unwrap().len(), 3);
    assert!(std::fs::read(model.join("loss.png")).unwrap().starts_with(b"\x89PNG"));

    assert_eq!(ckpt.meta.sampling, None, "DDPM's chain unless asked");
    assert_eq!(ckpt.meta.training.ema_decay, 0.999, "the default EMA");

    // The same folder again without --resume would throw the run away: refused.
    let again = train_cli(&data, &model);
    assert_eq!(again.status.code(), Some(2));
    assert!(stderr(&again).contains("--resume"), "{}", stderr(&again));

    // The model's default sampler goes into its config.json, as the shipped dining model's, and
    // so do another EMA decay and another end of the learning rate's cosine.
    let with_eta = dir.path().join("with_eta");
    let o = train_cli_with(&data, &with_eta, &["--geometry-eta", "1.5", "--ema-decay", "0.99", "--lr-final", "0.01"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let meta = Checkpoint::load(&with_eta).unwrap().meta;
    assert_eq!(meta.sampling, Some(shade_sim::generator::SamplingDefaults { geometry_eta: 1.5 }));
    assert_eq!((meta.training.ema_decay, meta.training.lr_final), (0.99, 0.01));
    assert_eq!(Checkpoint::load(&model).unwrap().meta.training.lr_final, 0.1, "the default end: a tenth");
    for (extra, want) in [
        (["--geometry-eta", "3"], "error: --geometry-eta: must be between 0 and 2"),
        (["--lr", "-1"], "error: --lr: must be a positive number"),
        (["--lr-final", "2"], "error: --lr-final: must be a fraction of the peak, from 0 to 1"),
        (["--ema-decay", "1"], "error: --ema-decay: must be a number between 0 and 1, not 1"),
        (["--relation-loss", "-1"], "error: --relation-loss: must be a non-negative number, not -1"),
    ] {
        let o = train_cli_with(&data, &dir.path().join("refused"), &extra);
        assert_eq!(o.status.code(), Some(2));
        assert!(stderr(&o).starts_with(want) && stderr(&o).lines().count() == 1, "{}", stderr(&o));
        assert!(!dir.path().join("refused").exists(), "nothing written");
    }

    // Fine-tuning the model just trained, as a user would a shipped one: the flags that choose an
    // architecture are refused beside --init, and so are --resume and a folder without a model;
    // then the run takes the model's architecture.
    let (d, m) = (data.to_str().unwrap(), model.to_str().unwrap());
    let tuned = dir.path().join("tuned");
    let t = tuned.to_str().unwrap();
    let missing = dir.path().join("missing");
    let base = ["train", "--data", d, "--out", t, "--steps", "2", "--batch", "4", "--init"];
    for (extra, want) in [
        (vec![m, "--preset", "tiny"], format!("error: --init: the model's architecture is {m}'s; leave out --preset")),
        (
            vec![m, "--resume"],
            "error: --init: a resumed run continues from its own checkpoint; leave out --init".into(),
        ),
        (vec![missing.to_str().unwrap()], format!("error: {}: ", missing.join("config.json").display())),
    ] {
        let o = shade_sim(&[&base[..], &extra].concat());
        assert_eq!(o.status.code(), Some(2));
        assert!(stderr(&o).starts_with(&want) && stderr(&o).lines().count() == 1, "{}", stderr(&o));
        assert!(!tuned.exists(), "nothing written");
    }
    let o = shade_sim(&[&base[..], &[m]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let tuned_meta = Checkpoint::load(&tuned).unwrap().meta;
    assert_eq!((tuned_meta.model, tuned_meta.training.steps), (ckpt.meta.model.clone(), 2));
    // Resumed with no flag, the run keeps the model config it started with; --expert-below is
    // what training draws, not the network: a low-noise expert fine-tuned from the model.
    let o = shade_sim(&["train", "--data", d, "--out", t, "--steps", "3", "--batch", "4", "--resume"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let expert = dir.path().join("expert");
    let e = expert.to_str().unwrap();
    let o = shade_sim(&[
        "train",
        "--data",
        d,
        "--out",
        e,
        "--steps",
        "2",
        "--batch",
        "4",
        "--init",
        m,
        "--expert-below",
        "5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(Checkpoint::load(&expert).unwrap().meta.model.expert_below, Some(5));

    let input = root().join("scenes/examples/bedroom_rect.json");
    let generate = |seed: &str, out: &Path| {
        let o = shade_sim(&[
            "generate",
            "--input",
            input.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--samples",
            "2",
            "--seed",
            seed,
            "--model",
            model.to_str().unwrap(),
            "--json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(summary["scenes"].as_array().unwrap().len(), 2);
        (0..2).map(|k| std::fs::read_to_string(out.join(format!("bedroom_rect_{k}.json"))).unwrap()).collect::<Vec<_>>()
    };
    let a = generate("5", &dir.path().join("a"));
    let b = generate("5", &dir.path().join("b"));
    let c = generate("6", &dir.path().join("c"));
    assert_eq!(a, b);
    // (Other seeds, or two samples of one seed, may repair to the same layout here: a tiny x₀
    // model trained for a few steps predicts nearly the same x₀ from any noise. `c` is still
    // written and valid.)
    assert_eq!(c.len(), 2);
    // By default every sample is repaired: the same as sampling with --no-repair and running
    // `repair` on the result.
    let unrepaired = dir.path().join("unrepaired");
    let o = generate_cli(&input, &unrepaired, &model, &["--samples", "2", "--seed", "5", "--no-repair"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let repaired = dir.path().join("repaired");
    let o = shade_sim(&["-q", "repair", unrepaired.to_str().unwrap(), "--out", repaired.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for (k, expected) in a.iter().enumerate() {
        let name = format!("bedroom_rect_{k}.json");
        assert_ne!(
            &std::fs::read_to_string(unrepaired.join(&name)).unwrap(),
            expected,
            "repair changes a tiny model's layout"
        );
        assert_eq!(&std::fs::read_to_string(repaired.join(&name)).unwrap(), expected);
    }
    // --require-clean: an (untrained) tiny model's unrepaired layouts never pass the check (repaired,
    // its near-constant x₀ layout may); every round samples
    // anew, nothing is written and the exit status is 1.
    let strict = dir.path().join("strict");
    let o = shade_sim(&[
        "generate",
        "--input",
        input.to_str().unwrap(),
        "--out",
        strict.to_str().unwrap(),
        "--samples",
        "2",
        "--model",
        model.to_str().unwrap(),
        "--require-clean",
        "--attempts",
        "3",
        "--no-repair",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["sampled"], 6);
    assert_eq!(summary["acceptance_rate"], 0.0);
    assert_eq!(summary["inputs_without_clean_layout"], 1);
    assert_eq!(std::fs::read_dir(&strict).unwrap().count(), 0);

    let original = Scene::load(&input).unwrap();
    let generated = Scene::load(dir.path().join("a/bedroom_rect_0.json")).unwrap();
    assert_eq!(generated.floor_plan, original.floor_plan);
    assert_eq!(generated.humans, original.humans);
    assert!(generated.objects.iter().all(|o| RoomType::Bedroom.categories().contains(&o.category)));
}

#[test]
fn bad_and_mismatched_checkpoints_give_one_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let model = dir.path().join("model");
    assert!(train_cli(&data, &model).status.success());
    let run = |model: &Path, input: &str| {
        let input = root().join("scenes/examples").join(input);
        shade_sim(&[
            "generate",
            "--input",
            input.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
            "--model",
            model.to_str().unwrap(),
        ])
    };
    let expect_error = |o: std::process::Output, needle: &str| {
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.starts_with("error: ") && e.contains(needle), "{e}");
    };
    expect_error(run(&model, "living_rect.json"), "is a living but the model generates bedroom");

    let corrupt = dir.path().join("corrupt");
    std::fs::create_dir(&corrupt).unwrap();
    // A config without the weights' hash, so that the weights themselves are read.
    let config = std::fs::read_to_string(model.join("config.json")).unwrap();
    assert!(config.contains("\"weights_hash\""), "training records the weights' hash");
    let mut unhashed: serde_json::Value = serde_json::from_str(&config).unwrap();
    unhashed.as_object_mut().unwrap().remove("weights_hash");
    let unhashed = serde_json::to_string_pretty(&unhashed).unwrap();
    std::fs::write(corrupt.join("config.json"), &unhashed).unwrap();
    std::fs::write(corrupt.join("model.safetensors"), b"not tensors at all").unwrap();
    expect_error(run(&corrupt, "bedroom_rect.json"), "model.safetensors: not a readable safetensors file");

    // Weights of a different shape (the config says d_model 48).
    let text = unhashed.replace("\"d_model\": 32", "\"d_model\": 48");
    std::fs::write(corrupt.join("config.json"), text).unwrap();
    std::fs::copy(model.join("model.safetensors"), corrupt.join("model.safetensors")).unwrap();
    expect_error(run(&corrupt, "bedroom_rect.json"), "model.safetensors: ");

    // The example bedroom with the test model and `guidance` flags.
    let guided = |guidance: &[&str]| {
        let input = root().join("scenes/examples/bedroom_rect.json");
        let out = dir.path().join("o");
        let mut args = vec!["generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend(["--model", model.to_str().unwrap()]);
        args.extend(guidance);
        shade_sim(&args)
    };
    expect_error(guided(&["--guidance", "mot,floor"]), "--guidance: unknown guidance term \"floor\"");

    // A guidance config asking for a billion gradient steps per step (it hung) or a negative step
    // bound (it was taken) is refused before any work, naming the file.
    for (field, value) in [("iterations", "1000000000"), ("max_step", "-0.03")] {
        let file = dir.path().join(format!("guidance_{field}.json"));
        let config = format!(
            "{{\"motion\": 1, \"bound\": 1, \"object\": 1, \"scale\": 0.1, \"until_step\": 20, \"{field}\": {value}}}"
        );
        std::fs::write(&file, config).unwrap();
        expect_error(guided(&["--guidance-config", file.to_str().unwrap()]), &format!("{}: {field}: ", file.display()));
    }

    // Checked on load: a weight file that does not match config.json's hash, weights that are NaN
    // (here under a config without a hash), and a chain too long to allocate (it aborted on 8 TB).
    let mut weights = std::fs::read(model.join("model.safetensors")).unwrap();
    let n = weights.len();
    weights[n - 4..].copy_from_slice(&f32::NAN.to_le_bytes());
    std::fs::write(corrupt.join("model.safetensors"), &weights).unwrap();
    std::fs::write(corrupt.join("config.json"), &config).unwrap();
    expect_error(run(&corrupt, "bedroom_rect.json"), "model.safetensors: does not match the weights_hash");
    std::fs::write(corrupt.join("config.json"), &unhashed).unwrap();
    expect_error(run(&corrupt, "bedroom_rect.json"), "model.safetensors: tensor ");
    expect_error(run(&corrupt, "bedroom_rect.json"), "has a non-finite value");
    let long = config.replace("\"diffusion_steps\": 200", "\"diffusion_steps\": 1000000000000");
    std::fs::write(corrupt.join("config.json"), long).unwrap();
    expect_error(
        run(&corrupt, "bedroom_rect.json"),
        "config.json: bad model config: diffusion_steps 1000000000000 is outside",
    );

    std::fs::write(corrupt.join("config.json"), "{ \"format\": ").unwrap();
    expect_error(run(&corrupt, "bedroom_rect.json"), "config.json: not a model config");
    expect_error(run(&dir.path().join("missing"), "bedroom_rect.json"), "config.json");
}

#[test]
fn every_room_type_has_a_shipped_model_and_the_demo_runs_on_it() {
    assert_eq!(shipped_rooms(), RoomType::ALL.to_vec());
    let dir = tempfile::tempdir().unwrap();
    let inputs = dir.path().join("inputs");
    std::fs::create_dir(&inputs).unwrap();
    for name in ["bedroom_rect.json", "dining_l.json"] {
        std::fs::copy(root().join("scenes/examples").join(name), inputs.join(name)).unwrap();
    }
    let out = dir.path().join("demo");
    let o = shade_sim(&["demo", "--inputs", inputs.to_str().unwrap(), "--out", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = summary["scenes"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for (row, stem) in rows.iter().zip(["bedroom_rect_0", "dining_l_0"]) {
        assert_eq!(row["scene"], stem);
        assert!(row["objects"].as_u64().unwrap() > 0, "{row}");
        assert!(row["violations"].is_u64());
        let scene = Scene::load(out.join(format!("{stem}.json"))).unwrap();
        assert_eq!(scene.objects.len() as u64, row["objects"].as_u64().unwrap());
        assert!(std::fs::read_to_string(out.join(format!("{stem}.xml"))).unwrap().starts_with("<mujoco"));
        assert!(std::fs::read(out.join(format!("{stem}.png"))).unwrap().starts_with(b"\x89PNG"));
        assert!(std::fs::read(out.join(format!("{stem}.glb"))).unwrap().starts_with(b"glTF"));
    }
    // `generate` on the same mixed folder samples each room type with its own model, as the demo
    // does: the same layouts.
    let generated = dir.path().join("generated");
    let o = shade_sim(&["-q", "generate", "--input", inputs.to_str().unwrap(), "--out", generated.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for stem in ["bedroom_rect_0", "dining_l_0"] {
        let file = format!("{stem}.json");
        assert!(std::fs::read(generated.join(&file)).unwrap() == std::fs::read(out.join(&file)).unwrap(), "{stem}");
    }
    // A --model must generate every room type of the inputs.
    let o = shade_sim(&[
        "generate",
        "--input",
        inputs.to_str().unwrap(),
        "--out",
        dir.path().join("x").to_str().unwrap(),
        "--model",
        root().join("models/bedroom").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("dining_l.json: is a dining but the model generates bedroom"), "{}", stderr(&o));
}

#[test]
fn without_the_empty_slot_projection_the_shipped_model_samples_more_objects() {
    let dir = tempfile::tempdir().unwrap();
    let input = root().join("scenes/examples/bedroom_rect.json");
    let count = |flag: Option<&str>| {
        let out = dir.path().join(flag.unwrap_or("default"));
        let mut args = vec!["-q", "generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend(["--samples", "8", "--guidance", "none"]);
        args.extend(flag);
        let o = shade_sim(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        (0..8).map(|k| Scene::load(out.join(format!("bedroom_rect_{k}.json"))).unwrap().objects.len()).sum::<usize>()
    };
    // The raw model over-generates (docs/RESULTS.md, "Empty-slot projection"): 59 objects in these
    // eight samples against 48 projected with the bedroom v model (58 against 50 with the
    // world-yaw x₀ model, 65 against 50 with the anchored x₀ model before it, 52 against 32 before
    // that).
    let (projected, raw) = (count(None), count(Some("--no-empty-projection")));
    assert!(raw as f64 > 1.1 * projected as f64, "{raw} vs {projected}");
}

#[test]
fn a_model_records_the_counts_its_training_rooms_have_and_samples_keep_to_them() {
    let dir = tempfile::tempdir().unwrap();
    let data = dataset(dir.path(), RoomType::Bedroom);
    let model = dir.path().join("model");
    let mut o = options(&data, &model);
    o.steps = 2;
    train(&o, &AtomicBool::new(false), &mut ()).unwrap();
    let ckpt = Checkpoint::load(&model).unwrap();
    let seen = ckpt.meta.seen_counts.clone().expect("seen counts");
    // Counted by hand from the train split: per category, each count and the rooms that have it.
    let mut want: Vec<std::collections::BTreeMap<u32, u32>> = vec![Default::default(); ckpt.meta.categories.len()];
    let (mut rooms, mut areas) = (0, [f32::INFINITY, 0.0f32]);
    let (mut widths, mut lengths) = (areas, areas);
    let widen = |r: [f32; 2], v: f32| [r[0].min(v), r[1].max(v)];
    for f in std::fs::read_dir(data.join("train")).unwrap() {
        let scene = Scene::load(f.unwrap().path()).unwrap();
        let to_tenth = |v: f64| ((v * 10.0).round() / 10.0) as f32; // m² and m to 0.1
        // The procedural plans stand square to the axes: their own frame's sides are the world's.
        let (lo, hi) = scene.floor_plan.polygon().bounds();
        let sides = hi - lo;
        rooms += 1;
        areas = widen(areas, to_tenth(scene.floor_plan.polygon().area()));
        widths = widen(widths, to_tenth(sides.min_element()));
        lengths = widen(lengths, to_tenth(sides.max_element()));
        for (c, &category) in ckpt.meta.categories.iter().enumerate() {
            let n = scene.objects.iter().filter(|o| o.category == category).count() as u32;
            *want[c].entry(n).or_default() += 1;
        }
    }
    let room = seen.of_room(RoomType::Bedroom).expect("the bedroom's counts");
    let got: Vec<std::collections::BTreeMap<u32, u32>> =
        room.categories.iter().map(|pairs| pairs.iter().map(|p| (p[0], p[1])).collect()).collect();
    assert_eq!(got, want);
    // And their floors' least and largest area, width and length.
    let floors = ckpt.meta.seen_floors.clone().expect("seen floors");
    let floor = shade_sim::generator::SeenFloor {
        room: RoomType::Bedroom,
        rooms,
        area: areas,
        width: Some(widths),
        length: Some(lengths),
    };
    assert_eq!(floors.rooms, [floor]);
    assert!(widths[0] < widths[1] && lengths[0] < lengths[1], "the rooms differ: {widths:?} {lengths:?}");

    // Were every training room to have one wardrobe, an empty room (no one in it, so no piece is
    // held for anyone) would get one in every sample; this two-step model's own samples are empty.
    let wardrobe = ckpt.meta.categories.iter().position(|c| c.name() == "wardrobe").unwrap();
    let mut one_each = ckpt.clone();
    let room = &mut one_each.meta.seen_counts.as_mut().unwrap().rooms[0];
    room.categories[wardrobe] = vec![[1, 12]];
    let mut input = Scene::load(root().join("scenes/examples/bedroom_rect.json")).unwrap();
    input.humans.clear();
    input.objects.clear();
    let wardrobes = |generator: Generator| -> Vec<usize> {
        let layouts = generator.generate(std::slice::from_ref(&input), 6, 5).unwrap().remove(0);
        layouts.iter().map(|s| s.objects.iter().filter(|o| o.category.name() == "wardrobe").count()).collect()
    };
    assert_eq!(wardrobes(Generator::new(one_each.clone())), [1; 6]);
    assert_eq!(wardrobes(Generator::new(one_each).without_seen_counts()), [0; 6]);
    assert_eq!(wardrobes(Generator::new(ckpt.clone())), [0; 6], "none is a count the data has");

    // Seen counts of another width, or without a room type the model serves, are a bad checkpoint.
    let config = model.join("config.json");
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&config).unwrap()).unwrap();
    let bad = [
        (serde_json::json!({ "rooms": [{ "room": "bedroom", "categories": [[[0, 1]]] }] }), "categories, not"),
        (serde_json::json!({ "rooms": [] }), "seen_counts has no bedroom room"),
    ];
    for (value, message) in bad {
        let mut json = json.clone();
        json["seen_counts"] = value;
        std::fs::write(&config, serde_json::to_string_pretty(&json).unwrap()).unwrap();
        let error = Checkpoint::load(&model).unwrap_err().to_string();
        assert!(error.contains("config.json") && error.contains(message), "{message}: {error}");
    }
}

#[test]
fn the_shipped_bedroom_model_keeps_to_the_counts_its_data_has() {
    let dir = tempfile::tempdir().unwrap();
    let input = root().join("scenes/examples/bedroom_rect.json");
    let shipped = root().join("models/bedroom");
    // Every category count of eight unguided samples of `model` that no room of `seen` has, as
    // (sample, category, count).
    let meta = Checkpoint::load(&shipped).unwrap().meta;
    let unseen = |model: &Path, seen: &SeenRoom, flag: Option<&str>| {
        let out = dir.path().join(format!("{}-{}", model.file_name().unwrap().display(), flag.unwrap_or("default")));
        let mut args = vec!["-q", "generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap()];
        args.extend(["--model", model.to_str().unwrap(), "--samples", "8", "--guidance", "none", "--no-repair"]);
        args.extend(flag);
        let o = shade_sim(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let mut found = Vec::new();
        for k in 0..8 {
            let scene = Scene::load(out.join(format!("bedroom_rect_{k}.json"))).unwrap();
            for (c, n) in scene.room_type.category_counts(&scene.objects).into_iter().enumerate() {
                if !seen.categories[c].iter().any(|p| p[0] as usize == n) {
                    found.push((k, meta.categories[c].name().to_string(), n));
                }
            }
        }
        found
    };
    let seen = meta.seen_counts.as_ref().and_then(|s| s.of_room(RoomType::Bedroom)).expect("seen counts").clone();
    assert_eq!(unseen(&shipped, &seen, None), []);

    // The same model as if its data had never held three pendant lamps in a room: the rule moves
    // sample 1's three to a count the data has; without it they stay.
    let model = dir.path().join("no-three-lamps");
    std::fs::create_dir(&model).unwrap();
    std::fs::copy(shipped.join("model.safetensors"), model.join("model.safetensors")).unwrap();
    let lamp = meta.categories.iter().position(|c| c.name() == "pendant_lamp").unwrap();
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(shipped.join("config.json")).unwrap()).unwrap();
    let counts = json["seen_counts"]["rooms"][0]["categories"][lamp].as_array_mut().unwrap();
    counts.retain(|p| p[0] != 3);
    std::fs::write(model.join("config.json"), serde_json::to_string_pretty(&json).unwrap()).unwrap();
    let mut fewer = seen.clone();
    fewer.categories[lamp].retain(|p| p[0] != 3);
    assert_eq!(unseen(&model, &fewer, None), []);
    assert_eq!(unseen(&model, &fewer, Some("--unseen-counts")), [(1, "pendant_lamp".to_string(), 3)]);
}

#[test]
fn ddim_eta_one_is_the_ddpm_chain_and_eta_zero_is_deterministic() {
    let input = Scene::load(root().join("scenes/examples/bedroom_rect.json")).unwrap();
    let ddpm = Generator::new(shade_sim::generator::shipped_model(RoomType::Bedroom).unwrap());
    let layouts = |g: &Generator, seed| g.generate(std::slice::from_ref(&input), 2, seed).unwrap().remove(0);
    // η 1 is DDPM's posterior (Schedule::jump): the default chain to the bit.
    assert_eq!(layouts(&ddpm.clone().with_eta(1.0), 4), layouts(&ddpm, 4));
    // η 0 draws no noise after the start: the same seed gives the same rooms, other than DDPM's,
    // respaced as well; each is a bedroom with pieces.
    let ddim = ddpm.clone().with_eta(0.0);
    let a = layouts(&ddim, 4);
    assert_eq!(a, layouts(&ddim, 4));
    assert_ne!(a, layouts(&ddpm, 4));
    let fast = ddim.with_sampling_steps(25);
    assert_eq!(layouts(&fast, 4), layouts(&fast, 4));
    for room in a.iter().chain(&layouts(&fast, 4)) {
        assert!(!room.objects.is_empty());
        assert!(room.objects.iter().all(|o| RoomType::Bedroom.categories().contains(&o.category)));
    }
    // η outside [0, 2] is refused with one line.
    for bad in ["2.5", "-0.1", "NaN"] {
        let dir = tempfile::tempdir().unwrap();
        let input = root().join("scenes/examples/bedroom_rect.json");
        let eta = format!("--eta={bad}");
        let args = ["generate", "--input", input.to_str().unwrap(), "--out", dir.path().to_str().unwrap(), &eta];
        let o = shade_sim(&args);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(stderr(&o).starts_with("error: --eta: must be between 0 and 2"), "{}", stderr(&o));
    }
}

/// `scene` turned by `angle` about the origin: floor plan, people and pieces.
fn turned(scene: &Scene, angle: f64) -> Scene {
    let (s, c) = angle.sin_cos();
    let turn = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
    let mut out = scene.clone();
    out.floor_plan.polygon = scene.floor_plan.polygon.iter().map(|p| turn(p[0], p[1])).collect();
    for j in out.humans.iter_mut().flat_map(|h| h.frames.iter_mut()).flat_map(|f| f.iter_mut()) {
        let [x, y] = turn(j[0], j[1]);
        *j = [x, y, j[2]];
    }
    for o in &mut out.objects {
        let [x, y] = turn(o.center[0], o.center[1]);
        o.center = [x, y, o.center[2]];
        o.yaw += angle;
    }
    out
}

#[test]
fn a_room_at_an_angle_is_sampled_square_to_its_own_walls() {
    // The models learned rooms whose walls run along the axes. A plan turned by 30° is sampled in
    // its own frame (scene::RoomFrame), so even unguided, every piece comes out square to its
    // walls (sampled in the world's frame they stood 22–35° off them) and inside the room: as
    // square as the unguided model draws pieces in an unturned room (a few degrees at most, 0.7°
    // on average, for the shipped bedroom model here).
    let input = Scene::load(root().join("scenes/examples/bedroom_rect.json")).unwrap();
    let angle = 30f64.to_radians();
    let room = turned(&input, angle);
    let model = Generator::new(shade_sim::generator::shipped_model(RoomType::Bedroom).unwrap());
    let layouts = model.generate(std::slice::from_ref(&room), 4, 0).unwrap().remove(0);
    let polygon = room.floor_plan.polygon();
    let mut offs = Vec::new();
    for layout in &layouts {
        assert_eq!((&layout.floor_plan, &layout.humans), (&room.floor_plan, &room.humans), "the input as it was");
        assert!(!layout.objects.is_empty());
        for o in &layout.objects {
            let off = (o.yaw - angle).to_degrees().rem_euclid(90.0);
            offs.push(off.min(90.0 - off));
            assert!(off.min(90.0 - off) < 10.0, "{} {:.1}° off square to its walls", o.id, off.min(90.0 - off));
            let centre = glam::DVec2::new(o.center[0], o.center[1]);
            assert!(polygon.signed_distance(centre) < 0.0, "{} stands outside the room", o.id);
        }
    }
    let mean = offs.iter().sum::<f64>() / offs.len() as f64;
    assert!(mean < 2.0, "pieces {mean:.1}° off square on average");
}

#[test]
fn refining_at_the_least_noise_keeps_the_input_and_needs_its_pieces() {
    let input = Scene::load(root().join("scenes/reference/bedroom_rect.json")).unwrap();
    let shipped = Generator::new(shade_sim::generator::shipped_model(RoomType::Bedroom).unwrap());
    // The chain respaced to its first and last step, refined from the noise of the linear
    // schedule's step 0: one model call at σ 0.8 cm, whose estimate is within centimetres of
    // the input (docs/RESULTS.md, "Where the error enters"). The same make-up, each piece near
    // its own; sampled from pure noise instead, the layout is another.
    let near = |g: &Generator| -> f64 {
        let out = g.generate(std::slice::from_ref(&input), 1, 5).unwrap().remove(0).remove(0);
        let mut cats: Vec<_> = out.objects.iter().map(|o| o.category).collect();
        let mut want: Vec<_> = input.objects.iter().map(|o| o.category).collect();
        cats.sort();
        want.sort();
        if cats != want {
            return f64::INFINITY;
        }
        let dist = |o: &shade_sim::scene::Object| {
            let same = input.objects.iter().filter(|p| p.category == o.category);
            same.map(|p| (p.center[0] - o.center[0]).hypot(p.center[1] - o.center[1])).fold(f64::INFINITY, f64::min)
        };
        out.objects.iter().map(dist).fold(0.0, f64::max)
    };
    let one_step = shipped.clone().with_sampling_steps(2).refining(0.001);
    assert!(near(&one_step) < 0.05, "{}", near(&one_step));
    assert!(near(&shipped.clone().with_sampling_steps(2)) > 0.2);
    // Deterministic for a seed.
    let twice = |g: &Generator| g.generate(std::slice::from_ref(&input), 2, 3).unwrap();
    let refined = shipped.refining(0.1);
    assert_eq!(twice(&refined), twice(&refined));
    // An input without pieces, or a strength outside (0, 1], is refused with one line.
    let empty = root().join("scenes/examples/bedroom_rect.json");
    let dir = tempfile::tempdir().unwrap();
    for (file, strength, said) in [
        (&empty, "0.1", "--refine: the input has no bedroom pieces to refine"),
        (&root().join("scenes/reference/bedroom_rect.json"), "0", "error: --refine: must be a number above 0"),
        (&root().join("scenes/reference/bedroom_rect.json"), "NaN", "error: --refine: must be a number above 0"),
    ] {
        let refine = format!("--refine={strength}");
        let args = ["generate", "--input", file.to_str().unwrap(), "--out", dir.path().to_str().unwrap(), &refine];
        let o = shade_sim(&args);
        assert_eq!(o.status.code(), Some(2), "{strength}");
        assert!(stderr(&o).contains(said) && stderr(&o).lines().count() == 1, "{}", stderr(&o));
    }
}

#[test]
fn a_low_noise_expert_takes_the_last_steps_and_must_fit_its_model() {
    let input = Scene::load(root().join("scenes/examples/bedroom_rect.json")).unwrap();
    let shipped = Generator::new(shade_sim::generator::shipped_model(RoomType::Bedroom).unwrap());
    let layouts = |g: &Generator| g.generate(std::slice::from_ref(&input), 2, 4).unwrap().remove(0);
    // Experts written as a user's training run would leave them: the shipped bedroom weights
    // under an edited config.
    let dir = tempfile::tempdir().unwrap();
    let expert = |name: &str, edit: &dyn Fn(&mut serde_json::Value)| -> PathBuf {
        let out = dir.path().join(name);
        std::fs::create_dir_all(&out).unwrap();
        let shipped = root().join("models/bedroom");
        std::fs::copy(shipped.join("model.safetensors"), out.join("model.safetensors")).unwrap();
        let mut config: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(shipped.join("config.json")).unwrap()).unwrap();
        edit(&mut config);
        std::fs::write(out.join("config.json"), config.to_string()).unwrap();
        out
    };
    let with = |path: &Path| shipped.clone().with_expert(Checkpoint::load(path).unwrap(), path);
    // The model itself as its own expert changes nothing, to the bit.
    let same = expert("same", &|c| c["model"]["expert_below"] = 60.into());
    assert_eq!(layouts(&with(&same).unwrap()), layouts(&shipped));
    // Another denoiser in the last steps (the same weights read as an x₀ model) changes the rooms.
    let other = expert("other", &|c| {
        c["model"]["expert_below"] = 60.into();
        c["model"]["prediction"] = "x0".into();
    });
    assert_ne!(layouts(&with(&other).unwrap()), layouts(&shipped));
    // A model not trained as an expert, or one of another schedule, is refused, naming its folder.
    let whole = expert("whole", &|_| {});
    let err = with(&whole).unwrap_err().to_string();
    assert!(err.starts_with(&whole.display().to_string()) && err.contains("--expert-below"), "{err}");
    let linear = expert("linear", &|c| {
        c["model"]["expert_below"] = 60.into();
        c["model"]["schedule"] = "linear".into();
    });
    assert!(with(&linear).unwrap_err().to_string().contains("does not fit"));
}

#[test]
fn every_shipped_model_runs_the_whole_chain_alone_and_the_weights_stay_small() {
    use shade_sim::generator::{Prediction, shipped_expert, shipped_generator, shipped_model};
    // Three v models on the log-SNR schedule, one per room type, none with a low-noise expert
    // (the living rooms' x₀ model needed one until 2026-12-05: docs/RESULTS.md).
    for room in [RoomType::Bedroom, RoomType::Living, RoomType::Dining] {
        let model = shipped_model(room).unwrap();
        assert_eq!(model.meta.model.prediction, Prediction::V, "{room:?}");
        assert!(shipped_expert(room).unwrap().is_none() && shipped_generator(room).unwrap().expert().is_none());
    }
    // Every shipped weight file together stays within the model issue's 30 MB: three models of
    // about 5.3 MB each.
    let files: Vec<u64> = std::fs::read_dir(root().join("models"))
        .unwrap()
        .map(|d| d.unwrap().path().join("model.safetensors"))
        .filter(|p| p.is_file())
        .map(|p| p.metadata().unwrap().len())
        .collect();
    assert_eq!(files.len(), 3, "{files:?}");
    assert!(files.iter().all(|&b| b > 5_000_000) && files.iter().sum::<u64>() <= 30_000_000, "{files:?}");
}

#[test]
fn the_shipped_dining_model_samples_with_its_own_geometry_eta() {
    let input = Scene::load(root().join("scenes/examples/dining_rect.json")).unwrap();
    let shipped = shade_sim::generator::shipped_model(RoomType::Dining).unwrap();
    let sampling = shipped.meta.sampling.clone().expect("the dining model's sampling defaults");
    assert_eq!(sampling.geometry_eta, 2.0);
    let rooms = |g: &Generator| g.generate(std::slice::from_ref(&input), 2, 6).unwrap();
    // Its default is η 2 on the geometry with the classes on DDPM's chain: the same rooms as
    // the model without the setting asked for it, and others than DDPM's chain everywhere.
    let plain = Checkpoint {
        meta: shade_sim::generator::CheckpointMeta { sampling: None, ..shipped.meta.clone() },
        ..shipped.clone()
    };
    let default = rooms(&Generator::new(shipped.clone()));
    assert_eq!(default, rooms(&Generator::new(plain.clone()).with_geometry_eta(2.0)));
    assert_ne!(default, rooms(&Generator::new(plain.clone())));
    assert_eq!(rooms(&Generator::new(shipped).with_eta(1.0)), rooms(&Generator::new(plain)));
    // A geometry η outside [0, 2] is a bad config; --eta-geometry-only needs --eta.
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("dining");
    std::fs::create_dir_all(&folder).unwrap();
    let models = root().join("models/dining");
    std::fs::copy(models.join("model.safetensors"), folder.join("model.safetensors")).unwrap();
    let mut config: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(models.join("config.json")).unwrap()).unwrap();
    config["sampling"]["geometry_eta"] = serde_json::json!(3.0);
    std::fs::write(folder.join("config.json"), config.to_string()).unwrap();
    let err = Checkpoint::load(&folder).unwrap_err().to_string();
    assert!(err.contains("sampling.geometry_eta 3 is not in [0, 2]"), "{err}");
    let input = root().join("scenes/examples/dining_rect.json");
    let o = shade_sim(&[
        "generate",
        "--input",
        input.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
        "--eta-geometry-only",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn contact_spans_beyond_the_models_slots_are_named_before_sampling() {
    use shade_sim::human::{Body, Motion, sit};
    use shade_sim::scene::{Action, FloorPlan};
    // Ten sitters in a row, five a side of a long table: the dining model anchors eight.
    let plan = FloorPlan { polygon: vec![[0.0, 0.0], [4.5, 0.0], [4.5, 4.0], [0.0, 4.0]], height: 2.7 };
    let mut scene = Scene::new(RoomType::Dining, plan);
    for k in 0..10 {
        let (x, y, yaw) = (0.9 + 0.65 * (k / 2) as f64, if k % 2 == 0 { 1.3 } else { 2.7 }, (k % 2) as f64 * 180.0);
        let mut m = Motion::new(Body::default(), 10.0);
        m.hold(sit(&Body::default(), glam::DVec2::new(x, y), 0.46, yaw.to_radians()), 10, Action::Sit);
        scene.humans.push(m.into_human(format!("h{k}")));
    }
    let dining = Generator::new(shade_sim::generator::shipped_model(RoomType::Dining).unwrap());
    let unseen = dining.unseen_contacts(&scene);
    assert_eq!(unseen.iter().map(|b| b.human.as_str()).collect::<Vec<_>>(), ["h8", "h9"]);
    let note = shade_sim::pipeline::unseen_contacts_message(&unseen, 8).unwrap();
    assert!(note.starts_with("2 contact spans beyond the 8 the model conditions on (h8 sit, h9 sit)"), "{note}");
    // generate says so, once, before it samples.
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("ten.json");
    scene.save(&input).unwrap();
    let out = dir.path().join("out");
    let o = shade_sim(&["generate", "--input", input.to_str().unwrap(), "--out", out.to_str().unwrap(), "--no-repair"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o).matches("contact spans beyond the 8").count(), 1, "{}", stderr(&o));
    // Eight sitters: all seen, nothing said.
    scene.humans.truncate(8);
    assert!(dining.unseen_contacts(&scene).is_empty());
    assert_eq!(shade_sim::pipeline::unseen_contacts_message(&[], 8), None);
}

#[test]
fn a_floor_unlike_any_training_room_is_named_before_sampling() {
    // The shipped dining model's training rooms are 10–40 m², 2.5–7.4 m wide and 3.2–9.4 m long
    // (models/MODEL_CARD.md).
    let mut scene = Scene::load(root().join("tests/inputs/dinner_for_three.json")).unwrap();
    let dining = Generator::new(shade_sim::generator::shipped_model(RoomType::Dining).unwrap());
    assert_eq!(dining.unseen_floor(&scene), None, "4.2 × 3.6 m is a room the model saw");
    assert!(shade_sim::pipeline::input_notes(&dining, &scene).is_empty());
    // An 11 × 3.6 m hall: an area the model saw (39.6 m²), a length it did not.
    scene.floor_plan.polygon = vec![[0.0, 0.0], [11.0, 0.0], [11.0, 3.6], [0.0, 3.6]];
    let unseen = dining.unseen_floor(&scene).expect("11 m is longer than any");
    let beyond: Vec<_> = unseen.beyond.iter().map(|b| (b.measure, b.value, b.seen)).collect();
    assert_eq!(beyond, [(FloorMeasure::Length, 11.0, [3.2, 9.4])]);
    // A 10 × 8 m hall: twice the largest area, wider and longer than any.
    scene.floor_plan.polygon = vec![[-3.0, -2.0], [7.0, -2.0], [7.0, 6.0], [-3.0, 6.0]];
    let unseen = dining.unseen_floor(&scene).expect("80 m² is twice the largest");
    let measures: Vec<_> = unseen.beyond.iter().map(|b| b.measure).collect();
    assert_eq!(measures, [FloorMeasure::Area, FloorMeasure::Width, FloorMeasure::Length]);
    assert_eq!((unseen.beyond[0].value, unseen.beyond[0].seen), (80.0, [10.0, 40.0]));
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("hall.json");
    scene.save(&input).unwrap();
    let out = dir.path().join("out");
    let args = ["--out", out.to_str().unwrap(), "--no-repair", "--guidance", "none"];
    let o = shade_sim(&[&["generate", "--input", input.to_str().unwrap()][..], &args].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let said = "hall.json: the floor plan is unlike the model's dining training rooms: its 80.0 m² is larger than any (10.0–40.0 m²), and it is 8.0 m wide, wider than any (2.5–7.4 m), and it is 10.0 m long, longer than any (3.2–9.4 m); its layouts may be less like real rooms";
    assert_eq!(stderr(&o).matches(said).count(), 1, "{}", stderr(&o));
    // A model folder that does not record its rooms' floors says nothing of them.
    let mut unrecorded = shade_sim::generator::shipped_model(RoomType::Dining).unwrap();
    unrecorded.meta.seen_floors = None;
    assert_eq!(Generator::new(unrecorded).unseen_floor(&scene), None);
    // A folder whose areas are no range is a bad config.
    let folder = dir.path().join("dining");
    std::fs::create_dir_all(&folder).unwrap();
    let models = root().join("models/dining");
    std::fs::copy(models.join("model.safetensors"), folder.join("model.safetensors")).unwrap();
    let mut config: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(models.join("config.json")).unwrap()).unwrap();
    config["seen_floors"]["rooms"][0]["area"] = serde_json::json!([40.0, 10.0]);
    std::fs::write(folder.join("config.json"), config.to_string()).unwrap();
    let err = Checkpoint::load(&folder).unwrap_err().to_string();
    assert!(err.ends_with("seen_floors for dining: area [40, 10] is not a range of m² above 0"), "{err}");
}
