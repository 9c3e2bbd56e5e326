//! The DEM world and its time-stepping pipeline. One step is five named stages:
//!
//! 1. [`World::broad_phase`]: candidate pairs of bodies whose bounding boxes (grown by a
//!    margin) overlap, by sort-and-sweep along x; redone only when some body has moved by
//!    more than half the margin since the last time, so it scales with the number of blocks.
//! 2. [`World::narrow_phase`]: vertex-to-edge contacts of each candidate pair (every vertex
//!    of one body inside the other, in both directions), matched to last step's contacts so
//!    the shear spring keeps its history while a contact persists (Cundall & Strack 1979;
//!    Cundall 1988, "Formulation of a three-dimensional distinct element model"). One pass
//!    over the bodies decides whether the broad phase or the search is due; between searches
//!    the explicit stepping leaves the known contacts' depths to stage 3, which measures them
//!    by the search's own expression as it reads them.
//! 3. [`World::contact_forces`]: penalty springs and dashpots at each contact: normal force
//!    `N = max(0, kn d - cn vn)` (no tension, no cohesion; released as soon as the vertex
//!    leaves the edge), incremental shear force `S <- S - ks vt dt` capped by Coulomb
//!    `|S| <= mu N`.
//! 4. [`World::tie_forces`]: tie rods (`crate::interaction::tie`) as elastic-perfectly-plastic
//!    bars between their body-fixed anchors: tension `T = P + k (L - L0 - dp)` (prestress `P`
//!    ramped with gravity), no compression (a slack bar carries nothing), yield at the
//!    capacity `C`, where the plastic elongation `dp` grows. Its stiffness `k` is the
//!    contacts' normal stiffness (`IntegrationParameters::normal_stiffness`): the bar is as
//!    rigid as the blocks' contacts, the rigid-plastic tie of the limit analyses, so the three
//!    methods check the same model (and the time step is unchanged). A real bar's `E A / L0`
//!    lets it stretch about 2 mm per metre before it yields, and the mechanism softens
//!    geometrically meanwhile: on the bundled portal tied between its springings at 1 kN the
//!    DEM then collapsed 7 % below the limit analyses' multiplier.
//! 5. [`World::integrate`]: symplectic Euler (the central-difference scheme of UDEC) on each
//!    block's centroid and rotation, with Cundall's local damping `F <- F - alpha |F| sign(v)`
//!    per degree of freedom.
//!
//! Loads (all from the model's [`crate::model::LoadCase`], scaled by the factors the protocol
//! sets: `Load::gravity` for the permanent forces, `Load::lambda` for the seismic ones):
//! - each block's own weight `m0 g` down at its centroid, and its seismic force
//!   `lambda m0 g (1, r)` there (`r` the load case's vertical ratio);
//! - every other load of the block (point, line, fill) as a force fixed to the block at its
//!   point of application: the force keeps its direction, its point turns with the block, so
//!   its moment about the centroid is `cross(R r_k, F_k)` with `R` the block's rotation;
//! - the seismic masses of those loads, `lambda S_k (1, r)` at their (body-fixed) centre.
//!   They also move with the block: its mass is `m0 + sum S_k / g`, its polar inertia scaled
//!   in the same proportion (the added mass is spread like the block's own). Loads that are
//!   not seismic add force and no mass.

use super::body::{Body, BodyLoads, ExtraLoads};
use crate::dem_settings::{IntegrationParameters, Integrator, MOREAU_STEP_SHARE};
use crate::geometry::{cross, Vec2};
use crate::model::{LoadSource, Model};

/// One vertex-to-edge contact: vertex `vertex` of one body of the pair touches edge `edge` of
/// the other.
#[derive(Debug, Clone)]
pub(crate) struct Contact {
    /// false: a vertex of `pair.a` on an edge of `pair.b`; true: the other way round.
    pub flipped: bool,
    pub vertex: usize,
    pub edge: usize,
    /// Shear spring force (N) along the edge tangent, kept while the contact persists.
    pub shear: f64,
    /// Normal force of the last step (N), >= 0.
    pub normal_force: f64,
    /// Penetration depth of the last step (m), > 0.
    pub depth: f64,
    /// Whether the contact slid (|S| = mu N) in the last step.
    pub sliding: bool,
    /// Normal and tangential impulses (N s) of the last Moreau-Jean step
    /// ([`super::moreau`]), kept while the contact persists to warm-start the next one.
    pub impulse: (f64, f64),
}

impl Contact {
    /// The depth of the vertex behind the edge at the bodies' current positions (m; negative:
    /// a gap), `vb` the vertex's body and `eb` the edge's: the one expression of the contact
    /// search, the depth updates and the force loop, so a depth is the same whichever
    /// measured it.
    #[inline]
    fn depth_in(&self, vb: &Body, eb: &Body) -> f64 {
        -(vb.world[self.vertex] - eb.world[self.edge]).dot(&eb.normals[self.edge])
    }

    /// `(vertex body, edge body)` of this contact in `pair`.
    fn bodies(&self, pair_a: usize, pair_b: usize) -> (usize, usize) {
        if self.flipped {
            (pair_b, pair_a)
        } else {
            (pair_a, pair_b)
        }
    }
}

/// A candidate pair of bodies and its contacts (`a < b`).
#[derive(Debug, Clone)]
pub(crate) struct Pair {
    pub a: usize,
    pub b: usize,
    /// Critical damping coefficient sqrt(kn m_red) of the pair's contacts (`m_red` from the
    /// effective masses at a corner, see `effective_mass`).
    pub sqrt_km: f64,
    /// Coulomb coefficient of the pair's contacts.
    pub mu: f64,
    pub contacts: Vec<Contact>,
}

/// A tie rod between two bodies (or a body and the ground), elastic-perfectly-plastic.
#[derive(Debug, Clone)]
pub(crate) struct Bar {
    /// Anchored bodies (None: the ground) and the anchor points in the assembly's geometry.
    pub bodies: [Option<usize>; 2],
    pub anchors: [Vec2; 2],
    pub rest_length: f64,
    /// Axial stiffness (N/m).
    pub stiffness: f64,
    pub prestress: f64,
    pub capacity: f64,
    /// Plastic elongation so far (m).
    pub plastic: f64,
    /// Tension of the last step (N).
    pub force: f64,
    /// Whether the capacity grows with the permanent loads as they are ramped in (the fill's
    /// passive reaction, proportional to the fill's weight): `gravity * capacity`.
    pub capacity_with_gravity: bool,
}

/// The load factors the protocol applies.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Load {
    /// Fraction of the permanent loads (gravity) applied (ramped from 0 to 1 while
    /// settling).
    pub gravity: f64,
    /// Seismic multiplier currently applied (ramped to the target of a run).
    pub lambda: f64,
}

/// Rigid blocks, the fixed ground under the supports, and the contacts between them.
#[derive(Debug, Clone)]
pub(crate) struct World {
    pub bodies: Vec<Body>,
    pub pairs: Vec<Pair>,
    pub params: IntegrationParameters,
    pub dt: f64,
    /// The explicit stability limit of the time step (s), whatever step is used.
    pub stability_limit: f64,
    pub time: f64,
    pub steps: u64,
    pub load: Load,
    /// Direction of the seismic body force per unit weight and unit lambda,
    /// `(+1, vertical_ratio)`.
    pub seismic_direction: Vec2,
    /// Cundall's local damping coefficient applied now (the protocol switches it).
    pub local_damping: f64,
    /// Coulomb coefficient used for contacts (scene friction, or `infinite_friction`).
    pub mu: f64,
    /// Broad-phase margin (m) and the positions at the last broad phase.
    margin: f64,
    broad_pos: Vec<(Vec2, f64)>,
    /// Positions at the last contact search.
    search_pos: Vec<(Vec2, f64)>,
    /// Force and moment on each body: while a step runs, those of the contacts and ties;
    /// after it, the net force of the step (with the loads, before the local damping; the
    /// Moreau-Jean step writes its `m (v_{k+1} - v_k) / h`), read by [`World::unbalanced`].
    pub(super) force: Vec<(Vec2, f64)>,
    /// Tie rods.
    pub bars: Vec<Bar>,
    /// Moreau-Jean steps whose contact solve (the active set, then projected Gauss-Seidel)
    /// stopped at `moreau::MAX_SWEEPS` short of its
    /// tolerance (0 with the explicit stepping).
    pub unconverged: u64,
}

impl World {
    /// Bodies from the blocks of the model's assembly (their polygons, with the polygon's
    /// mass and centroid: for curved voussoirs the DEM simulates the chord polygon) carrying
    /// the model's loads (see [`BodyLoads`]), plus the fixed ground under the support joints
    /// ([`ground_rectangles`]: one body per line of neighbouring supports). The seismic
    /// forces act along `loads.seismic_direction(+1)`: ground motion toward +x, as the static
    /// program's default direction.
    pub fn new(model: &Model, params: &IntegrationParameters) -> World {
        // `Auto` is decided by the caller for its purpose (`IntegrationParameters::resolved`);
        // a world built directly (`Simulation`) steps explicitly.
        let mut params = params.clone();
        if params.integrator == Integrator::Auto {
            params.integrator = Integrator::Explicit;
        }
        let params = &params;
        let assembly = &model.assembly;
        let g = params.gravity;
        let size = assembly.size();
        let mut bodies: Vec<Body> = assembly
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| {
                // Unit weight x depth from the block's own weight and area; the DEM mass is
                // that of its polygon.
                let gamma = b.weight / b.area;
                let mut body = Body::new(&b.polygon, gamma / g, false, Some(i));
                let weight = body.mass * g;
                body.loads = BodyLoads {
                    weight,
                    extra: None,
                    scale: weight,
                };
                body
            })
            .collect();
        // The loads other than self-weight, at their offsets from the body's centroid; their
        // seismic masses move with the block (added mass, inertia scaled alike).
        for load in model.loads.applied() {
            if load.source == LoadSource::SelfWeight {
                continue;
            }
            let Some(body) = bodies.get_mut(load.block) else {
                continue;
            };
            let r = load.point - body.home;
            let l = &mut body.loads;
            let extra = l.extra.get_or_insert_with(ExtraLoads::default);
            if model.loads.is_variable(load) {
                // A live load under a live action: lambda multiplies it, gravity does not.
                extra.add_live(r, load.force);
            } else {
                extra.add(r, load.force, load.seismic_weight);
            }
            l.scale += load.force.norm().max(load.seismic_weight);
            body.add_mass(load.seismic_weight / g);
        }
        for poly in ground_rectangles(assembly, size) {
            bodies.push(Body::new(&poly, 0.0, true, None));
        }
        let mu_scene = assembly
            .joints
            .iter()
            .map(|j| j.friction)
            .fold(0.0_f64, f64::max);
        let mu = if mu_scene.is_finite() {
            mu_scene
        } else {
            params.infinite_friction
        };
        let stability_limit = critical_time_step(&bodies, params);
        let dt = params.time_step.unwrap_or(match params.integrator {
            Integrator::Auto | Integrator::Explicit => stability_limit * params.time_step_factor,
            // Rigid contacts have no stability limit: the step resolves the blocks' motion.
            Integrator::Moreau => MOREAU_STEP_SHARE * (size / params.gravity).sqrt(),
        });
        let n = bodies.len();
        let mut w = World {
            bodies,
            pairs: Vec::new(),
            params: params.clone(),
            dt,
            stability_limit,
            time: 0.0,
            steps: 0,
            load: Load::default(),
            // Zero under a live action: no mass is shaken, the live loads are the action.
            seismic_direction: model.loads.variable_direction(1.0),
            local_damping: params.local_damping,
            mu,
            margin: (0.01 * size).max(4.0 * params.contact_tolerance),
            broad_pos: Vec::new(),
            search_pos: Vec::new(),
            force: vec![(Vec2::zeros(), 0.0); n],
            bars: model
                .ties
                .iter()
                .map(|t| {
                    let length = t.length();
                    Bar {
                        // Bodies are the blocks, in order; the ground is fixed.
                        bodies: [t.from.block, t.to.block],
                        anchors: [t.from.point, t.to.point],
                        rest_length: length,
                        stiffness: params.normal_stiffness,
                        prestress: t.prestress,
                        capacity: t.capacity,
                        plastic: 0.0,
                        force: 0.0,
                        capacity_with_gravity: false,
                    }
                })
                .chain(model.strips.iter().map(|s| {
                    // A strip across a joint: a bar along the joint's normal from a point of
                    // `from` just behind the reinforced end to the end on `to`, which carries
                    // tension up to the strip's capacity.
                    let j = &assembly.joints[s.joint];
                    let p = s.point(assembly);
                    let gap = 1e-3 * j.length();
                    Bar {
                        bodies: [j.from, j.to],
                        anchors: [p - gap * j.normal(), p],
                        rest_length: gap,
                        stiffness: params.normal_stiffness,
                        prestress: 0.0,
                        capacity: s.capacity,
                        plastic: 0.0,
                        force: 0.0,
                        capacity_with_gravity: false,
                    }
                }))
                .chain(model.passive.iter().map(|p| {
                    // The fill's passive reaction: a one-sided horizontal spring that pushes
                    // the face's point back out of the fill, elastic up to its cap and
                    // perfectly plastic beyond (`crate::interaction::passive`). It is a bar
                    // from the point to a ground anchor far on the structure's side (`reach`,
                    // a hundred times the structure's size, so its line stays horizontal to
                    // 1 % of the point's vertical movement over that size), in tension when
                    // the point moves into the fill and slack when it moves away. Its
                    // stiffness is the contacts' normal stiffness, as a tie's: the fill is
                    // as rigid as the joints, the DEM's image of the rigid-plastic limit
                    // analyses (a real fill needs far larger movements to mobilise its
                    // passive pressure, which the mobilisation factor stands for).
                    let reach = 100.0 * size;
                    Bar {
                        bodies: [Some(p.block), None],
                        anchors: [p.point, p.point + reach * p.direction()],
                        rest_length: reach,
                        stiffness: params.normal_stiffness,
                        prestress: 0.0,
                        capacity: p.cap,
                        plastic: 0.0,
                        force: 0.0,
                        capacity_with_gravity: true,
                    }
                }))
                .collect(),
            unconverged: 0,
        };
        w.broad_phase();
        w.search_contacts();
        w
    }

    /// One time step: the five stages of the pipeline, or with `dem.integrator = "moreau"`
    /// the contact search followed by the Moreau-Jean stages ([`super::moreau`]).
    pub fn step(&mut self) {
        match self.params.integrator {
            Integrator::Auto | Integrator::Explicit => {
                // `contact_forces` measures the depths of the known contacts itself.
                self.update_contacts(false);
                self.contact_forces();
                self.tie_forces();
                self.integrate();
            }
            Integrator::Moreau => {
                self.find_contacts();
                super::moreau::step(self);
            }
        }
        self.time += self.dt;
        self.steps += 1;
    }

    /// Stages 1 and 2: the broad phase when some body has moved by half the margin, else the
    /// narrow phase.
    pub fn find_contacts(&mut self) {
        self.update_contacts(true);
    }

    /// [`World::find_contacts`], measuring the depths of the known contacts between searches
    /// only if `depths` (the explicit stepping measures them in `contact_forces`). One pass
    /// over the bodies decides both tests, the broad phase's and the search's.
    fn update_contacts(&mut self, depths: bool) {
        let n = self.bodies.len();
        let (broad, near) = (0.5 * self.margin, 0.25 * self.params.contact_tolerance);
        let mut search = self.search_pos.len() != n;
        let broad_moved = self.broad_pos.len() != n
            || self.bodies.iter().enumerate().any(|(i, b)| {
                if beyond(b, self.broad_pos[i], broad) {
                    return true;
                }
                if !search && beyond(b, self.search_pos[i], near) {
                    search = true;
                }
                false
            });
        if broad_moved {
            self.broad_phase();
            self.search_contacts();
        } else if search {
            self.search_contacts();
        } else if depths {
            self.update_depths();
        }
    }

    /// Stage 1: candidate pairs by sort-and-sweep of the grown bounding boxes along x. The
    /// contacts of pairs that stay candidates are kept.
    pub fn broad_phase(&mut self) {
        self.bound();
        let m = self.margin;
        let mut order: Vec<usize> = (0..self.bodies.len()).collect();
        order.sort_by(|&i, &j| self.bodies[i].lo.x.total_cmp(&self.bodies[j].lo.x));
        let mut keys: Vec<(usize, usize)> = Vec::new();
        for (k, &i) in order.iter().enumerate() {
            let bi = &self.bodies[i];
            for &j in &order[k + 1..] {
                let bj = &self.bodies[j];
                if bj.lo.x > bi.hi.x + m {
                    break;
                }
                if (bi.fixed && bj.fixed) || bj.lo.y > bi.hi.y + m || bi.lo.y > bj.hi.y + m {
                    continue;
                }
                keys.push((i.min(j), i.max(j)));
            }
        }
        keys.sort_unstable();
        let mut old = std::mem::take(&mut self.pairs).into_iter().peekable();
        let mut pairs = Vec::with_capacity(keys.len());
        for (a, b) in keys {
            while old.peek().is_some_and(|p| (p.a, p.b) < (a, b)) {
                old.next();
            }
            if let Some(p) = old.next_if(|p| (p.a, p.b) == (a, b)) {
                pairs.push(p);
                continue;
            }
            let (ba, bb) = (&self.bodies[a], &self.bodies[b]);
            let m_red = reduced_mass(ba, bb);
            pairs.push(Pair {
                a,
                b,
                sqrt_km: (self.params.normal_stiffness * m_red).sqrt(),
                mu: self.mu,
                contacts: Vec::new(),
            });
        }
        self.pairs = pairs;
        self.broad_pos.clear();
        self.broad_pos
            .extend(self.bodies.iter().map(|b| (b.pos, b.angle)));
    }

    /// The bounding boxes of the free bodies, for the broad phase and the contact search.
    fn bound(&mut self) {
        for b in self.bodies.iter_mut().filter(|b| !b.fixed) {
            b.bound();
        }
    }

    /// Stage 2: vertex-to-edge contacts. A full search of every candidate pair runs only
    /// when some body has moved by a quarter of the contact tolerance since the last one; it
    /// also keeps vertices that are within the tolerance outside a facing edge, as inactive
    /// contacts with a gap. Between searches no vertex can reach an edge it was farther than
    /// the tolerance from, so updating the depth of the known contacts is exact.
    pub fn narrow_phase(&mut self) {
        let near = 0.25 * self.params.contact_tolerance;
        if self.search_pos.len() != self.bodies.len()
            || self
                .bodies
                .iter()
                .zip(&self.search_pos)
                .any(|(b, &since)| beyond(b, since, near))
        {
            self.search_contacts();
            return;
        }
        self.update_depths();
    }

    /// The depths of the known contacts at the bodies' current positions (the contact
    /// search's expression, so a depth is the same whichever measured it).
    fn update_depths(&mut self) {
        for pair in &mut self.pairs {
            for c in &mut pair.contacts {
                let (vi, ei) = c.bodies(pair.a, pair.b);
                let (vb, eb) = (&self.bodies[vi], &self.bodies[ei]);
                c.depth = c.depth_in(vb, eb);
            }
        }
    }

    /// The full vertex-to-edge search of every candidate pair, keeping the shear history of
    /// contacts that persist (same vertex on the same edge).
    fn search_contacts(&mut self) {
        self.bound();
        let window = self.params.contact_tolerance;
        for pair in &mut self.pairs {
            let (a, b) = (&self.bodies[pair.a], &self.bodies[pair.b]);
            let old = std::mem::take(&mut pair.contacts);
            let mut found = Vec::with_capacity(old.len().max(4));
            for (flipped, v_body, e_body) in [(false, a, b), (true, b, a)] {
                let n = v_body.world.len();
                for i in 0..n {
                    let p = v_body.world[i];
                    // The two edges of the vertex's own body that meet at it.
                    let adj = [v_body.normals[(i + n - 1) % n], v_body.normals[i]];
                    if let Some((edge, depth)) = touch(p, adj, e_body, window) {
                        let kept = old
                            .iter()
                            .find(|c| c.flipped == flipped && c.vertex == i && c.edge == edge);
                        let shear = kept.map_or(0.0, |c| c.shear);
                        let impulse = kept.map_or((0.0, 0.0), |c| c.impulse);
                        found.push(Contact {
                            flipped,
                            vertex: i,
                            edge,
                            shear,
                            normal_force: 0.0,
                            depth,
                            sliding: false,
                            impulse,
                        });
                    }
                }
            }
            pair.contacts = found;
        }
        self.search_pos.clear();
        self.search_pos
            .extend(self.bodies.iter().map(|b| (b.pos, b.angle)));
    }

    /// Stage 3: contact forces (normal and shear springs with dashpots, no tension, Coulomb).
    pub fn contact_forces(&mut self) {
        for f in &mut self.force {
            *f = (Vec2::zeros(), 0.0);
        }
        let p = &self.params;
        let dt = self.dt;
        let shear_ratio = (p.shear_stiffness / p.normal_stiffness).sqrt();
        for pair in &mut self.pairs {
            let cn = 2.0 * p.contact_damping * pair.sqrt_km;
            let cs = cn * shear_ratio;
            for c in &mut pair.contacts {
                let (vi, ei) = c.bodies(pair.a, pair.b);
                let (vb, eb) = (&self.bodies[vi], &self.bodies[ei]);
                let point = vb.world[c.vertex];
                // Outward normal of the touched edge: it pushes the vertex's body away.
                let n = eb.normals[c.edge];
                // The depth now (the explicit step leaves it to this loop).
                c.depth = c.depth_in(vb, eb);
                if c.depth <= 0.0 {
                    // A gap: the contact carries nothing and forgets its shear.
                    c.normal_force = 0.0;
                    c.shear = 0.0;
                    c.sliding = false;
                    continue;
                }
                let t = Vec2::new(-n.y, n.x);
                let vrel = vb.point_velocity(point) - eb.point_velocity(point);
                let (vn, vt) = (vrel.dot(&n), vrel.dot(&t));
                let normal = p.normal_stiffness * c.depth - cn * vn;
                if normal <= 0.0 {
                    // No tension: the contact carries nothing and forgets its shear.
                    c.normal_force = 0.0;
                    c.shear = 0.0;
                    c.sliding = false;
                    continue;
                }
                let mut shear = c.shear - p.shear_stiffness * vt * dt;
                let cap = pair.mu * normal;
                c.sliding = false;
                if shear.abs() > cap {
                    shear = cap * shear.signum();
                    c.sliding = true;
                }
                c.shear = shear;
                c.normal_force = normal;
                // The dashpot acts in shear only while sticking and within the Coulomb cap.
                // `max` then `min`, not `clamp`: a state gone non-finite (an overflowing load)
                // must reach the divergence checks as a NaN, not panic here.
                let s_total = if c.sliding {
                    shear
                } else {
                    (shear - cs * vt).max(-cap).min(cap)
                };
                let f = normal * n + s_total * t;
                let fv = &mut self.force[vi];
                fv.0 += f;
                fv.1 += cross(point - vb.pos, f);
                let fe = &mut self.force[ei];
                fe.0 -= f;
                fe.1 -= cross(point - eb.pos, f);
            }
        }
    }

    /// Stage 4: tie rods, elastic-perfectly-plastic bars (module docs), added to the contact
    /// forces.
    pub fn tie_forces(&mut self) {
        let gravity = self.load.gravity;
        for bar in &mut self.bars {
            let at = |k: usize| match bar.bodies[k] {
                Some(b) => self.bodies[b].carry(bar.anchors[k]),
                None => bar.anchors[k],
            };
            let (a, b) = (at(0), at(1));
            let length = (b - a).norm();
            if length.is_nan() || length <= 0.0 {
                bar.force = 0.0;
                continue;
            }
            let e = (b - a) / length;
            let trial =
                gravity * bar.prestress + bar.stiffness * (length - bar.rest_length - bar.plastic);
            let capacity = if bar.capacity_with_gravity {
                gravity * bar.capacity
            } else {
                bar.capacity
            };
            let force = if trial > capacity {
                // Yield: the bar lengthens plastically at the capacity.
                bar.plastic =
                    length - bar.rest_length - (capacity - gravity * bar.prestress) / bar.stiffness;
                capacity
            } else {
                trial.max(0.0)
            };
            bar.force = force;
            for (k, point, f) in [(0, a, force * e), (1, b, -force * e)] {
                if let Some(i) = bar.bodies[k] {
                    let fb = &mut self.force[i];
                    fb.0 += f;
                    fb.1 += cross(point - self.bodies[i].pos, f);
                }
            }
        }
    }

    /// Stage 5: loads, local damping and symplectic Euler on every free block.
    pub fn integrate(&mut self) {
        let alpha = self.local_damping;
        let dt = self.dt;
        let d = self.seismic_direction;
        for (body, net) in self.bodies.iter_mut().zip(&mut self.force) {
            if body.fixed {
                continue;
            }
            let (f, m) = add_loads(body, self.load, d, net.0, net.1);
            // Kept for `unbalanced`, which the rest tests read far less often than every step.
            *net = (f, m);
            // Cundall's local damping opposes the motion of each degree of freedom with a
            // force proportional to the unbalanced force, never larger than it.
            let damp = |force: f64, v: f64| {
                if v == 0.0 {
                    force
                } else {
                    force - alpha * force.abs() * v.signum()
                }
            };
            let fx = damp(f.x, body.vel.x);
            let fy = damp(f.y, body.vel.y);
            let mz = damp(m, body.omega);
            body.vel += Vec2::new(fx, fy) * (dt / body.mass);
            body.omega += mz * dt / body.inertia;
            body.pos += body.vel * dt;
            body.angle += body.omega * dt;
            body.refresh();
        }
    }

    /// Largest unbalanced force of any free block in the last step, as a fraction of its
    /// load scale (its weight plus the magnitudes of the other loads it carries): computed
    /// when asked, from the net forces the step keeps.
    pub fn unbalanced(&self) -> f64 {
        self.bodies
            .iter()
            .zip(&self.force)
            .filter(|(b, _)| !b.fixed)
            .fold(0.0, |u: f64, (b, (f, m))| {
                u.max(f.norm().max(m.abs() / b.radius) / b.loads.scale)
            })
    }

    /// Largest speed of any point of a free block (m/s), `|v| + |omega| r`.
    pub fn max_speed(&self) -> f64 {
        self.bodies
            .iter()
            .filter(|b| !b.fixed)
            .fold(0.0, |s: f64, b| {
                s.max(b.vel.norm() + b.omega.abs() * b.radius)
            })
    }

    /// The deepest overlap of a contact carrying a force (m).
    pub fn max_penetration(&self) -> f64 {
        self.pairs
            .iter()
            .flat_map(|p| &p.contacts)
            .filter(|c| c.normal_force > 0.0)
            .map(|c| c.depth)
            .fold(0.0, f64::max)
    }

    /// Kinetic energy of all blocks (J).
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies.iter().map(Body::kinetic_energy).sum()
    }

    /// Potential energy of the applied loads (the permanent and seismic forces at their
    /// current factors, measured from the origin) plus the elastic energy of the contact
    /// springs (J). A constant force `F` at a body point `p` has the potential `-F . p`.
    pub fn potential_energy(&self) -> f64 {
        let d = self.seismic_direction;
        let loads: f64 = self
            .bodies
            .iter()
            .filter(|b| !b.fixed)
            .map(|b| {
                let l = &b.loads;
                let own = l.weight
                    * (self.load.gravity * b.pos.y
                        - self.load.lambda * (d.x * b.pos.x + d.y * b.pos.y));
                let extra = l.extra.as_ref().map_or(0.0, |e| {
                    let (sin, cos) = b.angle.sin_cos();
                    let permanent = e.force.dot(&b.pos) + e.lever(sin, cos);
                    let seismic = e.seismic_weight * d.dot(&(b.pos + b.rotate(e.seismic_offset)))
                        + e.live_force.dot(&b.pos)
                        + e.live_lever(sin, cos);
                    -self.load.gravity * permanent - self.load.lambda * seismic
                });
                own + extra
            })
            .sum();
        loads + self.elastic_energy()
    }

    /// Elastic energy of the normal and shear contact springs (J).
    pub fn elastic_energy(&self) -> f64 {
        let (kn, ks) = (self.params.normal_stiffness, self.params.shear_stiffness);
        self.pairs
            .iter()
            .flat_map(|p| &p.contacts)
            .filter(|c| c.depth > 0.0)
            .map(|c| 0.5 * kn * c.depth * c.depth + 0.5 * c.shear * c.shear / ks)
            .sum()
    }
}

/// `f0` and `m0` (N, N m) plus the loads `body` carries at the factors `load`, the seismic
/// ones along `d` (module docs): own weight and its seismic force at the centroid, the other
/// loads at their body-fixed points.
pub(crate) fn add_loads(body: &Body, load: Load, d: Vec2, f0: Vec2, m0: f64) -> (Vec2, f64) {
    let l = &body.loads;
    let w = l.weight;
    let sw = load.lambda * w;
    let mut f = f0 + Vec2::new(sw * d.x, -load.gravity * w + sw * d.y);
    let mut m = m0;
    if let Some(e) = &l.extra {
        let (sin, cos) = body.angle.sin_cos();
        let se = load.lambda * e.seismic_weight;
        let lambda = load.lambda;
        f += load.gravity * e.force + se * d + lambda * e.live_force;
        m += load.gravity * e.moment(sin, cos)
            + se * cross(body.rotate(e.seismic_offset), d)
            + lambda * e.live_moment(sin, cos);
    }
    (f, m)
}

/// The fixed ground: a rectangle on the far side of every support joint, three joint lengths
/// wide, so that a block can rock or slide on it without falling off. Supports on one line
/// whose rectangles overlap (the courses of a wall standing side by side on the ground) share
/// one rectangle over all of them: two overlapping grounds would give a block's corner two
/// contacts at one point, twice the contact stiffness under the explicit stepping and the
/// same rigid constraint twice (a singular Delassus operator) under the Moreau-Jean one.
fn ground_rectangles(assembly: &crate::assembly::Assembly, size: f64) -> Vec<[Vec2; 4]> {
    // Each ground: its normal into the ground, the line's offset along it, the span along the
    // joint's tangent `u` (extended by a joint length each side), and its rectangle.
    struct Ground {
        n: Vec2,
        u: Vec2,
        offset: f64,
        span: (f64, f64),
        depth: f64,
        poly: [Vec2; 4],
    }
    let same_line = 1e-9 * size.max(f64::MIN_POSITIVE);
    let mut grounds: Vec<Ground> = Vec::new();
    for j in assembly.joints.iter().filter(|j| j.is_support()) {
        let l = j.length();
        let u = j.tangent();
        let n = if j.to.is_none() {
            j.normal()
        } else {
            -j.normal()
        };
        let (a, b) = (j.p1 - l * u, j.p2 + l * u);
        let depth = l.max(0.1 * size);
        let mut g = Ground {
            n,
            u,
            offset: j.p1.dot(&n),
            span: (a.dot(&u), b.dot(&u)),
            depth,
            poly: [a, b, b + depth * n, a + depth * n],
        };
        // Fold in every ground already made on the same line that overlaps this one (and
        // again, since the wider span may now reach others).
        while let Some(k) = grounds.iter().position(|o| {
            o.n.dot(&g.n) > 1.0 - 1e-12 && (o.offset - g.offset).abs() <= same_line && {
                // The other's span along this tangent (the two tangents may be opposite).
                let (p, q) = (o.poly[0].dot(&g.u), o.poly[1].dot(&g.u));
                p.min(q) <= g.span.1 && g.span.0 <= p.max(q)
            }
        }) {
            let o = grounds.swap_remove(k);
            let (p, q) = (o.poly[0].dot(&g.u), o.poly[1].dot(&g.u));
            g.span = (g.span.0.min(p.min(q)), g.span.1.max(p.max(q)));
            g.depth = g.depth.max(o.depth);
            let base = g.offset * g.n;
            let (a, b) = (base + g.span.0 * g.u, base + g.span.1 * g.u);
            g.poly = [a, b, b + g.depth * g.n, a + g.depth * g.n];
        }
        grounds.push(g);
    }
    grounds.into_iter().map(|g| g.poly).collect()
}

/// Whether vertex `p` (whose own body's edges meeting at it have outward normals `adj`)
/// presses into the convex body `e`, or lies within the tolerance outside a facing edge;
/// if so, the edge it touches and the penetration depth (negative: a gap).
///
/// The corners of `e` are rounded by the `window`, as UDEC rounds block corners: a vertex
/// that presses into an edge and lies beyond its end by less than the window still touches
/// it. Without this, two blocks whose joint faces end at the same corners (every voussoir
/// joint) would see each corner contact flicker between "vertex of A in B" and "vertex of B
/// in A" with the round-off of the tangential offset, losing the shear history each time.
/// Near a corner the edge most nearly facing one of the vertex's own edges wins: a vertex on
/// the corner of a face-to-face joint must push along the joint normal, not along the joint;
/// and a vertex outside the polygon (within the rounding) touches only such a facing edge.
/// Cosine above which a vertex's own edge and a touched edge face each other (25 degrees).
const FACE_TO_FACE: f64 = 0.9;

fn touch(p: Vec2, adj: [Vec2; 2], e: &Body, window: f64) -> Option<(usize, f64)> {
    if p.x < e.lo.x - window
        || p.x > e.hi.x + window
        || p.y < e.lo.y - window
        || p.y > e.hi.y + window
    {
        return None;
    }
    let n = e.world.len();
    let mut max_s = f64::NEG_INFINITY;
    for k in 0..n {
        let s = (p - e.world[k]).dot(&e.normals[k]);
        if s >= window {
            return None;
        }
        max_s = max_s.max(s);
    }
    let mut best: Option<(usize, f64, f64)> = None;
    for k in 0..n {
        let nk = e.normals[k];
        let s = (p - e.world[k]).dot(&nk);
        if s < max_s - window {
            continue;
        }
        let score = (-adj[0].dot(&nk)).max(-adj[1].dot(&nk));
        // Outside the polygon (within the rounding) only a facing edge counts: a vertex
        // just past the corner of an opening joint must not catch the neighbouring face of
        // the other block, which would glue the joint shut.
        if max_s >= 0.0 && score < FACE_TO_FACE {
            continue;
        }
        let a = e.world[k];
        let edge = e.world[(k + 1) % n] - a;
        let len2 = edge.norm_squared();
        let tpar = (p - a).dot(&edge) / len2;
        let eps = window / len2.sqrt();
        if tpar < -eps || tpar > 1.0 + eps {
            continue;
        }
        let better = match best {
            None => true,
            Some((_, bs, bscore)) => score > bscore + 1e-9 || (score > bscore - 1e-9 && s > bs),
        };
        if better {
            best = Some((k, s, score));
        }
    }
    best.map(|(k, s, _)| (k, -s))
}

/// Whether body `b` has moved (a point of it, by translation plus rotation times its radius)
/// by more than `limit` since the position and rotation `since`. The square root is taken
/// only when [`surely_within`] cannot decide, so the answer is always the exact test's.
#[inline]
fn beyond(b: &Body, since: (Vec2, f64), limit: f64) -> bool {
    let d = b.pos - since.0;
    let turn = (b.angle - since.1).abs() * b.radius;
    !surely_within(d, turn, limit) && d.norm() + turn > limit
}

/// Whether a cheap bound proves that the computed `d.norm() + turn` is at most `limit`,
/// without the square root. `|d| <= |d_x| + |d_y|`, and the rounding of either side is a few
/// units in the last place (relative; plus the underflow of a square, below 1e-161
/// absolute), so a bound below the limit by a relative 1e-14 and an absolute 1e-150 proves
/// it. False when it cannot tell (a NaN or an infinity included).
#[inline]
pub(super) fn surely_within(d: Vec2, turn: f64, limit: f64) -> bool {
    (d.x.abs() + d.y.abs() + turn) * (1.0 + 1e-14) + 1e-150 <= limit
}

/// The mass a block shows at its farthest corner, `1 / (1/m + r^2/I)`: a corner contact
/// pushes the block and turns it (about a quarter of `m` for a rectangle).
pub(crate) fn effective_mass(b: &Body) -> f64 {
    1.0 / (1.0 / b.mass + b.radius * b.radius / b.inertia)
}

/// Reduced effective mass of two touching bodies (a fixed one counts as infinitely heavy).
fn reduced_mass(a: &Body, b: &Body) -> f64 {
    match (a.fixed, b.fixed) {
        (true, _) => effective_mass(b),
        (_, true) => effective_mass(a),
        _ => {
            let (ma, mb) = (effective_mass(a), effective_mass(b));
            ma * mb / (ma + mb)
        }
    }
}

/// The explicit stability limit of the stiffest block: `2 / omega_max (sqrt(1 + z^2) - z)`
/// (central differences with viscous damping). `omega_max^2` is bounded (Gershgorin) by
/// `2 n_c k / m_eff` over the block's `n_c = 2 x vertices` possible contacts, the factor 2
/// for two free blocks vibrating against each other; `z` is the damping ratio the contact
/// dashpots give that highest mode, `c omega_max / (2 k)`, much larger than the nominal
/// `contact_damping` because many dashpots act on one light block.
pub(crate) fn critical_time_step(bodies: &[Body], p: &IntegrationParameters) -> f64 {
    let k = p.normal_stiffness.max(p.shear_stiffness);
    bodies
        .iter()
        .filter(|b| !b.fixed)
        .map(|b| {
            let m = effective_mass(b);
            let omega = (2.0 * 2.0 * b.local.len() as f64 * k / m).sqrt();
            // The block's dashpots are at most those against the ground (m_red = m).
            let c = 2.0 * p.contact_damping * (p.normal_stiffness * m).sqrt();
            let z = c * omega / (2.0 * k);
            2.0 / omega * ((1.0 + z * z).sqrt() - z)
        })
        .fold(f64::INFINITY, f64::min)
        .min(1.0)
}
