//! Determinism: the same scene and the same inputs give a bit-identical trace, in one process and
//! across processes. The hashes are written here: a change that moves one alters physics traces and
//! must say so in its commit message (then update the constant).
//!
//! The inputs go through the World API at step boundaries, as the sandbox (and a recording of it)
//! applies them: pokes (impulses at a point), pulls (a force held over several steps toward a target
//! point), freezes and unfreezes.

use std::path::PathBuf;
use std::process::Command;

use glam::Vec3;
use nudge::physics::{BodyId, World};
use nudge::scene::builtin::by_name as builtin_scene;

/// Steps each run takes (10 s at 60 Hz).
const STEPS: u64 = 600;

/// FNV-1a, 64 bit: small, fixed and independent of the standard library's hasher (whose algorithm
/// may change between Rust releases and would move the written hashes with it).
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn floats(&mut self, values: &[f32]) {
        for v in values {
            self.bytes(&v.to_bits().to_le_bytes());
        }
    }
}

/// Hashes every body's pose and velocities, bit for bit.
fn hash_state(world: &World, hash: &mut Fnv) {
    for body in world.bodies() {
        let (p, q) = (body.pose().position, body.pose().rotation);
        let (v, w) = (body.linear_velocity(), body.angular_velocity());
        hash.floats(&[p.x, p.y, p.z, q.x, q.y, q.z, q.w]);
        hash.floats(&[v.x, v.y, v.z, w.x, w.y, w.z]);
        hash.bytes(&[u8::from(body.is_sleeping()), u8::from(body.is_static())]);
    }
}

/// The fixed input script at step `step`: one poke, a pull held for half a second, a freeze and its
/// release, and a second poke on another body, spread over the run so sleeping, waking and the
/// frozen body all take part. Bodies are picked by index modulo the body count, skipping body 0
/// (the floor in every built-in scene).
fn apply_inputs(world: &mut World, step: u64) {
    let n = world.len() as u32;
    let pick = |k: u32| BodyId(1 + k % (n - 1));
    let centre = |world: &World, id: BodyId| world.body(id).pose().position;
    match step {
        30 => {
            let id = pick(7);
            let p = centre(world, id) + Vec3::new(0.1, 0.2, 0.0);
            world.apply_impulse_at_point(id, Vec3::new(4.0, 1.0, -2.0), p);
        }
        120..=150 => {
            // A pull: a spring toward a point above and beside the body, as the right mouse button.
            let id = pick(3);
            let p = centre(world, id);
            let target = Vec3::new(1.5, 4.0, 0.5);
            let force = (target - p) * (20.0 * world.body(id).mass());
            world.apply_force_at_point(id, force, p + Vec3::new(0.0, 0.1, 0.05));
        }
        200 => world.set_static(pick(11), true),
        320 => world.set_static(pick(11), false),
        400 => {
            let id = pick(2);
            let p = centre(world, id) + Vec3::new(-0.2, 0.0, 0.15);
            world.apply_impulse_at_point(id, Vec3::new(-3.0, 6.0, 1.0), p);
        }
        _ => {}
    }
}

/// Runs the built-in scene `name` for [`STEPS`] steps under the input script and hashes the trace
/// (the state before the first step and after every step).
fn scripted_trace_hash(name: &str) -> u64 {
    let scene = builtin_scene(name).expect("a built-in scene");
    let mut world = scene.build_world();
    let mut hash = Fnv::new();
    hash_state(&world, &mut hash);
    for step in 0..STEPS {
        apply_inputs(&mut world, step);
        world.step();
        hash_state(&world, &mut hash);
    }
    hash.0
}

/// The pyramid's scripted trace. Moves when the physics changes: say so in the commit message.
const PYRAMID_HASH: u64 = 0x7820_4e15_173b_ea98;
/// The default scene's scripted trace. Moves when the physics changes: say so in the commit message.
const DEFAULT_HASH: u64 = 0x5ee3_e3e5_c707_ffc5;
/// The bytes of `nudge sim --scene pyramid --steps 600 --trace …`. Moves when the physics (or the
/// trace format) changes: say so in the commit message.
const SIM_PYRAMID_TRACE_HASH: u64 = 0x122f_76bb_a803_c7f2;

#[test]
fn the_scripted_pyramid_runs_twice_to_the_same_written_hash() {
    let first = scripted_trace_hash("pyramid");
    let second = scripted_trace_hash("pyramid");
    assert_eq!(first, second, "two runs in one process differ");
    assert_eq!(first, PYRAMID_HASH, "pyramid trace hash {first:#018x}");
}

#[test]
fn the_scripted_default_scene_runs_twice_to_the_same_written_hash() {
    let first = scripted_trace_hash("default");
    let second = scripted_trace_hash("default");
    assert_eq!(first, second, "two runs in one process differ");
    assert_eq!(first, DEFAULT_HASH, "default trace hash {first:#018x}");
}

/// A trace path unique to this test process.
fn temp_trace(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "nudge-determinism-{}-{name}.csv",
        std::process::id()
    ))
}

#[test]
fn nudge_sim_in_two_processes_writes_the_same_written_trace() {
    let mut hashes = Vec::new();
    for run in ["a", "b"] {
        let path = temp_trace(run);
        let output = Command::new(env!("CARGO_BIN_EXE_nudge"))
            .args(["sim", "--scene", "pyramid", "--steps", &STEPS.to_string()])
            .arg("--trace")
            .arg(&path)
            .output()
            .expect("the nudge binary runs");
        let text = std::fs::read(&path);
        let _ = std::fs::remove_file(&path);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let mut hash = Fnv::new();
        hash.bytes(&text.expect("the trace file was written"));
        hashes.push(hash.0);
    }
    assert_eq!(hashes[0], hashes[1], "two processes differ");
    assert_eq!(
        hashes[0], SIM_PYRAMID_TRACE_HASH,
        "sim trace hash {:#018x}",
        hashes[0]
    );
}
