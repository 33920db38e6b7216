use glam::Vec3;
use nudge::testing::hard_case::{self, Knobs};
fn knobs() -> Knobs {
    let mut k = Knobs::default();
    let f = std::env::var("FIXES").unwrap_or_default();
    if f.contains("noshock") {
        k.fixes.shock_propagation = false;
    }
    if f.contains("nomr") {
        k.fixes.mass_ratio_sweeps = false;
    }
    if f.contains("nospread") {
        k.fixes.spread_row = false;
    }
    if let Ok(s) = std::env::var("SUBSTEPS") {
        k.substeps = s.parse().unwrap();
    }
    if let Ok(s) = std::env::var("ITERS") {
        k.iterations = s.parse().unwrap();
    }
    k
}
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let what = args.get(1).map(|s| s.as_str()).unwrap_or("all");
    if what == "all" || what == "cols" {
        for count in [10, 20, 30, 40, 50] {
            let out = hard_case::stack(count, Vec3::ZERO, 10.0, knobs());
            println!(
                "stack {count}: pen {:.3} mm drift {:.3} mm hover {:.4} mm ms {:.4}",
                out.max_penetration_m * 1e3,
                out.max_drift_m * 1e3,
                out.max_hover_m * 1e3,
                out.ms_per_step
            );
        }
    }
    if what == "all" || what == "pyr" {
        let out = hard_case::pyramid(20, 10.0, knobs());
        println!("pyramid20: {out:?}");
    }
    if what == "all" || what == "mr" {
        let out = hard_case::mass_ratio(10.0, knobs());
        println!("mass_ratio: {out:?}");
    }
    if what == "tl" {
        let n: usize = args[2].parse().unwrap();
        let sleep = args.get(3).map(|s| s == "sleep").unwrap_or(true);
        timeline(n, sleep, 10.0, 15);
    }
    if what == "mrt" {
        mr_timeline();
    }
    if what == "nosleep" {
        let mut k = knobs();
        k.sleep = false;
        for count in [10, 30, 50] {
            let out = hard_case::stack(count, Vec3::ZERO, 10.0, k);
            println!(
                "nosleep stack {count}: pen {:.3} mm drift {:.3} mm hover {:.4} mm",
                out.max_penetration_m * 1e3,
                out.max_drift_m * 1e3,
                out.max_hover_m * 1e3
            );
        }
    }
}

#[allow(dead_code)]
pub fn timeline(count: usize, sleep: bool, seconds: f32, every: usize) {
    use nudge::scene::cases;
    let mut k = knobs();
    k.sleep = sleep;
    let mut world = k.world(&cases::stack(count, Vec3::ZERO));
    let steps = (seconds * 60.0) as usize;
    for s in 0..steps {
        world.step();
        if s % every == 0 || s == steps - 1 {
            let b = world.bodies();
            let mut gaps = vec![];
            let mut y_below = -0.5f32;
            let mut drift = 0.0f32;
            let mut vmax = 0.0f32;
            let mut wmax = 0.0f32;
            for body in b.iter().skip(1) {
                let p = body.pose().position;
                gaps.push((p.y - y_below - 1.0) * 1e3);
                y_below = p.y;
                drift = drift.max((p.x * p.x + p.z * p.z).sqrt());
                vmax = vmax.max(body.linear_velocity().length());
                wmax = wmax.max(body.angular_velocity().length());
            }
            let lowest = gaps.iter().cloned().fold(f32::MAX, f32::min);
            println!(
                "t {:.2} awake {} drift {:.3}mm vmax {:.4} wmax {:.4} lowest gap {:.3}mm gaps0..3 {:?} top {:.3}",
                s as f32 / 60.0,
                world.awake_count(),
                drift * 1e3,
                vmax,
                wmax,
                lowest,
                &gaps[..]
                    .iter()
                    .map(|g| (g * 1000.0).round() / 1000.0)
                    .collect::<Vec<_>>(),
                gaps[gaps.len() - 1]
            );
        }
    }
}

#[allow(dead_code)]
pub fn mr_timeline() {
    use nudge::scene::cases;
    let mut world = knobs().world(&cases::mass_ratio());
    for s in 0..120 {
        world.step();
        if s < 10 || s % 10 == 0 {
            let b = world.bodies();
            println!(
                "step {s} light y {:.5} v {:?} heavy y {:.5} v {:?} w {:?}",
                b[1].pose().position.y,
                b[1].linear_velocity(),
                b[2].pose().position.y,
                b[2].linear_velocity(),
                b[2].angular_velocity()
            );
        }
    }
}
