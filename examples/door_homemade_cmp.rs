use mrr_control::sim::door::{door_opening, DoorConfig, DoorControl};
fn main() {
    for (name, c, h) in [("passive", DoorControl::Passive, 0.0), ("heading", DoorControl::Passive, 3f64.to_radians()), ("hold", DoorControl::ActiveHold, 0.0)] {
        let mut v: Vec<f64> = (1..=20).map(|s| door_opening(&DoorConfig::thesis(c, h, s)).peak()).collect();
        v.sort_by(|a, b| a.total_cmp(b));
        println!("{name}: median {:.2} min {:.2} max {:.2} q1 {:.2} q3 {:.2}", 0.5 * (v[9] + v[10]), v[0], v[19], v[5], v[14]);
    }
}
