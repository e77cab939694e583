//! Motion files from one input: the first byte picks the reader (BVH, `.npy`, `.npz`), the rest
//! is the file. A clip that reads is imported into a 30 m room. Any panic or abort is a finding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use shade_sim::motion::{ImportOptions, bvh::read_bvh, import_clip, npy};
use shade_sim::scene::{FloorPlan, RoomType};

fuzz_target!(|data: &[u8]| {
    let Some((&kind, file)) = data.split_first() else { return };
    let clip = match kind % 3 {
        0 => match std::str::from_utf8(file) {
            Ok(text) => read_bvh(text),
            Err(_) => return,
        },
        1 => npy::read_npy(file, 30.0),
        _ => npy::read_npz(file, 30.0),
    };
    let Ok(clip) = clip else { return };
    let floor = FloorPlan { polygon: vec![[-15.0, -15.0], [15.0, -15.0], [15.0, 15.0], [-15.0, 15.0]], height: 2.8 };
    let _ = import_clip(&clip, 0, &ImportOptions::new(RoomType::Living, floor));
});
