//! Exhaustive search over the one-degree-of-freedom hinge mechanisms of a chain of blocks
//! (families in the module docs of [`crate::kinematic`]).
//!
//! # Cost and the exact pruning of the four-hinge family
//! With N joints there are C(N,4) joint quadruples and 16 hinge-end patterns each (C(129,4) *
//! 16 = 1.8e8 for a 128-voussoir arch). The relative rotations of a four-hinge mechanism are
//! the cofactors `c_A = T(b,c,d)`, `c_B = -T(a,c,d)`, `c_C = T(a,b,d)`, `c_D = -T(a,b,c)`
//! (`T` = twice the signed area of a triangle), and admissibility is a sign condition on each:
//! a hinge at p2 needs `sigma c > 0`, at p1 `sigma c < 0`, with one common orientation sigma.
//! The key observation is that the rotation of each hinge does *not* depend on where that
//! hinge is: `c_A` depends on b, c, d only. So the sign of every triangle `T(p,q,r)` of three
//! joints, for each of their 2^3 end choices, is computed once (a byte per joint triple, C(N,3)
//! of them), and the admissible (pattern, sigma) pairs of a quadruple are the bitwise AND of
//! four 16-bit masks read from 256-entry tables indexed by those bytes (the sigma = -1 masks
//! are the complements). Nothing is approximated: a pattern is discarded only when one of its
//! four sign conditions fails, and whenever a triangle's area is within round-off of zero
//! (collinear hinge points, e.g. along a pier face) the quadruple falls back to the direct
//! evaluation of all 16 patterns with a tolerance. Only the survivors (typically the two
//! alternating intrados/extrados patterns) get their virtual work evaluated, in O(1) from
//! prefix sums of the load resultants (`kinematic::Sums`) along the chain.
//!
//! The two-hinges-one-open family (N C(N-1,2) joint choices times 4 end patterns) uses the
//! closed forms of its cofactors: with the open joint's line through p with unit normal n and
//! hinges h1, h2, the relative rotations are `(p - h2).n` and `(h1 - p).n`, and the open
//! joint's relative motion is the rotation `(h2 - h1).n` about p plus the normal translation
//! `-T(h1, h2, p)`.

use super::{
    motion_work, solve_motion, Act, Active, Extremes, Family, KinematicError, KinematicResult,
    KinematicSettings, Mechanism, Search, Sums, ADMISSIBLE_TOL,
};
use crate::assembly::{Assembly, Hinge, JointEnd};
use crate::geometry::{cross, Vec2};
use crate::model::Model;
use crate::statics::{StaticResult, Status};
use rayon::prelude::*;
use std::time::Instant;

/// The active joints of a mechanism, for comparisons and tie-breaking: joint indices in chain
/// order and what each does (0 = hinge at p1, 1 = hinge at p2, 2 = open).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Key {
    joints: [u32; 4],
    acts: [u8; 4],
    count: u8,
}

const OPEN: u8 = 2;

impl Key {
    fn new(items: &[(usize, u8)]) -> Key {
        let mut k = Key {
            joints: [u32::MAX; 4],
            acts: [0; 4],
            count: items.len() as u8,
        };
        for (i, &(j, a)) in items.iter().enumerate() {
            k.joints[i] = j as u32;
            k.acts[i] = a;
        }
        k
    }
    pub(crate) fn items(&self) -> impl Iterator<Item = (usize, u8)> + '_ {
        (0..self.count as usize).map(|i| (self.joints[i] as usize, self.acts[i]))
    }

    /// The key with joint k renamed `joints[k]` (from a restricted chain to the full one; the
    /// map is increasing, so chain order and tie-breaking are kept).
    fn mapped(&self, joints: &[usize]) -> Key {
        let mut k = *self;
        for j in k.joints.iter_mut().take(self.count as usize) {
            *j = joints[*j as usize] as u32;
        }
        k
    }
}

/// The chain's joints and the prefix sums of its blocks, with the load direction.
pub(crate) struct Chain {
    /// `p[e][j]`: end e (0 = p1, 1 = p2) of joint j.
    p: [Vec<Vec2>; 2],
    normal: Vec<Vec2>,
    len: Vec<f64>,
    /// `pre[k]`: sums over blocks `0..k`.
    pre: Vec<Sums>,
    /// Size of the structure (m), for round-off thresholds.
    size: f64,
    /// Whether both ends are supported.
    closed: bool,
    /// Tie rods, with the place of their anchored blocks along the chain.
    ties: Vec<ChainTie>,
    /// Bonded strips: the tensile capacity at each joint's ends `[p1, p2]` (N), empty
    /// without strips.
    strips: Vec<[f64; 2]>,
    /// The fill's passive faces, with the place of their blocks along the chain (as a tie's
    /// anchors), empty without `[fill] passive`.
    passive: Vec<(crate::model::Passive, usize)>,
}

/// The twist of the block after `slot` chain joints (see [`ChainTie`]) in the motion `m` of
/// the active joints `js`: the running sum of the relative twists before it; the bodies
/// before the first active joint, and after the last on a two-support chain, are fixed.
fn twist_at_slot(
    slot: Option<usize>,
    js: &[usize],
    m: &super::Motion,
    closed: bool,
) -> super::Twist {
    let Some(slot) = slot else { return [0.0; 3] };
    // Active joints before the block.
    let k = js.partition_point(|&j| j < slot);
    if k == 0 || (closed && k == js.len()) {
        return [0.0; 3];
    }
    let mut t = [0.0; 3];
    for r in &m.rel[..k] {
        for (tc, rc) in t.iter_mut().zip(r) {
            *tc += rc;
        }
    }
    t
}

/// A tie rod of a chain: the tie, and for each anchor (from, to) the number of chain joints
/// before its block (`slot`: block b of the full chain lies after joints 0..=b, so
/// `slot = b + 1`; None for the ground). A mechanism's body k, between its active joints
/// `js[k]` and `js[k + 1]`, holds the block when `js[k] < slot <= js[k + 1]`.
#[derive(Debug, Clone)]
struct ChainTie {
    tie: crate::model::Tie,
    slots: [Option<usize>; 2],
}

impl ChainTie {
    /// The tie's dissipation (`crate::interaction::tie`) in the motion `m` of the active joints
    /// `js` (chain order, `count` of them): body twists are the running sums of the relative
    /// twists; the bodies before the first active joint, and after the last on a two-support
    /// chain, are fixed.
    fn dissipation(&self, js: &[usize], m: &super::Motion, closed: bool) -> f64 {
        let twists = self.slots.map(|s| twist_at_slot(s, js, m, closed));
        let rate = self.tie.elongation_rate(|block, q| {
            let t = if block == self.tie.from.block {
                twists[0]
            } else {
                twists[1]
            };
            super::velocity(t, q)
        });
        self.tie.dissipation(rate)
    }
}

impl Chain {
    fn new(model: &Model, sign: f64, closed: bool) -> Chain {
        let a = &model.assembly;
        let mut pre = Vec::with_capacity(a.blocks.len() + 1);
        let mut s = Sums::default();
        pre.push(s);
        for i in 0..a.blocks.len() {
            s = s + Sums::of_block(&model.loads, i, sign);
            pre.push(s);
        }
        Chain {
            p: [
                a.joints.iter().map(|j| j.p1).collect(),
                a.joints.iter().map(|j| j.p2).collect(),
            ],
            normal: a.joints.iter().map(|j| j.normal()).collect(),
            len: a.joints.iter().map(|j| j.length()).collect(),
            pre,
            size: a.size(),
            closed,
            ties: model
                .ties
                .iter()
                .map(|t| ChainTie {
                    tie: t.clone(),
                    slots: [t.from.block.map(|b| b + 1), t.to.block.map(|b| b + 1)],
                })
                .collect(),
            strips: if model.strips.is_empty() {
                Vec::new()
            } else {
                let mut s = vec![[0.0; 2]; a.joints.len()];
                for strip in &model.strips {
                    s[strip.joint][strip.end as usize] += strip.capacity;
                }
                s
            },
            passive: model.passive.iter().map(|p| (*p, p.block + 1)).collect(),
        }
    }

    /// A two-support chain of sections `(p1, p2)` with the material `segments[k]` between
    /// sections k and k + 1.
    pub(crate) fn from_sections(sections: &[(Vec2, Vec2)], segments: &[Sums], size: f64) -> Chain {
        let mut pre = Vec::with_capacity(segments.len() + 1);
        let mut s = Sums::default();
        pre.push(s);
        for g in segments {
            s = s + *g;
            pre.push(s);
        }
        let normal = sections
            .iter()
            .map(|(p1, p2)| {
                let d = (p2 - p1).normalize();
                Vec2::new(d.y, -d.x)
            })
            .collect();
        Chain {
            p: [
                sections.iter().map(|s| s.0).collect(),
                sections.iter().map(|s| s.1).collect(),
            ],
            normal,
            len: sections.iter().map(|(p1, p2)| (p2 - p1).norm()).collect(),
            pre,
            size,
            closed: true,
            ties: Vec::new(),
            strips: Vec::new(),
            passive: Vec::new(),
        }
    }

    pub(crate) fn joints(&self) -> usize {
        self.len.len()
    }

    /// The two-support chain restricted to the joints `keep` (increasing): the mechanisms of
    /// the result are exactly the mechanisms of `self` whose active joints are all in `keep`
    /// (joint k of the result is joint `keep[k]`). The body between two kept joints is every
    /// block between them, since `pre` is indexed by joint (`pre[j]` = blocks before joint j).
    fn restricted(&self, keep: &[usize]) -> Chain {
        debug_assert!(self.closed && keep.windows(2).all(|w| w[0] < w[1]));
        let pick = |v: &Vec<Vec2>| keep.iter().map(|&j| v[j]).collect::<Vec<_>>();
        Chain {
            p: [pick(&self.p[0]), pick(&self.p[1])],
            normal: pick(&self.normal),
            len: keep.iter().map(|&j| self.len[j]).collect(),
            pre: keep.iter().map(|&j| self.pre[j]).collect(),
            size: self.size,
            closed: true,
            // Block b lies after the kept joints `<= b`: its slot counts them.
            ties: self
                .ties
                .iter()
                .map(|t| ChainTie {
                    tie: t.tie.clone(),
                    slots: t.slots.map(|s| s.map(|s| keep.partition_point(|&j| j < s))),
                })
                .collect(),
            strips: if self.strips.is_empty() {
                Vec::new()
            } else {
                keep.iter().map(|&j| self.strips[j]).collect()
            },
            passive: self
                .passive
                .iter()
                .map(|&(p, s)| (p, keep.partition_point(|&j| j < s)))
                .collect(),
        }
    }

    /// Sums of the blocks between joints `j1 < j2` (blocks `j1..j2`).
    #[inline]
    fn body(&self, j1: usize, j2: usize) -> Sums {
        self.pre[j2] - self.pre[j1]
    }

    fn active(&self, j: usize, act: u8) -> Active {
        Active {
            p1: self.p[0][j],
            p2: self.p[1][j],
            act: match act {
                0 => Act::Hinge(JointEnd::P1),
                1 => Act::Hinge(JointEnd::P2),
                _ => Act::Open,
            },
        }
    }

    /// Direct evaluation of any candidate: `(A, G)` if admissible.
    pub(crate) fn evaluate(&self, key: &Key) -> Option<(f64, f64, super::Motion)> {
        let count = key.count as usize;
        let mut actives = [Active {
            p1: Vec2::zeros(),
            p2: Vec2::zeros(),
            act: Act::Open,
        }; 4];
        let mut js = [0usize; 4];
        for (k, (j, a)) in key.items().enumerate() {
            actives[k] = self.active(j, a);
            js[k] = j;
        }
        let m = solve_motion(&actives[..count], self.closed)?;
        let mut bodies = [Sums::default(); 4];
        for k in 0..count - 1 {
            bodies[k] = self.body(js[k], js[k + 1]);
        }
        let nbodies = if self.closed {
            count - 1
        } else {
            bodies[count - 1] = self.body(js[count - 1], self.pre.len() - 1);
            count
        };
        let (ax, mut g) = motion_work(&m, &bodies[..nbodies]);
        for t in &self.ties {
            g += t.dissipation(&js[..count], &m, self.closed);
        }
        if !self.strips.is_empty() {
            for (k, &j) in js[..count].iter().enumerate() {
                g += self.strip_dissipation(j, m.rel[k]);
            }
        }
        // The fill's passive faces (`crate::interaction::passive`): the cap times the rate
        // at which the face's point moves into the fill.
        for (face, slot) in &self.passive {
            let t = twist_at_slot(Some(*slot), &js[..count], &m, self.closed);
            g += face.dissipation(super::velocity(t, face.point).x);
        }
        Some((ax, g, m))
    }

    /// The bonded strips' dissipation at joint `j` whose relative motion is the twist `rel`
    /// (`crate::interaction::strip`): each reinforced end opening at the normal rate `vn`
    /// dissipates its capacity times `max(vn, 0)`.
    fn strip_dissipation(&self, j: usize, rel: super::Twist) -> f64 {
        let Some(caps) = self.strips.get(j) else {
            return 0.0;
        };
        (0..2)
            .filter(|&e| caps[e] > 0.0)
            .map(|e| {
                caps[e]
                    * super::velocity(rel, self.p[e][j])
                        .dot(&self.normal[j])
                        .max(0.0)
            })
            .sum()
    }

    /// Whether the chain has tie rods, bonded strips or passive fill (the searches' closed
    /// forms then hand every admissible mechanism to [`Chain::evaluate`], which adds their
    /// dissipation).
    fn has_dissipation(&self) -> bool {
        !self.ties.is_empty() || !self.strips.is_empty() || !self.passive.is_empty()
    }
}

/// Whether `a` is a one-support chain: joint k joins block k - 1 (ground for k = 0) to block
/// k, and the last block is free.
pub fn is_column(a: &Assembly) -> bool {
    let nb = a.blocks.len();
    a.joints.len() == nb
        && a.joints
            .iter()
            .enumerate()
            .all(|(k, j)| j.from == k.checked_sub(1) && j.to == Some(k))
}

/// Discrete kinematic analysis of a chain assembly: the least multiplier over all admissible
/// one-degree-of-freedom mechanisms whose hinges sit at joint ends.
pub fn analyse(
    model: &Model,
    settings: &KinematicSettings,
) -> Result<KinematicResult, KinematicError> {
    let start = Instant::now();
    let assembly = &model.assembly;
    let closed = chain_kind(model)?;
    let nj = assembly.joints.len();
    if nj > settings.max_joints {
        return Err(KinematicError::TooManyJoints {
            joints: nj,
            max: settings.max_joints,
        });
    }
    let chain = Chain::new(model, settings.direction.sign(), closed);
    let (ext, candidates) = if closed {
        search_closed(&chain, settings.parallel)
    } else {
        search_column(&chain)
    };
    let (status, key) = ext.verdict();
    Ok(result(
        assembly,
        &chain,
        &ext,
        status,
        key,
        candidates,
        settings,
        (
            Search::Exhaustive,
            nj,
            (!chain.ties.is_empty()).then(|| TIED_FAMILIES.to_string()),
        ),
        start,
    ))
}

/// What the exhaustive search covers on a chain with tie rods.
const TIED_FAMILIES: &str = "with tie rods the search covers the hinge families of the chain, each valued with the ties' dissipation; a tie that keeps its length at collapse (a force below its capacity) makes the collapse mechanism one of more hinges, outside those families, so lambda_upper is then an upper bound above the collapse multiplier (the certified mechanism, the default, covers that case)";

/// Whether the model is a two-support chain (true) or a one-support column (false).
fn chain_kind(model: &Model) -> Result<bool, KinematicError> {
    let assembly = &model.assembly;
    model.validate()?;
    if assembly.is_chain() {
        Ok(true)
    } else if is_column(assembly) {
        Ok(false)
    } else {
        Err(KinematicError::NotAChain)
    }
}

/// The result of a search whose extremes are `ext` (keys of the full chain) and verdict
/// `(status, key)`.
#[allow(clippy::too_many_arguments)]
fn result(
    assembly: &Assembly,
    chain: &Chain,
    ext: &Extremes<Key>,
    status: Status,
    key: Option<Key>,
    candidates: u64,
    settings: &KinematicSettings,
    (search, searched_joints, note): (Search, usize, Option<String>),
    start: Instant,
) -> KinematicResult {
    KinematicResult {
        status,
        lambda_upper: if status == Status::Collapse {
            ext.best.as_ref().map(|b| b.0)
        } else {
            None
        },
        lambda_signed: ext.best.as_ref().map(|b| b.0),
        lambda_needed: ext.needed.as_ref().map(|b| b.0),
        mechanism: key.and_then(|k| mechanism_of(assembly, chain, &k)),
        direction: settings.direction,
        candidates,
        admissible: ext.admissible,
        wall_time_s: start.elapsed().as_secs_f64(),
        search,
        searched_joints,
        note,
    }
}

/// Local kinematic search (module docs of [`crate::kinematic`]): the exhaustive search of
/// [`analyse`] restricted to the mechanisms whose active joints all lie within `window`
/// joints of a hinge, open or sliding joint of the static solution `around` (which must be at
/// collapse, for the same load direction). Its `lambda_upper` is an upper bound of the
/// collapse multiplier, flagged [`Search::Local`]. When the window covers every joint this is
/// the exhaustive search and is flagged so. `settings.max_joints` limits the joints searched.
///
/// Errors: [`KinematicError::LocalNeedsCollapse`], [`KinematicError::LocalNoCentres`],
/// [`KinematicError::LocalFoundNothing`] (no mechanism driven by the load in the window: no
/// bound, and no claim of `NoCollapse`), besides those of [`analyse`].
pub fn analyse_local(
    model: &Model,
    around: &StaticResult,
    settings: &KinematicSettings,
    window: usize,
) -> Result<KinematicResult, KinematicError> {
    let start = Instant::now();
    if around.status != Status::Collapse {
        return Err(KinematicError::LocalNeedsCollapse(around.status.as_str()));
    }
    let assembly = &model.assembly;
    let nj = assembly.joints.len();
    if !chain_kind(model)? {
        // A one-support chain has 2 N candidates: search them all.
        return analyse(
            model,
            &KinematicSettings {
                max_joints: nj,
                ..settings.clone()
            },
        );
    }
    let mut centres: Vec<usize> = around
        .hinges
        .iter()
        .map(|h| h.joint)
        .chain(around.open.iter().copied())
        .chain(around.sliding.iter().copied())
        .filter(|&j| j < nj)
        .collect();
    centres.sort_unstable();
    centres.dedup();
    if centres.is_empty() {
        return Err(KinematicError::LocalNoCentres);
    }
    let mut inside = vec![false; nj];
    for &c in &centres {
        for f in &mut inside[c.saturating_sub(window)..(c + window + 1).min(nj)] {
            *f = true;
        }
    }
    let keep: Vec<usize> = (0..nj).filter(|&j| inside[j]).collect();
    if keep.len() == nj {
        return analyse(model, settings);
    }
    if keep.len() > settings.max_joints {
        return Err(KinematicError::TooManyJoints {
            joints: keep.len(),
            max: settings.max_joints,
        });
    }
    let chain = Chain::new(model, settings.direction.sign(), true);
    let (ext, candidates) = search_closed(&chain.restricted(&keep), settings.parallel);
    let ext = ext.map_keys(|k| k.mapped(&keep));
    let (status, key) = ext.verdict();
    if status == Status::NoCollapse {
        return Err(KinematicError::LocalFoundNothing {
            joints: keep.len(),
            total: nj,
            window,
        });
    }
    let list = centres
        .iter()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let note = format!(
        "local search: {} of {nj} joints, those within {window} of the static solution's hinge, open or sliding joints {list}; lambda_upper is an upper bound from the best admissible mechanism found, not an exhaustive search",
        keep.len()
    );
    Ok(result(
        assembly,
        &chain,
        &ext,
        status,
        key,
        candidates,
        settings,
        (Search::Local, keep.len(), Some(note)),
        start,
    ))
}

/// What both certificates ([`certify`], [`certify_crushing`]) ask first: a static collapse,
/// on a chain between two supports (a one-support chain has no four-hinge mechanism).
fn four_hinge_chain(model: &Model, around: &StaticResult) -> Result<(), KinematicError> {
    if around.status != Status::Collapse {
        return Err(KinematicError::LocalNeedsCollapse(around.status.as_str()));
    }
    if !chain_kind(model)? {
        return Err(KinematicError::NotCertified(
            "a one-support chain has no four-hinge mechanism".into(),
        ));
    }
    Ok(())
}

/// The upper bound certified by the static solution `around` at collapse (issue: both bounds
/// at the physical limit): at a non-degenerate optimum the static solution has four tight
/// no-tension rows: four hinges, or two hinges and a joint that carries nothing (it opens), or
/// two such joints; by complementary slackness they are the active joints of the governing
/// mechanism. When the resultants touch a fifth joint end within the hinge tolerance, the
/// four hinges are read from the mechanism of the program's duals instead. That mechanism is
/// rebuilt here from the joint points alone (cofactor kinematics, as in the exhaustive
/// search), checked for admissibility (every hinge opens), and its multiplier
/// computed by virtual work from the load case, independently of the static program: any
/// admissible mechanism bounds the collapse multiplier from above, so when it equals the static
/// multiplier the collapse multiplier is certified. Cost: linear in the number of blocks.
///
/// Errors with [`KinematicError::NotCertified`] when the static solution is degenerate (not
/// one of those patterns, or sliding joints), when the mechanism is not admissible, or
/// when the load does no work on it; the caller then falls back to a search.
pub fn certify(
    model: &Model,
    around: &StaticResult,
    settings: &KinematicSettings,
) -> Result<KinematicResult, KinematicError> {
    let start = Instant::now();
    four_hinge_chain(model, around)?;
    if !around.sliding.is_empty() || around.open.len() > 2 {
        return Err(KinematicError::NotCertified(format!(
            "the static solution has {} open and {} sliding joints",
            around.open.len(),
            around.sliding.len()
        )));
    }
    // Ties whose force lies strictly between their bounds do not stretch in the collapse
    // mechanism: each is one more constraint, met by one more hinge.
    let held = held_ties(model, around);
    if !held.is_empty() {
        return certify_held(model, around, settings, &held, start);
    }
    // A joint that carries nothing opens completely: with one open joint the mechanism has two
    // hinges (two bodies), with two open joints none (one body lifts off). Either way the
    // vertex has four tight rows (an open joint's two no-tension rows, two per hinge).
    let wanted = 4 - 2 * around.open.len();
    let mut items = match hinges_from_forces(model, around, wanted) {
        Ok(items) => items,
        // A thrust line that touches a fifth joint within the hinge tolerance (a symmetric
        // arch near its minimum thickness) is degenerate only in appearance when the static
        // program's duals name four hinges: read them from its mechanism.
        Err(e) if wanted == 4 => hinges_from_velocities(model, &around.mechanism).ok_or(e)?,
        Err(e) => return Err(e),
    };
    items.extend(around.open.iter().map(|&j| (j, OPEN)));
    items.sort_unstable();
    if items.windows(2).any(|w| w[0].0 == w[1].0) {
        return Err(KinematicError::NotCertified(
            "the static solution has a hinge at an open joint".into(),
        ));
    }
    let key = Key::new(&items);
    let chain = Chain::new(model, settings.direction.sign(), true);
    let Some((a, g, _)) = chain.evaluate(&key) else {
        return Err(KinematicError::NotCertified(
            "the mechanism of the static hinges is not admissible".into(),
        ));
    };
    if a <= 0.0 {
        return Err(KinematicError::NotCertified(
            "the seismic load does no work on the mechanism of the static hinges".into(),
        ));
    }
    let mut ext = Extremes::new();
    ext.push(a, g, || key);
    let (status, key) = ext.verdict();
    let lambda = g / a;
    let note = format!(
        "certified: the mechanism of the static hinges (joints {}) has lambda = {lambda:.10} by virtual work",
        items
            .iter()
            .map(|&(j, act)| if act == OPEN {
                format!("{j} open")
            } else {
                j.to_string()
            })
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(result(
        &model.assembly,
        &chain,
        &ext,
        status,
        key,
        1,
        settings,
        (Search::Certified, 4, Some(note)),
        start,
    ))
}

/// The ties whose force in the static solution lies strictly between the prestress and the
/// capacity (beyond the solver's accuracy): in the collapse mechanism they keep their length.
fn held_ties(model: &Model, around: &StaticResult) -> Vec<usize> {
    model
        .ties
        .iter()
        .zip(&around.ties)
        .enumerate()
        .filter(|(_, (t, f))| {
            let slack = crate::interaction::tie::YIELD_TOLERANCE * t.capacity.max(f.force);
            f.force > t.prestress + slack && f.force < t.capacity - slack
        })
        .map(|(k, _)| k)
        .collect()
}

/// [`certify`] when tie rods `held` keep their length at collapse: a chain between two
/// supports with `4 + held` hinges at the static solution's hinges moves with one degree of
/// freedom when its bodies' twists close (three equations) and no held tie stretches (one
/// equation each). With rotations `c_k` about the hinges `h_k`, body i turns with the twist
/// `sum_{k <= i} c_k (1, h_y, -h_x)`; the equations are linear in `c`, and the mechanism is
/// the null vector of their `(3 + t) x (4 + t)` matrix, its signed maximal minors. It is
/// admissible when every hinge opens on its free side (one common orientation), and its
/// multiplier is `(G + D)/A` with `D` the yielding ties' dissipation.
fn certify_held(
    model: &Model,
    around: &StaticResult,
    settings: &KinematicSettings,
    held: &[usize],
    start: Instant,
) -> Result<KinematicResult, KinematicError> {
    let not = |why: String| KinematicError::NotCertified(why);
    if !around.open.is_empty() {
        return Err(not(format!(
            "the static solution has {} open joints besides {} ties that keep their length",
            around.open.len(),
            held.len()
        )));
    }
    let wanted = 4 + held.len();
    let items = hinges_from_forces(model, around, wanted)?;
    let chain = Chain::new(model, settings.direction.sign(), true);
    let js: Vec<usize> = items.iter().map(|&(j, _)| j).collect();
    let points: Vec<Vec2> = items.iter().map(|&(j, e)| chain.p[e as usize][j]).collect();
    let m = points.len();
    // The twist of the body holding block slot `slot` when only hinge k turns, at unit rate.
    let unit_twist = |slot: Option<usize>, k: usize| -> super::Twist {
        let Some(slot) = slot else { return [0.0; 3] };
        let before = js.partition_point(|&j| j < slot);
        if before == 0 || before == m || k >= before {
            [0.0; 3]
        } else {
            super::rot(points[k])
        }
    };
    let rate_of = |t: &ChainTie, twist: &dyn Fn(Option<usize>) -> super::Twist| {
        let tw = [twist(t.slots[0]), twist(t.slots[1])];
        t.tie.elongation_rate(|block, q| {
            let i = usize::from(block != t.tie.from.block);
            super::velocity(tw[i], q)
        })
    };
    let rows = 3 + held.len();
    let mut a = nalgebra::DMatrix::<f64>::zeros(rows, m);
    for k in 0..m {
        let r = super::rot(points[k]);
        for (row, v) in r.iter().enumerate() {
            a[(row, k)] = *v;
        }
        for (i, &t) in held.iter().enumerate() {
            a[(3 + i, k)] = rate_of(&chain.ties[t], &|slot| unit_twist(slot, k));
        }
    }
    // The null vector by signed maximal minors.
    let mut c: Vec<f64> = (0..m)
        .map(|k| {
            let minor = a.clone().remove_column(k);
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            sign * minor.determinant()
        })
        .collect();
    let cmax = c.iter().fold(0.0_f64, |s, x| s.max(x.abs()));
    if !(cmax > 0.0 && cmax.is_finite()) {
        return Err(not(
            "the hinges and the ties that keep their length lock the chain".into(),
        ));
    }
    let tol = ADMISSIBLE_TOL * cmax;
    // A hinge at p2 turns positively, at p1 negatively (times one common orientation).
    let wants = |k: usize| if items[k].1 == 1 { 1.0 } else { -1.0 };
    let sigma = if (0..m).all(|k| wants(k) * c[k] >= -tol) {
        1.0
    } else if (0..m).all(|k| wants(k) * c[k] <= tol) {
        -1.0
    } else {
        return Err(not(
            "the mechanism of the static hinges with the held ties is not admissible".into(),
        ));
    };
    for x in &mut c {
        *x *= sigma / cmax;
    }
    let body_twist = |i: usize| -> super::Twist {
        let mut t = [0.0; 3];
        for k in 0..=i {
            let r = super::rot(points[k]);
            for (tc, rc) in t.iter_mut().zip(r) {
                *tc += c[k] * rc;
            }
        }
        t
    };
    let (mut ax, mut g) = (0.0, 0.0);
    for i in 0..m - 1 {
        let (wa, wg) = super::work(body_twist(i), chain.body(js[i], js[i + 1]));
        ax += wa;
        g += wg;
    }
    let twist_of = |slot: Option<usize>| -> super::Twist {
        let Some(slot) = slot else { return [0.0; 3] };
        let before = js.partition_point(|&j| j < slot);
        if before == 0 || before == m {
            [0.0; 3]
        } else {
            body_twist(before - 1)
        }
    };
    let d: f64 = chain
        .ties
        .iter()
        .map(|t| t.tie.dissipation(rate_of(t, &twist_of)))
        .sum::<f64>()
        + (0..m)
            .map(|k| {
                let r = super::rot(points[k]);
                chain.strip_dissipation(js[k], [c[k] * r[0], c[k] * r[1], c[k] * r[2]])
            })
            .sum::<f64>()
        + chain
            .passive
            .iter()
            .map(|(face, slot)| {
                face.dissipation(super::velocity(twist_of(Some(*slot)), face.point).x)
            })
            .sum::<f64>();
    if ax <= 0.0 {
        return Err(not(
            "the seismic load does no work on the mechanism of the static hinges".into(),
        ));
    }
    let lambda = (g + d) / ax;
    let assembly = &model.assembly;
    let mut velocities: Vec<[f64; 3]> = (0..assembly.blocks.len())
        .map(|b| {
            let t = twist_of(Some(b + 1));
            let v = super::velocity(t, assembly.blocks[b].centroid);
            [v.x, v.y, t[0]]
        })
        .collect();
    let vmax = velocities
        .iter()
        .fold(0.0_f64, |s, v| s.max((v[0] * v[0] + v[1] * v[1]).sqrt()));
    if vmax > 0.0 {
        for v in &mut velocities {
            for x in v.iter_mut() {
                *x /= vmax;
            }
        }
    }
    let hinges = items
        .iter()
        .zip(&c)
        .filter(|(_, ck)| ck.abs() > tol / cmax)
        .map(|(&(j, e), _)| {
            Hinge::at(
                assembly,
                j,
                if e == 0 { JointEnd::P1 } else { JointEnd::P2 },
            )
        })
        .collect();
    let note = format!(
        "certified: the mechanism of the static hinges (joints {}) with tie{} {} keeping its length has lambda = {lambda:.10} by virtual work",
        js.iter().map(|j| j.to_string()).collect::<Vec<_>>().join(", "),
        if held.len() == 1 { "" } else { "s" },
        held.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(", "),
    );
    Ok(KinematicResult {
        status: Status::Collapse,
        lambda_upper: Some(lambda),
        lambda_signed: Some(lambda),
        lambda_needed: None,
        mechanism: Some(Mechanism {
            family: Family::HingesWithHeldTies,
            hinges,
            open: Vec::new(),
            sliding: Vec::new(),
            velocities,
            lambda,
        }),
        direction: settings.direction,
        candidates: 1,
        admissible: 1,
        wall_time_s: start.elapsed().as_secs_f64(),
        search: Search::Certified,
        searched_joints: wanted,
        note: Some(note),
    })
}

/// The `wanted` hinges of a static solution at collapse, read from where its resultants touch
/// the joint ends, as `(joint, end)` in chain order (end 0 = p1, 1 = p2).
fn hinges_from_forces(
    model: &Model,
    around: &StaticResult,
    wanted: usize,
) -> Result<Vec<(usize, u8)>, KinematicError> {
    // On long chains the resultants of a few joints next to each true hinge sit within the
    // hinge tolerance of the same end: a run of consecutive joints hinged at the same end is one
    // hinge, at the joint whose resultant is nearest the end.
    let mut hinges: Vec<(usize, u8)> = around
        .hinges
        .iter()
        .map(|h| (h.joint, if h.end == JointEnd::P1 { 0 } else { 1 }))
        .collect();
    hinges.sort_unstable();
    let margin = |&(j, end): &(usize, u8)| -> f64 {
        let half = 0.5 * model.assembly.joints[j].length();
        match around.forces.as_ref().and_then(|f| f.get(j)) {
            Some(f) if f.n > 0.0 => {
                let e = f.m / f.n;
                (half - if end == 0 { -e } else { e }) / half
            }
            _ => f64::INFINITY,
        }
    };
    let mut items: Vec<(usize, u8)> = Vec::new();
    let mut run_start = 0;
    for i in 1..=hinges.len() {
        let ends_run = i == hinges.len()
            || hinges[i].1 != hinges[i - 1].1
            || hinges[i].0 != hinges[i - 1].0 + 1;
        if ends_run {
            let run = &hinges[run_start..i];
            if let Some(best) = run.iter().min_by(|a, b| margin(a).total_cmp(&margin(b))) {
                items.push(*best);
            }
            run_start = i;
        }
    }
    items.dedup_by_key(|i| i.0);
    if items.len() != wanted {
        return Err(KinematicError::NotCertified(format!(
            "the static solution has {} hinges at {} places and {} open joints (a non-degenerate collapse has {wanted} hinges with that many open joints)",
            around.hinges.len(),
            items.len(),
            around.open.len()
        )));
    }
    Ok(items)
}

/// The hinges of the mechanism the static program's duals describe (block velocities
/// `[vx, vy, omega]`, blocks in chain order, the ground still at both ends): a joint where the
/// two sides move apart is a hinge at the end where their relative velocity vanishes. None
/// unless that gives exactly four pure hinges.
fn hinges_from_velocities(model: &Model, velocities: &[[f64; 3]]) -> Option<Vec<(usize, u8)>> {
    let a = &model.assembly;
    if velocities.len() != a.blocks.len() || a.joints.len() != a.blocks.len() + 1 {
        return None;
    }
    // Velocities are scaled so the fastest centroid moves at 1: a relative speed below this
    // is round-off (the interior point's duals) or nothing.
    const STILL: f64 = 1e-7;
    let at = |b: Option<usize>, q: Vec2| -> Vec2 {
        match b {
            Some(b) => {
                let [vx, vy, w] = velocities[b];
                let r = q - a.blocks[b].centroid;
                Vec2::new(vx - w * r.y, vy + w * r.x)
            }
            None => Vec2::zeros(),
        }
    };
    let mut items = Vec::new();
    for (k, j) in a.joints.iter().enumerate() {
        let before = k.checked_sub(1);
        let after = (k < a.blocks.len()).then_some(k);
        let rel = |q: Vec2| (at(after, q) - at(before, q)).norm();
        let (r1, r2) = (rel(j.p1), rel(j.p2));
        match (r1.max(r2) > STILL, r1 <= STILL, r2 <= STILL) {
            (false, _, _) => {}
            (true, true, false) => items.push((k, 0)),
            (true, false, true) => items.push((k, 1)),
            // Open, sliding or ambiguous: not a four-hinge mechanism.
            _ => return None,
        }
    }
    (items.len() == 4).then_some(items)
}

/// Virtual work of the four-hinge mechanism of a two-support chain with hinges `hinges`
/// (joint, end), in chain order: `(A, G)` with `A` the work of the seismic loads toward
/// `direction` per unit multiplier and `G` the work done against the permanent loads (so its
/// multiplier is `G / A`, and `G < 0` means the permanent loads alone drive it: the structure
/// cannot stand). None when the mechanism is not admissible (a hinge would close). Cost:
/// linear in the number of blocks (the prefix sums).
pub fn mechanism_work(
    model: &Model,
    hinges: &[(usize, JointEnd)],
    direction: crate::outcome::Direction,
) -> Result<Option<(f64, f64)>, KinematicError> {
    if !chain_kind(model)? {
        return Err(KinematicError::NotCertified(
            "a one-support chain has no four-hinge mechanism".into(),
        ));
    }
    let nj = model.assembly.joints.len();
    let mut items: Vec<(usize, u8)> = hinges
        .iter()
        .map(|&(j, e)| (j, if e == JointEnd::P1 { 0 } else { 1 }))
        .collect();
    items.sort_unstable();
    items.dedup_by_key(|i| i.0);
    if items.len() != 4 || items.iter().any(|&(j, _)| j >= nj) {
        return Err(KinematicError::NotCertified(format!(
            "a four-hinge mechanism needs four distinct joints below {nj}, got {hinges:?}"
        )));
    }
    let chain = Chain::new(model, direction.sign(), true);
    Ok(chain.evaluate(&Key::new(&items)).map(|(a, g, _)| (a, g)))
}

/// The mechanism of `key`, with block velocities normalised (fastest centroid at speed 1).
fn mechanism_of(assembly: &Assembly, chain: &Chain, key: &Key) -> Option<Mechanism> {
    let (a, g, m) = chain.evaluate(key)?;
    let js: Vec<usize> = key.items().map(|(j, _)| j).collect();
    let nb = assembly.blocks.len();
    let mut vel = vec![[0.0; 3]; nb];
    let mut twist = [0.0; 3];
    let nbodies = if chain.closed { js.len() - 1 } else { js.len() };
    for k in 0..nbodies {
        for (tc, rc) in twist.iter_mut().zip(m.rel[k]) {
            *tc += rc;
        }
        let end = if k + 1 < js.len() { js[k + 1] } else { nb };
        for (b, v) in vel.iter_mut().enumerate().take(end).skip(js[k]) {
            let u = super::velocity(twist, assembly.blocks[b].centroid);
            *v = [u.x, u.y, twist[0]];
        }
    }
    let vmax = vel
        .iter()
        .fold(0.0_f64, |s, v| s.max((v[0] * v[0] + v[1] * v[1]).sqrt()));
    if vmax > 0.0 {
        for v in &mut vel {
            for c in v.iter_mut() {
                *c /= vmax;
            }
        }
    }
    let mut hinges = Vec::new();
    let mut open = Vec::new();
    let mut n_open = 0;
    for (i, (j, act)) in key.items().enumerate() {
        match act {
            OPEN => {
                open.push(j);
                n_open += 1;
            }
            e if m.opening[i] > ADMISSIBLE_TOL => hinges.push(Hinge::at(
                assembly,
                j,
                if e == 0 { JointEnd::P1 } else { JointEnd::P2 },
            )),
            _ => {}
        }
    }
    let family = match (chain.closed, n_open) {
        (false, _) => Family::OneHinge,
        (true, 0) => Family::FourHinges,
        (true, 1) => Family::TwoHingesOneOpen,
        _ => Family::TwoOpen,
    };
    Some(Mechanism {
        family,
        hinges,
        open,
        sliding: Vec::new(),
        velocities: vel,
        lambda: g / a,
    })
}

/// One-support chain: a single hinge at either end of any joint.
fn search_column(chain: &Chain) -> (Extremes<Key>, u64) {
    let mut ext = Extremes::new();
    for j in 0..chain.joints() {
        for e in 0..2u8 {
            let key = Key::new(&[(j, e)]);
            if let Some((a, g, _)) = chain.evaluate(&key) {
                ext.push(a, g, || key);
            }
        }
    }
    (ext, 2 * chain.joints() as u64)
}

fn binom(n: usize, k: usize) -> u64 {
    if k > n {
        return 0;
    }
    (0..k).fold(1u64, |acc, i| acc * (n - i) as u64 / (i as u64 + 1))
}

fn search_closed(chain: &Chain, parallel: bool) -> (Extremes<Key>, u64) {
    let n = chain.joints();
    let candidates = 16 * binom(n, 4) + 4 * n as u64 * binom(n.saturating_sub(1), 2) + binom(n, 2);
    let four = four_hinges(chain, parallel);
    let three = two_hinges_one_open(chain, parallel);
    let two = two_open(chain);
    (four.merge(three).merge(two), candidates)
}

fn two_open(chain: &Chain) -> Extremes<Key> {
    let n = chain.joints();
    let mut ext = Extremes::new();
    for j1 in 0..n {
        for j2 in j1 + 1..n {
            let key = Key::new(&[(j1, OPEN), (j2, OPEN)]);
            if let Some((a, g, _)) = chain.evaluate(&key) {
                ext.push(a, g, || key);
            }
        }
    }
    ext
}

/// Two hinges h1, h2 and one open joint o, in any chain order, by the closed-form cofactors.
fn two_hinges_one_open(chain: &Chain, parallel: bool) -> Extremes<Key> {
    let n = chain.joints();
    let per_open = |o: usize| {
        if chain.has_dissipation() {
            let mut sink = Dissipating::new(chain);
            two_hinges_one_open_at(chain, o, &mut sink);
            return sink.inner;
        }
        let mut ext = Extremes::new();
        two_hinges_one_open_at(chain, o, &mut ext);
        ext
    };
    if parallel {
        (0..n)
            .into_par_iter()
            .map(per_open)
            .reduce(Extremes::new, Extremes::merge)
    } else {
        (0..n).map(per_open).fold(Extremes::new(), Extremes::merge)
    }
}

/// The two-hinges-one-open mechanisms whose open joint is `o`.
fn two_hinges_one_open_at<S: Sink>(chain: &Chain, o: usize, sink: &mut S) {
    let n = chain.joints();
    let nrm = chain.normal[o];
    let p = chain.p[0][o];
    let lo = chain.len[o];
    // Signed distances of every joint end from the open joint's line.
    let dist: [Vec<f64>; 2] = [
        chain.p[0].iter().map(|q| (q - p).dot(&nrm)).collect(),
        chain.p[1].iter().map(|q| (q - p).dot(&nrm)).collect(),
    ];
    for j1 in 0..n {
        if j1 == o {
            continue;
        }
        for j2 in j1 + 1..n {
            if j2 == o {
                continue;
            }
            for e1 in 0..2usize {
                let h1 = chain.p[e1][j1];
                let s1 = if e1 == 0 { -1.0 } else { 1.0 };
                for e2 in 0..2usize {
                    let h2 = chain.p[e2][j2];
                    let s2 = if e2 == 0 { -1.0 } else { 1.0 };
                    let c1 = -dist[e2][j2];
                    let c2 = dist[e1][j1];
                    let cp = dist[e2][j2] - dist[e1][j1];
                    let cn = -cross(h2 - h1, p - h1);
                    // Opening velocities: the free end of each hinge, both ends of o.
                    let v = [
                        s1 * c1 * chain.len[j1],
                        s2 * c2 * chain.len[j2],
                        cn,
                        cn - cp * lo,
                    ];
                    let vmax = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                    if vmax <= 0.0 {
                        continue;
                    }
                    let tol = ADMISSIBLE_TOL * vmax;
                    let sigma = if v.iter().all(|&x| x >= -tol) {
                        1.0
                    } else if v.iter().all(|&x| x <= tol) {
                        -1.0
                    } else {
                        continue;
                    };
                    sink.count(1);
                    let r1 = [sigma * c1, sigma * c1 * h1.y, -sigma * c1 * h1.x];
                    let r2 = [sigma * c2, sigma * c2 * h2.y, -sigma * c2 * h2.x];
                    let ro = [
                        sigma * cp,
                        sigma * (cp * p.y + cn * nrm.x),
                        sigma * (-cp * p.x + cn * nrm.y),
                    ];
                    // Chain order of the three active joints.
                    let items = if o < j1 {
                        [(o, ro, OPEN), (j1, r1, e1 as u8), (j2, r2, e2 as u8)]
                    } else if o < j2 {
                        [(j1, r1, e1 as u8), (o, ro, OPEN), (j2, r2, e2 as u8)]
                    } else {
                        [(j1, r1, e1 as u8), (j2, r2, e2 as u8), (o, ro, OPEN)]
                    };
                    let t1 = items[0].1;
                    let t2 = [
                        t1[0] + items[1].1[0],
                        t1[1] + items[1].1[1],
                        t1[2] + items[1].1[2],
                    ];
                    let (a1, g1) = super::work(t1, chain.body(items[0].0, items[1].0));
                    let (a2, g2) = super::work(t2, chain.body(items[1].0, items[2].0));
                    let (ax, g) = (a1 + a2, g1 + g2);
                    if sink.wants(ax, g) {
                        sink.take(
                            ax,
                            g,
                            Key::new(&[
                                (items[0].0, items[0].2),
                                (items[1].0, items[1].2),
                                (items[2].0, items[2].2),
                            ]),
                        );
                    }
                }
            }
        }
    }
}

/// Masks of admissible (pattern, sigma = +1) for the four sign conditions, indexed by the sign
/// byte of the relevant triangle. Pattern bits: eA << 3 | eB << 2 | eC << 1 | eD (1 = p2);
/// a triangle byte's bit `ep << 2 | eq << 1 | er` is set when `T > 0`.
struct MaskTables {
    a: [u16; 256],
    b: [u16; 256],
    c: [u16; 256],
    d: [u16; 256],
    /// The patterns that use an end choice flagged in a triangle's collinearity byte (the
    /// high byte of its sign word), for the triangles (b,c,d), (a,c,d), (a,b,d), (a,b,c).
    uses: [[u16; 256]; 4],
}

/// The mask tables depend on nothing: built once per process.
static MASKS: std::sync::OnceLock<MaskTables> = std::sync::OnceLock::new();

fn mask_tables() -> MaskTables {
    let mut t = MaskTables {
        a: [0; 256],
        b: [0; 256],
        c: [0; 256],
        d: [0; 256],
        uses: [[0; 256]; 4],
    };
    for y in 0..256usize {
        for pat in 0..16usize {
            let (ea, eb, ec, ed) = ((pat >> 3) & 1, (pat >> 2) & 1, (pat >> 1) & 1, pat & 1);
            let combos = [
                eb << 2 | ec << 1 | ed,
                ea << 2 | ec << 1 | ed,
                ea << 2 | eb << 1 | ed,
                ea << 2 | eb << 1 | ec,
            ];
            for (u, combo) in t.uses.iter_mut().zip(combos) {
                if (y >> combo) & 1 == 1 {
                    u[y] |= 1 << pat;
                }
            }
        }
    }
    for y in 0..256usize {
        let bit = |i: usize| (y >> i) & 1 == 1;
        for pat in 0..16usize {
            let (ea, eb, ec, ed) = ((pat >> 3) & 1, (pat >> 2) & 1, (pat >> 1) & 1, pat & 1);
            // c_A = +T(b,c,d): hinge A at p2 (ea = 1) needs c_A > 0.
            if (ea == 1) == bit(eb << 2 | ec << 1 | ed) {
                t.a[y] |= 1 << pat;
            }
            // c_B = -T(a,c,d).
            if (eb == 1) != bit(ea << 2 | ec << 1 | ed) {
                t.b[y] |= 1 << pat;
            }
            // c_C = +T(a,b,d).
            if (ec == 1) == bit(ea << 2 | eb << 1 | ed) {
                t.c[y] |= 1 << pat;
            }
            // c_D = -T(a,b,c).
            if (ed == 1) != bit(ea << 2 | eb << 1 | ec) {
                t.d[y] |= 1 << pat;
            }
        }
    }
    t
}

/// Receiver of admissible mechanisms `(A, G, key)` during a search.
pub(crate) trait Sink {
    /// Whether a mechanism with load power `ax` and gravity power `g` may matter (a cheap test
    /// before its key is built).
    fn wants(&self, ax: f64, g: f64) -> bool;
    fn take(&mut self, ax: f64, g: f64, key: Key);
    /// Count `n` admissible mechanisms.
    fn count(&mut self, n: u64);
}

impl Sink for Extremes<Key> {
    #[inline]
    fn wants(&self, ax: f64, g: f64) -> bool {
        // g/ax < best (ax > 0) and g/ax > needed (ax < 0) are both g < l * ax: no division.
        if ax > 0.0 {
            self.best.as_ref().is_none_or(|b| g <= b.0 * ax)
        } else if ax < 0.0 {
            self.needed.as_ref().is_none_or(|b| g <= b.0 * ax)
        } else {
            g < 0.0
        }
    }
    #[inline]
    fn take(&mut self, ax: f64, g: f64, key: Key) {
        self.record(ax, g, || key);
    }
    #[inline]
    fn count(&mut self, n: u64) {
        self.admissible += n;
    }
}

/// The sink of a chain with tie rods or bonded strips: the closed forms of the families give
/// the work of the loads only, so every admissible mechanism they may want is valued again by
/// [`Chain::evaluate`], which adds the dissipation `D` (`lambda = (G + D)/A`), before the
/// extremes see it. When no tie is prestressed, `D >= 0` for every mechanism, so a mechanism
/// the extremes do not want on the loads' work alone (`G > best A` for `A > 0`,
/// `G >= needed A` for `A < 0`, `G >= 0` for `A = 0`) is not wanted with `D` added either, and
/// is pruned before its key is valued; a prestress (`D` of either sign) turns that off.
struct Dissipating<'a> {
    chain: &'a Chain,
    inner: Extremes<Key>,
    /// Whether every mechanism's dissipation is >= 0 (no prestressed tie).
    nonnegative: bool,
}

impl<'a> Dissipating<'a> {
    fn new(chain: &'a Chain) -> Self {
        Dissipating {
            chain,
            inner: Extremes::new(),
            nonnegative: chain.ties.iter().all(|t| t.tie.prestress == 0.0),
        }
    }
}

impl Sink for Dissipating<'_> {
    #[inline]
    fn wants(&self, ax: f64, g: f64) -> bool {
        !self.nonnegative || self.inner.wants(ax, g)
    }
    fn take(&mut self, _ax: f64, _g: f64, key: Key) {
        if let Some((ax, g, _)) = self.chain.evaluate(&key) {
            if self.inner.wants(ax, g) {
                self.inner.take(ax, g, key);
            }
        }
    }
    #[inline]
    fn count(&mut self, n: u64) {
        self.inner.count(n);
    }
}

/// Index of the triple p < q < r in the combinatorial number system.
struct TripleIndex {
    c2: Vec<usize>,
    c3: Vec<usize>,
}

impl TripleIndex {
    fn new(n: usize) -> Self {
        TripleIndex {
            c2: (0..=n).map(|q| q * q.saturating_sub(1) / 2).collect(),
            c3: (0..=n)
                .map(|r| r * r.saturating_sub(1) * r.saturating_sub(2) / 6)
                .collect(),
        }
    }
}

/// Sign bytes of all joint triples: low byte = `T > eps` for each of the 8 end choices, high
/// byte = `|T| <= eps` (collinear within round-off).
fn triangle_signs(chain: &Chain, idx: &TripleIndex, parallel: bool) -> Vec<u16> {
    let n = chain.joints();
    let eps = 1e-11 * chain.size * chain.size;
    let row = |r: usize| {
        let mut out = Vec::with_capacity(idx.c3[r + 1] - idx.c3[r]);
        for q in 1..r {
            for p in 0..q {
                let mut v = 0u16;
                for combo in 0..8usize {
                    let pp = chain.p[(combo >> 2) & 1][p];
                    let qq = chain.p[(combo >> 1) & 1][q];
                    let rr = chain.p[combo & 1][r];
                    let t = cross(qq - pp, rr - pp);
                    if t.abs() <= eps {
                        v |= 1 << (8 + combo);
                    } else if t > 0.0 {
                        v |= 1 << combo;
                    }
                }
                out.push(v);
            }
        }
        out
    };
    let rows: Vec<Vec<u16>> = if parallel {
        (0..n).into_par_iter().map(row).collect()
    } else {
        (0..n).map(row).collect()
    };
    rows.concat()
}

/// Constants of the four-hinge work for fixed hinge points b, c, d (one end choice each):
/// `c_A`, the linear forms `T(a,c,d) = al0 + al . a` and `T(a,b,c) = be0 + be . a`, and the
/// contributions of the bodies [b, c) and [c, d) per unit rotation.
#[derive(Clone, Copy, Default)]
struct BcdConst {
    ca: f64,
    al: [f64; 3],
    be: [f64; 3],
    kb: [f64; 2],
    kd: [f64; 2],
}

/// Tables shared by the four-hinge loops.
pub(crate) struct FourTables {
    idx: TripleIndex,
    signs: Vec<u16>,
    masks: &'static MaskTables,
}

impl FourTables {
    fn new(chain: &Chain, parallel: bool) -> Self {
        let idx = TripleIndex::new(chain.joints());
        let signs = triangle_signs(chain, &idx, parallel);
        FourTables {
            idx,
            signs,
            masks: MASKS.get_or_init(mask_tables),
        }
    }
}

/// The four-hinge family over all joint quadruples a < b < c < d.
fn four_hinges(chain: &Chain, parallel: bool) -> Extremes<Key> {
    let n = chain.joints();
    if n < 4 {
        return Extremes::new();
    }
    let tables = FourTables::new(chain, parallel);
    let per_d = |d: usize| {
        if chain.has_dissipation() {
            let mut sink = Dissipating::new(chain);
            four_hinges_at(chain, &tables, d, &mut sink);
            return sink.inner;
        }
        let mut ext = Extremes::new();
        four_hinges_at(chain, &tables, d, &mut ext);
        ext
    };
    if parallel {
        (3..n)
            .into_par_iter()
            .rev()
            .map(per_d)
            .reduce(Extremes::new, Extremes::merge)
    } else {
        (3..n).map(per_d).fold(Extremes::new(), Extremes::merge)
    }
}

/// Every admissible mechanism of a chain, in any order, to the sinks of rayon tasks: every
/// task fills its own sink from `make`, and the sinks are folded with `merge` (which must not
/// depend on the order of the mechanisms, as a search's extremes and their tie-breaks by key
/// do not).
pub(crate) fn visit_all_par<S, M, F>(chain: &Chain, make: M, merge: F) -> S
where
    S: Sink + Send,
    M: Fn() -> S + Sync + Send,
    F: Fn(S, S) -> S + Sync + Send,
{
    let n = chain.joints();
    let four = || {
        if n < 4 {
            return make();
        }
        let tables = FourTables::new(chain, true);
        // The work of a last joint d grows as d^3: the largest first.
        (3..n)
            .into_par_iter()
            .rev()
            .map(|d| {
                let mut sink = make();
                four_hinges_at(chain, &tables, d, &mut sink);
                sink
            })
            .reduce(&make, &merge)
    };
    let three = || {
        (0..n)
            .into_par_iter()
            .map(|o| {
                let mut sink = make();
                two_hinges_one_open_at(chain, o, &mut sink);
                sink
            })
            .reduce(&make, &merge)
    };
    let two = || {
        let mut sink = make();
        for j1 in 0..n {
            for j2 in j1 + 1..n {
                let key = Key::new(&[(j1, OPEN), (j2, OPEN)]);
                if let Some((a, g, _)) = chain.evaluate(&key) {
                    sink.count(1);
                    sink.take(a, g, key);
                }
            }
        }
        sink
    };
    // The families run side by side, so no thread idles at the end of one of them.
    let (four, (three, two)) = rayon::join(four, || rayon::join(three, two));
    merge(merge(four, three), two)
}

/// The four-hinge quadruples whose last hinge is at joint `d`.
fn four_hinges_at<S: Sink>(chain: &Chain, tables: &FourTables, d: usize, sink: &mut S) {
    let (idx, signs, masks) = (&tables.idx, &tables.signs, &tables.masks);
    let mut konst = [BcdConst::default(); 8];
    for c in 2..d {
        let base_acd = idx.c3[d] + idx.c2[c];
        let scd = chain.body(c, d);
        for b in 1..c {
            let ybcd = signs[idx.c3[d] + idx.c2[c] + b];
            let base_abc = idx.c3[c] + idx.c2[b];
            let base_abd = idx.c3[d] + idx.c2[b];
            let sbc = chain.body(b, c);
            for (combo, k) in konst.iter_mut().enumerate() {
                let pb = chain.p[(combo >> 2) & 1][b];
                let pc = chain.p[(combo >> 1) & 1][c];
                let pd = chain.p[combo & 1][d];
                *k = BcdConst {
                    ca: cross(pc - pb, pd - pb),
                    al: [cross(pc, pd), pc.y - pd.y, pd.x - pc.x],
                    be: [cross(pb, pc), pb.y - pc.y, pc.x - pb.x],
                    kb: super::rot_work(pb, &sbc).into(),
                    kd: super::rot_work(pd, &scd).into(),
                };
            }
            let ma = masks.a[(ybcd & 0xff) as usize];
            let ua = masks.uses[0][(ybcd >> 8) as usize];
            let pre_c = chain.pre[c];
            for a in 0..b {
                let yabc = signs[base_abc + a];
                let yabd = signs[base_abd + a];
                let yacd = signs[base_acd + a];
                // Patterns whose hinge points are collinear within round-off in one of the
                // four triangles: their sign conditions are undecided by the tables, so they
                // are evaluated directly (with the admissibility tolerance). The other
                // patterns of the quadruple use only decided signs and take the fast path.
                let mut slow = 0;
                if (ybcd | yabc | yabd | yacd) >> 8 != 0 {
                    slow = ua
                        | masks.uses[1][(yacd >> 8) as usize]
                        | masks.uses[2][(yabd >> 8) as usize]
                        | masks.uses[3][(yabc >> 8) as usize];
                    slow_patterns(chain, [a, b, c, d], slow, sink);
                }
                let mb = masks.b[(yacd & 0xff) as usize];
                let mc = masks.c[(yabd & 0xff) as usize];
                let md = masks.d[(yabc & 0xff) as usize];
                let plus = ma & mb & mc & md & !slow;
                let minus = !ma & !mb & !mc & !md & !slow;
                if plus | minus == 0 {
                    continue;
                }
                sink.count(u64::from((plus | minus).count_ones()));
                let sac = pre_c - chain.pre[a];
                for (bits, sigma) in [(plus, 1.0), (minus, -1.0)] {
                    let mut bits = bits;
                    while bits != 0 {
                        let pat = bits.trailing_zeros() as usize;
                        bits &= bits - 1;
                        let k = &konst[pat & 7];
                        let pa = chain.p[(pat >> 3) & 1][a];
                        // c_B = -T(a,c,d), c_D = -T(a,b,c); the sign sigma is applied last.
                        let cb = -(k.al[0] + k.al[1] * pa.x + k.al[2] * pa.y);
                        let cd = -(k.be[0] + k.be[1] * pa.x + k.be[2] * pa.y);
                        let (wa, ga) = super::rot_work(pa, &sac);
                        let ax = k.ca * wa + cb * k.kb[0] - cd * k.kd[0];
                        let g = k.ca * ga + cb * k.kb[1] - cd * k.kd[1];
                        let (ax, g) = (sigma * ax, sigma * g);
                        if sink.wants(ax, g) {
                            sink.take(ax, g, quad_key([a, b, c, d], pat));
                        }
                    }
                }
            }
        }
    }
}

fn quad_key(j: [usize; 4], pat: usize) -> Key {
    Key::new(&[
        (j[0], ((pat >> 3) & 1) as u8),
        (j[1], ((pat >> 2) & 1) as u8),
        (j[2], ((pat >> 1) & 1) as u8),
        (j[3], (pat & 1) as u8),
    ])
}

/// `(A, G)` of the four-hinge mechanism with hinges at joints `j` and end pattern `pat`,
/// oriented by `sigma`. Bodies: [a, b), [b, c), [c, d); body twists `c_A m_a`,
/// `c_A m_a + c_B m_b`, `-c_D m_d` with `m_p = (1, p_y, -p_x)`.
#[cfg(test)]
fn quadruple_work(chain: &Chain, j: [usize; 4], pat: usize, sigma: f64) -> (f64, f64) {
    let a = chain.p[(pat >> 3) & 1][j[0]];
    let b = chain.p[(pat >> 2) & 1][j[1]];
    let c = chain.p[(pat >> 1) & 1][j[2]];
    let d = chain.p[pat & 1][j[3]];
    let ca = sigma * cross(c - b, d - b);
    let cb = -sigma * cross(c - a, d - a);
    let cd = -sigma * cross(b - a, c - a);
    let sac = chain.pre[j[2]] - chain.pre[j[0]];
    let sbc = chain.pre[j[2]] - chain.pre[j[1]];
    let scd = chain.pre[j[3]] - chain.pre[j[2]];
    let (wa, ga) = super::rot_work(a, &sac);
    let (wb, gb) = super::rot_work(b, &sbc);
    let (wd, gd) = super::rot_work(d, &scd);
    (ca * wa + cb * wb - cd * wd, ca * ga + cb * gb - cd * gd)
}

/// All 16 end patterns of a quadruple by direct evaluation (near-collinear hinge points).
#[cfg(test)]
fn slow_quadruple<S: Sink>(chain: &Chain, j: [usize; 4], sink: &mut S) {
    slow_patterns(chain, j, 0xffff, sink);
}

/// The end patterns `pats` (bit mask) of a quadruple by direct evaluation (near-collinear
/// hinge points).
#[cold]
fn slow_patterns<S: Sink>(chain: &Chain, j: [usize; 4], pats: u16, sink: &mut S) {
    let mut bits = pats;
    while bits != 0 {
        let pat = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        let key = quad_key(j, pat);
        if let Some((a, g, _)) = chain.evaluate(&key) {
            sink.count(1);
            sink.take(a, g, key);
        }
    }
}

/// The crushing counterpart of [`certify`]: with a finite compressive strength the static
/// hinges sit at the centres of the compressed zones (`a/2` from the joint ends,
/// [`Hinge::offset`]), and the mechanism that rotates about those points is valued by
/// virtual work. A uniform stress block rotating about its own centre does no work, and the
/// joints that do not hinge do not move, so the work equation of this mechanism is the static
/// equilibrium at the hinges: its multiplier equals the static one exactly when the static
/// solution is in equilibrium with its resultants at those points, which is what this checks.
/// (The associated mechanism, rotating about the far edge of each compressed zone and
/// dissipating `fc d` times the zone's crushing, is the program's dual.)
///
/// Four-hinge mechanisms of a chain between two supports only: hinges `H1..H4` at joints
/// `j1 < .. < j4` split the chain into three moving bodies; with relative rotations
/// `theta_i` about `H_i`, closure `sum theta_i rot(H_i) = 0` fixes `theta` up to scale, and
/// `lambda = -P_permanent / P_seismic` (the loads' powers).
pub fn certify_crushing(
    model: &Model,
    around: &StaticResult,
    settings: &KinematicSettings,
) -> Result<KinematicResult, KinematicError> {
    let start = Instant::now();
    four_hinge_chain(model, around)?;
    if !around.sliding.is_empty() || !around.open.is_empty() {
        return Err(KinematicError::NotCertified(format!(
            "the crushing check takes four-hinge mechanisms only; the static solution has {} open and {} sliding joints",
            around.open.len(),
            around.sliding.len()
        )));
    }
    let forces = around
        .forces
        .as_ref()
        .ok_or_else(|| KinematicError::NotCertified("the static solution has no forces".into()))?;
    // A run of consecutive joints hinged at the same end is one hinge: the joint whose
    // resultant is nearest its hinge point.
    let mut hinges: Vec<Hinge> = Vec::new();
    let miss = |h: &Hinge| {
        let jt = &model.assembly.joints[h.joint];
        let f = forces[h.joint];
        let e = f.m / f.n;
        let from_end = match h.end {
            JointEnd::P1 => 0.5 * jt.length() + e,
            JointEnd::P2 => 0.5 * jt.length() - e,
        };
        (from_end - h.offset).abs() / jt.length()
    };
    let mut sorted = around.hinges.clone();
    sorted.sort_by_key(|h| h.joint);
    for h in sorted {
        match hinges.last_mut() {
            Some(last) if last.end == h.end && h.joint == last.joint + 1 => {
                if miss(&h) < miss(last) {
                    *last = h;
                }
            }
            _ => hinges.push(h),
        }
    }
    if hinges.len() != 4 {
        return Err(KinematicError::NotCertified(format!(
            "the static solution has {} crushing hinges, not four",
            hinges.len()
        )));
    }
    let point = |h: &Hinge| Vec2::new(h.x, h.y);
    let twist = |p: Vec2| nalgebra::Vector3::new(1.0, p.y, -p.x);
    let m = nalgebra::Matrix3::from_columns(&[
        twist(point(&hinges[1])),
        twist(point(&hinges[2])),
        twist(point(&hinges[3])),
    ]);
    let theta = m
        .lu()
        .solve(&(-twist(point(&hinges[0]))))
        .filter(|t| t.iter().all(|v| v.is_finite()))
        .ok_or_else(|| {
            KinematicError::NotCertified(
                "three of the crushing hinges are collinear: no four-hinge mechanism".into(),
            )
        })?;
    let thetas = [1.0, theta[0], theta[1], theta[2]];
    // The twist of each block: the sum of the relative rotations of the hinges before it.
    let sign = settings.direction.sign();
    let (mut p_perm, mut p_seis) = (0.0, 0.0);
    let mut twists = Vec::with_capacity(model.assembly.blocks.len());
    for b in 0..model.assembly.blocks.len() {
        let mut t = nalgebra::Vector3::zeros();
        for (h, th) in hinges.iter().zip(thetas) {
            if h.joint <= b {
                t += th * twist(point(h));
            }
        }
        let velocity = |q: Vec2| Vec2::new(t[1] - t[0] * q.y, t[2] + t[0] * q.x);
        let g = model.loads.reference(b);
        let power = |w: crate::model::Wrench| w.force.dot(&velocity(g)) + w.moment * t[0];
        p_perm += power(model.loads.permanent(b));
        p_seis += power(model.loads.variable(b, sign));
        twists.push(t);
    }
    let scale_ref = model.loads.force_scale() * model.assembly.size();
    if p_seis.abs() <= 1e-12 * scale_ref {
        return Err(KinematicError::NotCertified(
            "the seismic load does no work on the mechanism of the crushing hinges".into(),
        ));
    }
    let lambda = -p_perm / p_seis;
    // Velocities: the seismic load does positive work; the fastest centroid moves at 1.
    let mut velocities: Vec<[f64; 3]> = model
        .assembly
        .blocks
        .iter()
        .zip(&twists)
        .map(|(blk, t)| {
            let c = blk.centroid;
            [t[1] - t[0] * c.y, t[2] + t[0] * c.x, t[0]]
        })
        .collect();
    let vmax = velocities
        .iter()
        .fold(0.0_f64, |a, v| a.max(v[0].hypot(v[1])));
    let s = p_seis.signum() / vmax.max(1e-300);
    for v in &mut velocities {
        for c in v.iter_mut() {
            *c *= s;
        }
    }
    let note = format!(
        "crushing: the mechanism rotating about the centres of the compressed zones at joints {} (a/2 = {} mm from the ends) has lambda = {lambda:.10} by virtual work",
        hinges
            .iter()
            .map(|h| h.joint.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        hinges
            .iter()
            .map(|h| format!("{:.3}", 1e3 * h.offset))
            .collect::<Vec<_>>()
            .join(", "),
    );
    Ok(KinematicResult {
        status: Status::Collapse,
        lambda_upper: Some(lambda),
        lambda_signed: Some(lambda),
        lambda_needed: None,
        mechanism: Some(Mechanism {
            family: Family::FourHinges,
            hinges,
            open: Vec::new(),
            sliding: Vec::new(),
            velocities,
            lambda,
        }),
        direction: settings.direction,
        candidates: 1,
        admissible: 1,
        wall_time_s: start.elapsed().as_secs_f64(),
        search: Search::Certified,
        searched_joints: 4,
        note: Some(note),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast paths agree with the generic cofactor evaluation on every candidate, under
    /// loads that are not parallel to the weights (an inclined point load, fill, a vertical
    /// seismic component).
    #[test]
    fn fast_paths_match_generic_evaluation() {
        let scene = crate::scene::Scene::from_toml_str(
            "[arch]\nshape='pointed'\nradius=1.0\neccentricity=0.2\nthickness=0.2\nvoussoirs=6\n[piers]\nheight=0.8\nwidth=0.35\ncourses=2\n[[loads]]\ntype='point'\nat=[-0.9, -0.2]\nforce=[300.0, -2000.0]\n[fill]\nlevel=1.3\n[seismic]\nvertical_ratio=0.2\n",
            "t",
        )
        .unwrap();
        let model = crate::scene::build(&scene).unwrap();
        let chain = Chain::new(&model, 1.0, true);
        let n = chain.joints();
        // Four hinges: quadruple_work against evaluate, where admissible.
        let mut checked = 0;
        for d in 3..n {
            for c in 2..d {
                for b in 1..c {
                    for a in 0..b {
                        for pat in 0..16 {
                            let key = quad_key([a, b, c, d], pat);
                            if let Some((ax, g, _)) = chain.evaluate(&key) {
                                let (ax1, g1) = quadruple_work(&chain, [a, b, c, d], pat, 1.0);
                                let sigma = if ax * ax1 + g * g1 >= 0.0 { 1.0 } else { -1.0 };
                                let (ax2, g2) = (sigma * ax1, sigma * g1);
                                let s = ax.abs() + g.abs();
                                assert!((ax - ax2).abs() <= 1e-9 * s && (g - g2).abs() <= 1e-9 * s);
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(checked > 100);
        // Both searches over the whole family agree with brute force.
        let fast = four_hinges(&chain, false).merge(two_hinges_one_open(&chain, false));
        let mut brute = Extremes::new();
        for d in 3..n {
            for c in 2..d {
                for b in 1..c {
                    for a in 0..b {
                        slow_quadruple(&chain, [a, b, c, d], &mut brute);
                    }
                }
            }
        }
        for o in 0..n {
            for j1 in 0..n {
                for j2 in j1 + 1..n {
                    if j1 == o || j2 == o {
                        continue;
                    }
                    for e1 in 0..2u8 {
                        for e2 in 0..2u8 {
                            let mut items = [(j1, e1), (j2, e2), (o, OPEN)];
                            items.sort_unstable();
                            let key = Key::new(&items);
                            if let Some((a, g, _)) = chain.evaluate(&key) {
                                brute.push(a, g, || key);
                            }
                        }
                    }
                }
            }
        }
        let (fb, bb) = (fast.best.unwrap(), brute.best.unwrap());
        assert!(
            (fb.0 - bb.0).abs() <= 1e-12 * bb.0.abs().max(1.0),
            "{fb:?} {bb:?}"
        );
        assert_eq!(fb.1, bb.1);
        assert_eq!(fast.admissible, brute.admissible);
    }
}
