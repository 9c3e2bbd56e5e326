//! The one place a scene becomes a model: the blocks and joints of the arch (and piers), or
//! the user's blocks as detected, then the loads of `[[loads]]`, `[fill]` and `[seismic]` and
//! the ties of `[[ties]]` placed on those blocks by one path, [`super::placement`].

use super::placement::{self, ArchLayout, Placement, Structure};
use super::{arcade, piers, spandrel, Scene, VoussoirShape};
use crate::assembly::{Assembly, BlockKind, Joint, JointKind};
use crate::error::SceneError;
use crate::geometry::Vec2;
use crate::model::Model;

thread_local! {
    /// Models built on this thread ([`build`] calls): see [`builds_on_this_thread`].
    static BUILDS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// How many models [`build`] has built on the calling thread so far: a test counts the builds
/// an analysis makes (one per analysis, one per step of a thickness search), and the counter
/// costs one increment per build.
pub fn builds_on_this_thread() -> u64 {
    BUILDS.with(std::cell::Cell::get)
}

/// Build the assembly and load case of a scene: the one place a scene becomes a model, run
/// once per analysis (a [`Scene`] holds values only). A tie or strip whose capacity is
/// `"design"` is refused: only a retrofit design sizes it ([`build_for_design`]).
pub fn build(scene: &Scene) -> Result<Model, SceneError> {
    let tie = (scene.ties.iter())
        .position(|t| t.capacity.is_none())
        .map(|k| format!("ties[{k}].capacity"));
    let strip = (scene.reinforcements.iter())
        .position(|r| r.tensile_capacity.is_none())
        .map(|k| format!("reinforcements[{k}].tensile_capacity"));
    if let Some(key) = tie.or(strip) {
        return Err(SceneError::OutOfRange {
            origin: scene.origin.clone(),
            key,
            value: "\"design\"".into(),
            allowed: "a number in N for an analysis: a capacity to be designed is sized by `voussoir retrofit` (run that, or give the capacity)".into(),
        });
    }
    build_model(scene)
}

/// [`build`] for a retrofit design: the ties whose capacity is `"design"` get their
/// prestress as capacity for now, the strips whose `tensile_capacity` is `"design"` 0; the
/// design sizes them.
pub fn build_for_design(scene: &Scene) -> Result<Model, SceneError> {
    build_model(scene)
}

/// The assembly of a scene and the structure loads are placed on.
pub(super) fn structure(scene: &Scene) -> Result<(Assembly, Structure), SceneError> {
    Ok(match (&scene.arch, &scene.blocks) {
        (Some(a), _) => {
            let (assembly, layout) = build_assembly(scene, a)?;
            (assembly, Structure::Arch(layout))
        }
        (None, Some(b)) => (
            b.detected.assembly.clone(),
            Structure::Blocks {
                tolerance: b.detected.tolerance,
                fixed: b
                    .detected
                    .fixed
                    .iter()
                    .map(|f| (f.block, f.polygon.clone()))
                    .collect(),
            },
        ),
        (None, None) => {
            return Err(SceneError::MissingKey {
                origin: scene.origin.clone(),
                key: "arch".into(),
                what: "the [arch] table or [blocks]".into(),
            })
        }
    })
}

/// The height a load standing at each of `xs` stands at (see `Placement::stand`): the fill's
/// road surface when the scene has a fill, the top of the structure otherwise; None where no
/// block's top lies under x (off the structure). A moving load (`crate::roll`) asks this once
/// for all its positions.
pub fn standing_heights(scene: &Scene, xs: &[f64]) -> Result<Vec<Option<f64>>, SceneError> {
    let (assembly, layout) = structure(scene)?;
    let placement = Placement::new(&assembly, layout);
    let surface = scene.fill.as_ref().map(|f| f.dispersal.surface(f.level));
    Ok(xs
        .iter()
        .map(|&x| placement.stand(x, surface).map(|p| p.y))
        .collect())
}

fn build_model(scene: &Scene) -> Result<Model, SceneError> {
    BUILDS.with(|b| b.set(b.get() + 1));
    let strength = crate::model::Strength {
        compressive: scene.material.compressive_strength,
        depth: scene.material.depth,
    };
    let (assembly, layout) = structure(scene)?;
    let placement = Placement::new(&assembly, layout);
    let (loads, ties) = placement::place(scene, &placement)?;
    let passive = match &scene.fill {
        Some(
            fill @ super::FillSpec {
                passive: Some(spec),
                ..
            },
        ) => placement.passive_faces(
            fill.level,
            spec.coefficient() * fill.unit_weight * scene.material.depth,
        ),
        _ => Vec::new(),
    };
    drop(placement);
    let strips = super::reinforcements::strips(&scene.reinforcements, &assembly, &scene.origin)?;
    Ok(Model {
        assembly,
        loads,
        strength,
        ties,
        strips,
        passive,
    })
}

/// The blocks and joints of a parametric scene: one arch or portal (a chain, see
/// [`chain_assembly`]) or an arcade of several bays ([`arcade::assemble`]), then the spandrel
/// wall's pieces after them ([`spandrel::build`]).
fn build_assembly(
    scene: &Scene,
    a: &super::ArchSpec,
) -> Result<(Assembly, ArchLayout), SceneError> {
    let bays = scene.arcade.as_ref().map_or(1, |c| c.bays);
    let (mut assembly, mut layout) = match (&scene.arcade, &scene.piers) {
        (Some(arcade), Some(piers)) if bays > 1 => {
            let g = geometry(scene, a)?;
            let gamma = scene.material.unit_weight * scene.material.depth;
            let curved = a.voussoir_shape == VoussoirShape::Curved;
            let parts = arcade::assemble(&g, curved, piers, arcade, gamma, scene.material.friction);
            (
                Assembly {
                    blocks: parts.blocks,
                    joints: parts.joints,
                },
                ArchLayout {
                    rings: parts.rings,
                    curved,
                    pier_tops: parts.tops,
                    spandrel: false,
                },
            )
        }
        _ => chain_assembly(scene, a)?,
    };
    if let (Some(wall), Some(piers)) = (&scene.spandrel, &scene.piers) {
        let (first_ring, last_ring) = (&layout.rings[0].0, &layout.rings[layout.rings.len() - 1].0);
        let n = first_ring.voussoirs();
        let x_left = first_ring.joints[0].0.x - piers.left.top_width();
        let x_right = last_ring.joints[n].0.x + piers.right.top_width();
        let gamma = scene.material.unit_weight * scene.material.depth;
        let (blocks, joints) = spandrel::build(
            wall,
            &layout.rings,
            &layout.pier_tops,
            x_left,
            x_right,
            assembly.blocks.len(),
            gamma,
            scene.material.friction,
        );
        assembly.blocks.extend(blocks);
        assembly.joints.extend(joints);
        layout.spandrel = true;
    }
    Ok((assembly, layout))
}

/// The ring of the scene's arch, cut with its stereotomy.
fn geometry(
    scene: &Scene,
    a: &super::ArchSpec,
) -> Result<crate::geometry::ArchGeometry, SceneError> {
    a.geometry().map_err(|why| SceneError::OutOfRange {
        origin: scene.origin.clone(),
        key: "arch.joints".into(),
        value: format!("\"{}\"", a.joints.name()),
        allowed: why,
    })
}

/// The blocks and joints of one arch or portal: the left pier courses from the base up, the
/// voussoirs from left to right, the right pier courses from the top down (a chain).
fn chain_assembly(
    scene: &Scene,
    a: &super::ArchSpec,
) -> Result<(Assembly, ArchLayout), SceneError> {
    let g = geometry(scene, a)?;
    let gamma = scene.material.unit_weight * scene.material.depth;
    let mu = scene.material.friction;
    let curved = a.voussoir_shape == VoussoirShape::Curved;
    let n = g.voussoirs();

    let mut blocks = Vec::new();
    let mut joints = Vec::new();
    let (kl, kr) = scene
        .piers
        .as_ref()
        .map_or((0, 0), |p| (p.left.courses, p.right.courses));
    let chain_joint = |p1, p2, idx: usize, last: usize, kind| Joint {
        p1,
        p2,
        from: idx.checked_sub(1),
        to: (idx < last).then_some(idx),
        friction: mu,
        kind,
    };
    let total_blocks = n + kl + kr;
    let mut pier_tops = Vec::new();

    // Left pier, base to top.
    let (xi, xe) = (g.joints[0].0.x, g.joints[0].1.x);
    let (xi_r, xe_r) = (g.joints[n].0.x, g.joints[n].1.x);
    if let Some(p) = &scene.piers {
        for (c, course) in piers::courses(&p.left, xi, -1.0).into_iter().enumerate() {
            blocks.push(arcade::rect_block(
                course.polygon,
                gamma,
                BlockKind::LeftPier(c),
            ));
            let idx = joints.len();
            joints.push(chain_joint(
                course.bed.0,
                course.bed.1,
                idx,
                total_blocks,
                JointKind::LeftPier(c),
            ));
        }
        let b = p.left.top_width();
        if xe > xi - b {
            pier_tops.push((kl - 1, xi - b, xe));
        }
    }
    let first = blocks.len();
    // Arch joints and voussoirs.
    for j in 0..=n {
        let (mut p1, mut p2) = g.joints[j];
        if let Some(p) = &scene.piers {
            // The arch rests on the pier top only where the springing joint lies on it.
            if j == 0 {
                p2 = Vec2::new(xe.max(xi - p.left.top_width()), 0.0);
                p1 = Vec2::new(xi, 0.0);
            } else if j == n {
                p1 = Vec2::new(xi_r, 0.0);
                p2 = Vec2::new(xe_r.min(xi_r + p.right.top_width()), 0.0);
            }
        }
        let idx = joints.len();
        joints.push(chain_joint(p1, p2, idx, total_blocks, JointKind::Arch(j)));
        if j < n {
            blocks.push(arcade::voussoir_block(
                &g,
                j,
                curved,
                gamma,
                BlockKind::Voussoir(j),
            ));
        }
    }
    // Right pier, top to base.
    if let Some(p) = &scene.piers {
        let b = p.right.top_width();
        if xe_r < xi_r + b {
            pier_tops.push((blocks.len(), xe_r, xi_r + b));
        }
        let courses = piers::courses(&p.right, xi_r, 1.0);
        for (c, course) in courses.into_iter().enumerate().rev() {
            blocks.push(arcade::rect_block(
                course.polygon,
                gamma,
                BlockKind::RightPier(c),
            ));
            let idx = joints.len();
            joints.push(chain_joint(
                course.bed.0,
                course.bed.1,
                idx,
                total_blocks,
                JointKind::RightPier(c),
            ));
        }
    }
    let layout = ArchLayout {
        rings: vec![(g, first)],
        curved,
        pier_tops,
        spandrel: false,
    };
    Ok((Assembly { blocks, joints }, layout))
}
