//! What the joint tests measure of a world: how far its joints came apart, and whether it is finite.

use nudge::physics::{JointKind, World};

/// The widest gap between the two anchors of any ball, hinge, slider or fixed joint, m (a distance
/// joint's anchors are apart by design).
pub fn widest_joint(world: &World) -> f32 {
    world
        .joints()
        .iter()
        .filter(|j| !matches!(j.desc.kind, JointKind::Distance { .. }))
        .map(|j| {
            let (a, b) = world.joint_anchors(j);
            a.distance(b)
        })
        .fold(0.0, f32::max)
}

/// Every body's pose and velocity, and every joint's load, are finite.
pub fn all_finite(world: &World) -> bool {
    world.bodies().iter().all(|b| {
        b.pose().position.is_finite()
            && b.pose().rotation.is_finite()
            && b.linear_velocity().is_finite()
            && b.angular_velocity().is_finite()
    }) && world.joints().iter().all(|j| {
        let load = world.joint_load(j);
        load.force.is_finite() && load.torque.is_finite() && load.axial.is_finite()
    })
}
