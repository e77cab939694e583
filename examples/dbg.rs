use shade_sim::data::{generate_room, calibrate_scene, Rng, contact_object};
use shade_sim::eval::{FurnitureField, human_penetration, contact_iou};
use shade_sim::human::contact_boxes;
use shade_sim::scene::RoomType;
fn main() {
    for idx in [17u64, 31, 36] {
        let clean = generate_room(RoomType::Bedroom, 1, idx, false);
        let raw = generate_room(RoomType::Bedroom, 1, idx, true);
        let s = &raw.scene;
        let field = FurnitureField::new(&s.objects);
        let h = &s.humans[0];
        let b = contact_boxes(h)[0].clone();
        let cb = contact_boxes(&clean.scene.humans[0])[0].clone();
        let o = &s.objects[raw.contact_objects[0]];
        println!("{idx} {:?} on {} clean epen={:.3} iou={:.3}; raw epen={:.3} iou={:.3} chosen={:?} true={}", b.action, o.category,
            human_penetration(&clean.scene.humans[0], &field), contact_iou(&cb.obox, &s.objects),
            human_penetration(h, &field), contact_iou(&b.obox, &s.objects), contact_object(&s.objects, b.action, &b.obox), raw.contact_objects[0]);
        println!("   raw box {:?}\n   clean box {:?}\n   obj {:?}", b.obox, cb.obox, o.obox());
        let cal = calibrate_scene(s, &mut Rng::new(1));
        println!("   {:?}", cal.humans[0]);
    }
}
