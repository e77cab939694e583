//! `import-3dfront-human` on small npz fixtures written here in the MIME release's layout.

use crate::{shade_sim, stderr};
use shade_sim::data::floor_outline;
use shade_sim::eval::contact_iou;
use shade_sim::human::contact_boxes;
use shade_sim::scene::{Category, Scene};
use std::io::Write;
use std::path::Path;

/// A little-endian f64 .npy file (format 1.0).
fn npy(shape: &[usize], data: &[f64]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend((header.len() as u16).to_le_bytes());
    out.extend(header.as_bytes());
    for x in data {
        out.extend(x.to_le_bytes());
    }
    out
}

fn write_npz(path: &Path, arrays: &[(&str, Vec<usize>, Vec<f64>)]) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut zip = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    let options = zip::write::FileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, shape, data) in arrays {
        zip.start_file(format!("{name}.npy"), options).unwrap();
        zip.write_all(&npy(shape, data)).unwrap();
    }
    zip.finish().unwrap();
}

fn one_hot(k: usize, width: usize) -> Vec<f64> {
    (0..width).map(|i| if i == k { 1.0 } else { 0.0 }).collect()
}

/// A 4 × 3.5 m bedroom: a double bed against the north wall (headboard north), a nightstand, an
/// ATISS end token, and a person lying on the bed. y-up, relative to the centroid (2, 0, −1.75).
fn bedroom(path: &Path, drop: Option<&str>) {
    let mut labels = one_hot(8, 23);
    labels.extend(one_hot(12, 23));
    labels.extend(one_hot(22, 23));
    let arrays = vec![
        ("class_labels", vec![3, 23], labels),
        ("translations", vec![3, 3], vec![0.0, 0.25, -0.65, 1.1, 0.25, -1.5, 0.0, 0.0, 0.0]),
        ("sizes", vec![3, 3], vec![0.8, 0.25, 1.0, 0.2, 0.25, 0.2, 0.1, 0.1, 0.1]),
        ("angles", vec![3, 1], vec![0.0, 0.0, 0.0]),
        ("floor_plan_vertices", vec![4, 3], vec![0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 4.0, 0.0, -3.5, 0.0, 0.0, -3.5]),
        ("floor_plan_faces", vec![2, 3], vec![0.0, 1.0, 2.0, 0.0, 2.0, 3.0]),
        ("floor_plan_centroid", vec![3], vec![2.0, 0.0, -1.75]),
        ("contact_cls", vec![1, 3], vec![0.0, 1.0, 0.0]),
        ("contact_transl", vec![1, 3], vec![0.0, 0.5, -0.75]),
        ("contact_sizes", vec![1, 3], vec![0.3, 0.05, 0.9]),
        ("contact_angles", vec![1, 1], vec![0.0]),
    ];
    let arrays: Vec<_> = arrays.into_iter().filter(|a| Some(a.0) != drop).collect();
    write_npz(path, &arrays);
}

#[test]
fn a_bedroom_converts_to_z_up_full_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let npz = dir.path().join("src/room_a/boxes.npz");
    bedroom(&npz, None);
    let s = shade_sim::data::import_room(&npz, shade_sim::scene::RoomType::Bedroom, 2.7).unwrap();
    assert_eq!(s.floor_plan.polygon, vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.5], [0.0, 3.5]]);
    assert_eq!(s.objects.len(), 2, "the end token is skipped");
    let bed = &s.objects[0];
    assert_eq!(bed.category, Category::DoubleBed);
    assert!((glam::DVec3::from(bed.center) - glam::DVec3::new(2.0, 2.4, 0.25)).length() < 1e-12);
    assert_eq!(bed.size, [1.6, 2.0, 0.5]);
    assert!((bed.yaw - std::f64::consts::PI).abs() < 1e-12, "front faces −y: the headboard is north");
    assert_eq!(s.objects[1].category, Category::Nightstand);
    assert!((glam::DVec3::from(s.objects[1].center) - glam::DVec3::new(3.1, 3.25, 0.25)).length() < 1e-12);
    // The sleeper lies on the bed, head north.
    assert_eq!(s.humans.len(), 1);
    let b = &contact_boxes(&s.humans[0])[0];
    assert!((b.obox.z_range().1 - 0.5).abs() < 1e-3);
    assert!(contact_iou(&b.obox, &s.objects) > 0.99);
    let head = s.humans[0].joint_at(0, 4);
    assert!(head.y > 2.9, "{head}");
}

#[test]
fn the_command_writes_a_dataset_and_rejects_broken_files() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("src");
    for name in ["r1", "r2", "r3"] {
        bedroom(&src.join(name).join("boxes.npz"), None);
    }
    let out = dir.path().join("out");
    let o = shade_sim(&[
        "-q",
        "import-3dfront-human",
        src.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--room",
        "bedroom",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut scenes = Vec::new();
    for split in ["train", "val", "test"] {
        for e in std::fs::read_dir(out.join(split)).unwrap() {
            scenes.push(Scene::load(e.unwrap().path()).unwrap());
        }
    }
    assert_eq!(scenes.len(), 3);
    assert!(out.join("stats.json").exists());

    bedroom(&src.join("r4/boxes.npz"), Some("sizes"));
    let o = shade_sim(&[
        "import-3dfront-human",
        src.to_str().unwrap(),
        "--out",
        dir.path().join("o2").to_str().unwrap(),
        "--room",
        "bedroom",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).trim_end(), format!("error: {}: missing array `sizes`", src.join("r4/boxes.npz").display()));
    std::fs::write(src.join("r4/boxes.npz"), "not a zip").unwrap();
    let o = shade_sim(&[
        "import-3dfront-human",
        src.to_str().unwrap(),
        "--out",
        dir.path().join("o3").to_str().unwrap(),
        "--room",
        "bedroom",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("r4/boxes.npz: not an npz archive"), "{}", stderr(&o));
}

#[test]
fn floor_outline_of_a_fan_triangulated_l_shape() {
    use glam::DVec2;
    // An L-shape split into 4 triangles around an inner vertex, with a duplicated corner.
    let v = [
        DVec2::new(0.0, 0.0),
        DVec2::new(4.0, 0.0),
        DVec2::new(4.0, 2.0),
        DVec2::new(2.0, 2.0),
        DVec2::new(2.0, 4.0),
        DVec2::new(0.0, 4.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(4.0, 0.0),
    ];
    let faces = [[6, 0, 7], [6, 1, 2], [6, 2, 3], [6, 3, 4], [6, 4, 5], [6, 5, 0]];
    let outline = floor_outline(&v, &faces).unwrap();
    let area = shade_sim::geom::Polygon::new(outline.clone()).signed_area();
    assert_eq!(outline.len(), 6);
    assert!((area - 12.0).abs() < 1e-9, "{area}");
}
