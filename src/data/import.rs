//! `import-3dfront-human`: converts the licensed MIME release of 3D-FRONT HUMAN to shade-scene/1.
//!
//! Each room is a folder holding `boxes.npz` with, as ATISS and MIME store them (y up, object
//! translations and contact boxes relative to `floor_plan_centroid`, half sizes, angles about +y):
//! `class_labels` (N × K one-hot, the room type's categories in our order, extra trailing columns
//! for ATISS's start/end tokens ignored), `translations` (N × 3), `sizes` (N × 3), `angles` (N × 1),
//! `floor_plan_vertices` (V × 3, absolute), `floor_plan_faces` (F × 3 triangle indices),
//! `floor_plan_centroid` (3), and the contact humans' boxes `contact_cls` (M × 3 one-hot of sit, lie,
//! touch, or M integers), `contact_transl`, `contact_sizes`, `contact_angles`.
//!
//! Conversion: (x, y, z) y-up → (x, −z, y) z-up; full sizes (2w, 2d, 2h) from half sizes; yaw =
//! angle + π, because 3D-FUTURE models face +z (y-up), which is −y here, while our fronts face +y.
//! The floor outline is the boundary of the floor mesh. Contact humans are rebuilt as default bodies
//! (1.70 m) in the pose of their class, placed on their box (its centre height taken as the surface
//! they rest on, its centre as the touched point); the release has no walking motions. The ceiling
//! height is not stored and is a parameter.

use super::DataError;
use crate::geom::{Polygon, facing};
use crate::human::{Body, Motion, Side, lie, sit, touch};
use crate::scene::{Action, FloorPlan, Object, RoomType, Scene, validate};
use glam::{DVec2, DVec3};
use npyz::npz::NpzArchive;
use std::collections::HashMap;
use std::path::Path;

fn bad(path: &Path, message: impl Into<String>) -> DataError {
    DataError::NotADataset { path: path.to_path_buf(), message: message.into() }
}

/// An array as (shape, values as f64), whatever its numeric dtype.
fn read(
    archive: &mut NpzArchive<std::io::BufReader<std::fs::File>>,
    path: &Path,
    name: &str,
) -> Result<(Vec<usize>, Vec<f64>), DataError> {
    macro_rules! attempt {
        ($t:ty) => {{
            let file = archive.by_name(name).map_err(|e| bad(path, format!("{name}: {e}")))?;
            let file = file.ok_or_else(|| bad(path, format!("missing array `{name}`")))?;
            let shape: Vec<usize> = file.shape().iter().map(|&s| s as usize).collect();
            if let Ok(v) = file.into_vec::<$t>() {
                return Ok((shape, v.into_iter().map(|x| x as f64).collect()));
            }
        }};
    }
    attempt!(f64);
    attempt!(f32);
    attempt!(i64);
    attempt!(i32);
    attempt!(u8);
    Err(bad(path, format!("array `{name}` is not numeric")))
}

/// y-up (relative to the centroid) → z-up world.
fn to_zup(p: &[f64], centroid: DVec3) -> DVec3 {
    let q = DVec3::new(p[0], p[1], p[2]) + centroid;
    DVec3::new(q.x, -q.z, q.y)
}

/// Rows of a 2-D array (a 1-D array is one column per row).
fn rows(shape: &[usize], values: &[f64]) -> Vec<Vec<f64>> {
    let n = shape.first().copied().unwrap_or(0);
    let k = if shape.len() > 1 { shape[1..].iter().product() } else { 1 };
    (0..n).map(|i| values[i * k..(i + 1) * k].to_vec()).collect()
}

fn argmax(row: &[f64]) -> usize {
    row.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |(i, _)| i)
}

/// The outline of a triangulated floor: its boundary edges chained into the loop of largest area,
/// counter-clockwise, without repeated or collinear vertices.
pub fn floor_outline(vertices: &[DVec2], faces: &[[usize; 3]]) -> Option<Vec<DVec2>> {
    // Merge vertices that coincide (meshes repeat them per face).
    let key = |p: DVec2| ((p.x * 1000.0).round() as i64, (p.y * 1000.0).round() as i64);
    let mut ids: HashMap<(i64, i64), usize> = HashMap::new();
    let mut points = Vec::new();
    let canon: Vec<usize> = vertices
        .iter()
        .map(|&p| {
            *ids.entry(key(p)).or_insert_with(|| {
                points.push(p);
                points.len() - 1
            })
        })
        .collect();
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    let mut directed = Vec::new();
    for f in faces {
        for k in 0..3 {
            let (a, b) = (canon[f[k]], canon[f[(k + 1) % 3]]);
            if a != b {
                *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                directed.push((a, b));
            }
        }
    }
    let mut next: HashMap<usize, usize> = HashMap::new();
    for &(a, b) in &directed {
        if count[&(a.min(b), a.max(b))] == 1 {
            next.insert(a, b);
        }
    }
    let mut best: Option<Vec<DVec2>> = None;
    let mut seen = std::collections::HashSet::new();
    let mut starts: Vec<usize> = next.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        let mut ring = vec![start];
        seen.insert(start);
        let mut cur = start;
        while let Some(&n) = next.get(&cur) {
            if n == start || !seen.insert(n) {
                break;
            }
            ring.push(n);
            cur = n;
        }
        let poly: Vec<DVec2> = ring.iter().map(|&i| points[i]).collect();
        if poly.len() >= 3
            && best.as_ref().is_none_or(|b| Polygon::new(b.clone()).area() < Polygon::new(poly.clone()).area())
        {
            best = Some(poly);
        }
    }
    let mut poly = best?;
    if Polygon::new(poly.clone()).signed_area() < 0.0 {
        poly.reverse();
    }
    // Drop collinear vertices.
    let mut changed = true;
    while changed && poly.len() > 3 {
        changed = false;
        for i in 0..poly.len() {
            let (a, b, c) = (poly[(i + poly.len() - 1) % poly.len()], poly[i], poly[(i + 1) % poly.len()]);
            if (b - a).perp_dot(c - b).abs() < 1e-9 {
                poly.remove(i);
                changed = true;
                break;
            }
        }
    }
    Some(poly)
}

/// Converts one room's `boxes.npz`.
///
/// # Errors
/// [`DataError::NotADataset`] naming the file for a missing or malformed array, an unknown class
/// index, a floor without outline or a scene that does not validate.
pub fn import_room(npz: &Path, room: RoomType, height: f64) -> Result<Scene, DataError> {
    let mut archive = NpzArchive::open(npz).map_err(|e| bad(npz, format!("not an npz archive: {e}")))?;
    let (_, c) = read(&mut archive, npz, "floor_plan_centroid")?;
    if c.len() != 3 {
        return Err(bad(npz, "floor_plan_centroid must hold 3 numbers"));
    }
    let centroid = DVec3::new(c[0], c[1], c[2]);
    let (vs, vv) = read(&mut archive, npz, "floor_plan_vertices")?;
    let (fs, fv) = read(&mut archive, npz, "floor_plan_faces")?;
    let vertices: Vec<DVec2> = rows(&vs, &vv).iter().map(|r| to_zup(r, DVec3::ZERO).truncate()).collect();
    let faces: Vec<[usize; 3]> = rows(&fs, &fv)
        .iter()
        .map(|r| {
            let idx = |k: usize| r.get(k).map(|&x| x as usize).filter(|&i| i < vertices.len());
            match (idx(0), idx(1), idx(2)) {
                (Some(a), Some(b), Some(c)) => Ok([a, b, c]),
                _ => Err(bad(npz, "floor_plan_faces refers to a vertex that does not exist")),
            }
        })
        .collect::<Result<_, _>>()?;
    let outline = floor_outline(&vertices, &faces).ok_or_else(|| bad(npz, "the floor mesh has no outline"))?;
    let mut scene = Scene::new(room, FloorPlan { polygon: outline.iter().map(|p| p.to_array()).collect(), height });

    let categories = room.categories();
    let (ls, lv) = read(&mut archive, npz, "class_labels")?;
    let (ts, tv) = read(&mut archive, npz, "translations")?;
    let (ss, sv) = read(&mut archive, npz, "sizes")?;
    let (as_, av) = read(&mut archive, npz, "angles")?;
    let (labels, trans, sizes, angles) = (rows(&ls, &lv), rows(&ts, &tv), rows(&ss, &sv), rows(&as_, &av));
    if trans.len() != labels.len() || sizes.len() != labels.len() || angles.len() != labels.len() {
        return Err(bad(npz, "class_labels, translations, sizes and angles differ in length"));
    }
    for (i, label) in labels.iter().enumerate() {
        let k = if label.len() == 1 { label[0] as usize } else { argmax(label) };
        if k >= categories.len() {
            if label.len() > categories.len() {
                continue; // ATISS's start / end tokens
            }
            return Err(bad(npz, format!("class index {k} of object {i} is not a {room} category")));
        }
        let (t, s) = (&trans[i], &sizes[i]);
        if t.len() != 3 || s.len() != 3 || angles[i].is_empty() {
            return Err(bad(npz, format!("object {i}: translations and sizes need 3 numbers, angles 1")));
        }
        let center = to_zup(t, centroid);
        scene.objects.push(Object {
            id: format!("o{}", scene.objects.len()),
            category: categories[k],
            center: center.to_array(),
            size: [2.0 * s[0], 2.0 * s[2], 2.0 * s[1]],
            yaw: angles[i][0] + std::f64::consts::PI,
        });
    }

    if archive.by_name("contact_cls").ok().flatten().is_some() {
        let (cs, cv) = read(&mut archive, npz, "contact_cls")?;
        let (xs, xv) = read(&mut archive, npz, "contact_transl")?;
        let (gs, gv) = read(&mut archive, npz, "contact_angles")?;
        let (classes, centers, yaws) = (rows(&cs, &cv), rows(&xs, &xv), rows(&gs, &gv));
        if centers.len() != classes.len() || yaws.len() != classes.len() {
            return Err(bad(npz, "contact_cls, contact_transl and contact_angles differ in length"));
        }
        let body = Body::new(1.70);
        for (j, cls) in classes.iter().enumerate() {
            let k = if cls.len() == 1 { cls[0] as usize } else { argmax(cls) };
            let action = [Action::Sit, Action::Lie, Action::Touch].get(k).copied().ok_or_else(|| {
                bad(npz, format!("contact class {k} of contact {j} is not sit (0), lie (1) or touch (2)"))
            })?;
            let c = to_zup(&centers[j], centroid);
            let yaw = yaws[j].first().copied().unwrap_or(0.0) + std::f64::consts::PI;
            let pose = match action {
                // Our sit box centre lies 6.6 cm ahead of the hips (see human::conditions).
                Action::Sit => sit(&body, c.truncate() - facing(yaw) * 0.066, c.z, yaw),
                Action::Lie => lie(&body, c.truncate(), c.z, yaw),
                _ => touch(&body, c, yaw, Side::Right),
            };
            let mut m = Motion::new(body, 30.0);
            m.hold(pose, 1, action);
            scene.humans.push(m.into_human(format!("h{j}")));
        }
    }
    let problems = validate(&scene);
    if let Some(p) = problems.first() {
        return Err(bad(npz, format!("converted scene is invalid: {p}")));
    }
    Ok(scene)
}

/// Every `boxes.npz` under `dir`, sorted.
fn find_npz(dir: &Path, out: &mut Vec<std::path::PathBuf>) -> Result<(), DataError> {
    let mut entries: Vec<_> =
        std::fs::read_dir(dir).map_err(|e| DataError::io(dir, e))?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            find_npz(&p, out)?;
        } else if p.file_name().is_some_and(|n| n == "boxes.npz") {
            out.push(p);
        }
    }
    Ok(())
}

/// Converts every room under `src` into a dataset in `out` (80/10/10 by a seeded shuffle, files
/// named after the room folders) with `stats.json`; returns the stats.
///
/// # Errors
/// The first room that cannot be converted, naming its file; rooms written before stay complete.
pub fn import_dataset(
    src: &Path,
    out: &Path,
    room: RoomType,
    height: f64,
    seed: u64,
    command: &str,
) -> Result<super::DatasetStats, DataError> {
    let mut files = Vec::new();
    find_npz(src, &mut files)?;
    if files.is_empty() {
        return Err(bad(src, "no boxes.npz found"));
    }
    let split = super::split_of(files.len(), seed);
    let mut splits = std::collections::BTreeMap::new();
    for s in super::DatasetStats::SPLITS {
        std::fs::create_dir_all(out.join(s)).map_err(|e| DataError::io(out.join(s), e))?;
        splits.insert(s.to_string(), super::SplitStats::default());
    }
    for (i, file) in files.iter().enumerate() {
        let scene = import_room(file, room, height)?;
        let folder = file
            .parent()
            .and_then(|p| p.file_name())
            .map_or_else(|| format!("{i:05}"), |n| n.to_string_lossy().into_owned());
        let name: String =
            folder.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
        let target = out.join(split[i]).join(format!("{name}.json"));
        scene.save(&target)?;
        splits.get_mut(split[i]).expect("all splits present").add(&scene);
    }
    let mut stats = super::DatasetStats {
        format: super::DATASET_FORMAT.to_string(),
        room_type: room,
        seed,
        command: command.to_string(),
        raw: true,
        splits,
        category_kl: 0.0,
    };
    stats.category_kl = super::kl_divergence(&super::target_frequencies(room), &stats.all().frequencies(room));
    super::write_stats(&stats, out)?;
    Ok(stats)
}
