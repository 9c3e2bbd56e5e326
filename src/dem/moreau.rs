//! Rigid-contact time stepping: the Moreau-Jean scheme of non-smooth contact dynamics
//! (Moreau 1988, "Unilateral contact and dry friction in finite freedom dynamics"; Jean 1999,
//! "The non-smooth contact dynamics method", CMAME 177:235-257; Acary & Brogliato 2008,
//! "Numerical methods for nonsmooth dynamical systems", ch. 10), chosen with
//! `[dem] integrator = "moreau"` (`crate::dem_settings::Integrator`).
//!
//! The blocks are rigid and so are their contacts: no spring presses in, and the time step is
//! set by the motion of the blocks (`MOREAU_STEP_SHARE` of the gravity time, about 1e-3 s),
//! not by a contact stiffness (the explicit stepping's 1e-5 s). The contacts are those the
//! explicit world finds (`World::find_contacts`: a vertex of one block on an edge of the other,
//! at the ends of every joint, including vertices within `contact_tolerance` outside a facing
//! edge). One step of length `h`, after that contact search, is four named stages:
//!
//! 1. [`free_velocities`]: each free block's velocity without the contacts,
//!    `v_free = v_k + h M^-1 f(q_k, t_k)` (the loads of `World::integrate`, at the start of the
//!    step: the "theta" of the forces is 0, explicit, since they are smooth and cheap).
//! 2. [`contact_rows`]: one row per contact point, with its normal `n` (the touched edge's
//!    outward normal) and tangent `t`, the lever arms to both centroids, the diagonal of the
//!    Delassus operator `W = J M^-1 J^T` for the normal and the tangent, and the normal
//!    velocity the contact must reach (its right-hand side), see below. The two contacts
//!    the explicit world keeps at each end of a joint (a vertex of each block on the other's
//!    face, at the same point along opposite normals) are one constraint for rigid blocks:
//!    [`merge_corners`] keeps one row for them.
//! 3. The contact impulses `(p_n, p_t)`: first the direct solve of
//!    [`super::active_set`] (a primal-dual active set on the contacts' statuses, each iterate
//!    a sparse direct solve of `W` restricted to the closed contacts), warm-started from the
//!    last step's impulses of the contacts that persist; where it gives up, [`solve`]:
//!    projected Gauss-Seidel (Jean & Moreau's "NSCD" solver) from the same warm start: for
//!    each contact in turn the normal impulse `p_n <- max(0, p_n - (u_n - b_n) / W_nn)`
//!    (Signorini at the velocity level: `0 <= p_n`, `u_n >= b_n`, complementary), then the
//!    tangential one `p_t <- proj_[-mu p_n, mu p_n](p_t - u_t / W_tt)` (Coulomb: sticking
//!    with `u_t = 0`, or sliding at `|p_t| = mu p_n` against the slip), sweeping until no
//!    contact law is violated by more than 1e-3 of `rest_velocity` (in the velocities,
//!    [`residual`]), or [`MAX_SWEEPS`] sweeps; forward and backward in turn (symmetric
//!    Gauss-Seidel). Alone, Gauss-Seidel converges on single blocks but not on an arch (a
//!    chain of 20 blocks: it stopped at its sweeps short of the tolerance in 91 % of the
//!    moving steps of `benches/dynamic.rs`, docs/performance.md), which the direct solve
//!    settles in one to a few factorisations.
//! 4. [`advance`]: `v_{k+1} = v_free + M^-1 J^T p`, `q_{k+1} = q_k + h v_{k+1}` (theta = 1:
//!    positions from the new velocities, which for the smooth motion is the symplectic Euler of
//!    the explicit stepping, so a free rocking block keeps its energy between impacts; theta
//!    = 1/2 would not be symplectic with forces taken at the start of the step).
//!
//! Which contacts are rows, and their right-hand side `b_n` (gap `g`, the negative of the
//! depth):
//! - an open contact, `g >` [`SLOP`] of `contact_tolerance`, is a row only when the free
//!   motion closes it within the step, `g + h u_n,free <= 0` (the index set of Moreau-Jean,
//!   predicted from the free velocity so that a block resting on a gap of round-off is held,
//!   not dropped for a step; a smaller gap counts as closed, since a contact the free motion
//!   leaves alone, the crown joint of an arch under its weight, may be pressed shut by the
//!   others), with
//!   `b_n = 0`: the impact is taken at the start of the step in which the contact lands, and
//!   the block may end the step up to `h |u_n|` short of touching (first order in `h`:
//!   `tests/it/dem_moreau.rs` measures it on Housner's impact);
//! - a closed contact, `g <= SLOP contact_tolerance`: `u_n >= 0`, Newton's impact law with a
//!   coefficient of restitution 0 at the contact point (the blocks do not bounce off each other; a rocking
//!   block still rocks on, since the impulse at the new pivot leaves it turning about that
//!   pivot: Housner's impact, `omega+ / omega- = 1 - 1.5 sin^2 alpha` for a rectangle, arises
//!   from the geometry);
//! - plus, where the vertex has sunk deeper than [`SLOP`] of `contact_tolerance`, a push-out
//!   of [`BAUMGARTE`] of that excess per step (Baumgarte's stabilisation): the velocity-level
//!   law keeps contacts from closing further but not from the small sinking of a step's
//!   round-off, which would otherwise accumulate.
//!
//! What it does not do: ties, strips and the fill's passive bars are elastic springs as stiff
//! as the explicit contacts, which a step of 1e-3 s cannot integrate, so a model with any is
//! refused (`check_time_step`); Cundall's local damping is not applied (rigid contacts need
//! no damping to come to rest: a block below its threshold never moves), so the settling and
//! the constant-lambda runs of the collapse search are undamped.

use super::world::{add_loads, World};
use crate::geometry::{cross, Vec2};

/// Most projected Gauss-Seidel sweeps in one step. Warm-started, a structure at rest or in a
/// mechanism takes a few; an impact on a chain of many blocks takes more.
pub const MAX_SWEEPS: usize = 400;

/// Penetration (as a share of `contact_tolerance`) left alone by the position stabilisation.
pub const SLOP: f64 = 0.01;

/// Share of the penetration beyond the slop pushed out in one step.
pub const BAUMGARTE: f64 = 0.2;

/// One contact point's constraint: vertex body `a` against edge body `b`.
pub(super) struct Row {
    pub(super) a: usize,
    pub(super) b: usize,
    /// Lever arms from the centroids of `a` and `b` to the contact point.
    pub(super) ra: Vec2,
    pub(super) rb: Vec2,
    pub(super) n: Vec2,
    pub(super) t: Vec2,
    /// Inverse diagonal of the Delassus operator along `n` and `t` (1 / W_nn, 1 / W_tt).
    pub(super) kn: f64,
    pub(super) kt: f64,
    /// Normal velocity the contact must reach at least (m/s).
    pub(super) target: f64,
    pub(super) mu: f64,
    pub(super) pn: f64,
    pub(super) pt: f64,
    /// The contact point (the vertex) and its penetration (m; negative: a gap).
    point: Vec2,
    depth: f64,
    /// Pair and contact index in `World::pairs`.
    pub(super) pair: usize,
    pub(super) contact: usize,
}

/// Velocities and inverse masses of the bodies for the solve.
pub(super) struct State {
    pub(super) vel: Vec<(Vec2, f64)>,
    pub(super) inv: Vec<(f64, f64)>,
}

impl State {
    pub(super) fn point_velocity(&self, i: usize, r: Vec2) -> Vec2 {
        let (v, w) = self.vel[i];
        v + w * Vec2::new(-r.y, r.x)
    }

    /// Relative velocity of the vertex body's point over the edge body's.
    pub(super) fn relative(&self, row: &Row) -> Vec2 {
        self.point_velocity(row.a, row.ra) - self.point_velocity(row.b, row.rb)
    }

    /// The velocities `free + M^-1 J^T p` of the rows' impulses `p` from the free velocities.
    pub(super) fn impulses_from(&mut self, free: &[(Vec2, f64)], rows: &[Row]) {
        self.vel.copy_from_slice(free);
        for row in rows {
            self.apply(row, row.pn * row.n + row.pt * row.t);
        }
    }

    /// Apply the impulse `p` at the row's point, `+p` on the vertex body, `-p` on the other.
    pub(super) fn apply(&mut self, row: &Row, p: Vec2) {
        let (ma, ia) = self.inv[row.a];
        let va = &mut self.vel[row.a];
        va.0 += ma * p;
        va.1 += ia * cross(row.ra, p);
        let (mb, ib) = self.inv[row.b];
        let vb = &mut self.vel[row.b];
        vb.0 -= mb * p;
        vb.1 -= ib * cross(row.rb, p);
    }
}

/// One Moreau-Jean step of `world` (module docs), after its contact search; the caller
/// advances the clock.
pub(crate) fn step(world: &mut World) {
    let mut state = free_velocities(world);
    let free = state.vel.clone();
    let mut rows = contact_rows(world, &state);
    let tolerance = 1e-3 * world.params.rest_velocity;
    let warm: Vec<(f64, f64)> = rows.iter().map(|r| (r.pn, r.pt)).collect();
    let direct = super::active_set::solve(&mut rows, &mut state, &free, tolerance);
    // If the active set gives up, the Gauss-Seidel sweeps start from the last step's
    // impulses (warm start), as they would alone.
    let ok = direct || {
        for (row, &(pn, pt)) in rows.iter_mut().zip(&warm) {
            row.pn = pn;
            row.pt = pt;
        }
        state.impulses_from(&free, &rows);
        solve(&mut rows, &mut state, tolerance)
    };
    if !ok {
        world.unconverged += 1;
    }
    advance(world, &state, &rows);
}

/// The warning of a run (or a collapse search) in which `unconverged` of `steps` time steps
/// ended with the contact laws broken beyond the solve's tolerance.
pub(crate) fn unconverged_warning(unconverged: u64, steps: u64) -> String {
    format!(
        "the Moreau-Jean contact solve stopped short of its tolerance in {unconverged} of {steps} time steps (the active set did not settle, and projected Gauss-Seidel stopped at {MAX_SWEEPS} sweeps): the contact laws hold only approximately there; compare with dem.integrator = \"explicit\""
    )
}

/// Stage 1: velocities under the loads alone, and the inverse masses (0 for fixed bodies).
fn free_velocities(world: &World) -> State {
    let h = world.dt;
    let (load, d) = (world.load, world.seismic_direction);
    let mut vel = Vec::with_capacity(world.bodies.len());
    let mut inv = Vec::with_capacity(world.bodies.len());
    for body in &world.bodies {
        if body.fixed {
            vel.push((Vec2::zeros(), 0.0));
            inv.push((0.0, 0.0));
            continue;
        }
        let (f, m) = add_loads(body, load, d, Vec2::zeros(), 0.0);
        vel.push((
            body.vel + f * (h / body.mass),
            body.omega + m * h / body.inertia,
        ));
        inv.push((1.0 / body.mass, 1.0 / body.inertia));
    }
    State { vel, inv }
}

/// Stage 2: the rows of every contact point, with their right-hand sides (module docs) and
/// the last step's impulses.
fn contact_rows(world: &World, state: &State) -> Vec<Row> {
    let h = world.dt;
    let slop = SLOP * world.params.contact_tolerance;
    let mut rows = Vec::new();
    for (k, pair) in world.pairs.iter().enumerate() {
        let from = rows.len();
        for (j, c) in pair.contacts.iter().enumerate() {
            let (a, b) = if c.flipped {
                (pair.b, pair.a)
            } else {
                (pair.a, pair.b)
            };
            let (ba, bb) = (&world.bodies[a], &world.bodies[b]);
            let point = ba.world[c.vertex];
            let n = bb.normals[c.edge];
            let t = Vec2::new(-n.y, n.x);
            let (ra, rb) = (point - ba.pos, point - bb.pos);
            let w = |dir: Vec2| {
                let (ma, ia) = state.inv[a];
                let (mb, ib) = state.inv[b];
                ma + mb + ia * cross(ra, dir).powi(2) + ib * cross(rb, dir).powi(2)
            };
            let (wn, wt) = (w(n), w(t));
            if !(wn > 0.0 && wt > 0.0) {
                continue;
            }
            let target = if c.depth < -slop {
                // Open: a constraint only if the free motion closes it within the step. A gap
                // within the slop counts as touching: a contact the free motion does not close
                // (the crown joint of an arch under its weight, both blocks falling alike) may
                // still be pressed shut by the rest of the structure, and a gap of round-off
                // must not drop it.
                let un = state.point_velocity(a, ra) - state.point_velocity(b, rb);
                if -c.depth + h * un.dot(&n) > 0.0 {
                    continue;
                }
                0.0
            } else {
                BAUMGARTE * (c.depth - slop).max(0.0) / h
            };
            rows.push(Row {
                a,
                b,
                ra,
                rb,
                n,
                t,
                kn: 1.0 / wn,
                kt: 1.0 / wt,
                target,
                mu: pair.mu,
                pn: c.impulse.0,
                pt: c
                    .impulse
                    .1
                    .max(-pair.mu * c.impulse.0)
                    .min(pair.mu * c.impulse.0),
                point,
                depth: c.depth,
                pair: k,
                contact: j,
            });
        }
        merge_corners(&mut rows, from, world.params.contact_tolerance);
    }
    rows
}

/// Fold the rows of one pair (from `from` on) that are one corner seen from both blocks: at
/// each end of a joint between faces that end at the same corners, a vertex of each block
/// touches the other's face at the same point, along opposite normals (`World::find_contacts`
/// keeps both, which the penalty springs need). For rigid contacts they are the same
/// constraint twice, the Delassus operator twice singular at every joint end, so one row is
/// kept: the deeper one, with the two impulses summed (`n' = -n`, `t' = -t` and the bodies
/// swapped, so the components of the impulse on either body add as they are).
fn merge_corners(rows: &mut Vec<Row>, from: usize, reach: f64) {
    let mut i = from;
    while i < rows.len() {
        let mut j = i + 1;
        while j < rows.len() {
            let (x, y) = (&rows[i], &rows[j]);
            if x.a == y.b
                && x.b == y.a
                && (x.point - y.point).norm() <= reach
                && x.n.dot(&y.n) < -0.99
            {
                let y = rows.remove(j);
                let (pn, pt) = (rows[i].pn + y.pn, rows[i].pt + y.pt);
                if y.depth > rows[i].depth {
                    rows[i] = y;
                }
                rows[i].pn = pn;
                rows[i].pt = pt;
            } else {
                j += 1;
            }
        }
        i += 1;
    }
}

/// Stage 3: projected Gauss-Seidel until the contact laws hold to `tolerance` (m/s, see
/// [`residual`]) after a sweep, or [`MAX_SWEEPS`]. Returns whether it got there.
fn solve(rows: &mut [Row], state: &mut State, tolerance: f64) -> bool {
    for sweep in 1..=MAX_SWEEPS {
        // Symmetric Gauss-Seidel: forward and backward sweeps in turn, so a load change at
        // one end of a chain of blocks (an arch) reaches the other end in one sweep pair
        // whichever way the contacts are numbered.
        let order: Box<dyn Iterator<Item = &mut Row>> = if sweep % 2 == 1 {
            Box::new(rows.iter_mut())
        } else {
            Box::new(rows.iter_mut().rev())
        };
        for row in order {
            let un = state.relative(row).dot(&row.n);
            let pn = (row.pn - (un - row.target) * row.kn).max(0.0);
            let dn = pn - row.pn;
            if dn != 0.0 {
                state.apply(row, dn * row.n);
                row.pn = pn;
            }
            let ut = state.relative(row).dot(&row.t);
            let cap = row.mu * row.pn;
            // `max` then `min`, not `clamp`: a NaN must reach the divergence checks.
            let pt = (row.pt - ut * row.kt).max(-cap).min(cap);
            let dt = pt - row.pt;
            if dt != 0.0 {
                state.apply(row, dt * row.t);
                row.pt = pt;
            }
        }
        let r = residual(rows, state);
        // A NaN residual ends the sweeps too: the divergence checks see the state.
        if r.is_nan() || r <= tolerance {
            return true;
        }
    }
    false
}

/// The largest violation (m/s) of the contact laws by the impulses and velocities: Signorini
/// (`u_n >= b_n`, and `u_n = b_n` where `p_n > 0`) and Coulomb (`u_t = 0` where sticking,
/// `|p_t| < mu p_n`; a slip against `p_t` where sliding). Measured on the velocities, not on
/// the impulses: two contacts at one corner (a vertex of each block on the other's face) are
/// redundant, and their impulses may trade between them without changing any velocity.
pub(super) fn residual(rows: &[Row], state: &State) -> f64 {
    let mut worst: f64 = 0.0;
    for row in rows {
        let u = state.relative(row);
        let (un, ut) = (u.dot(&row.n) - row.target, u.dot(&row.t));
        let normal = if row.pn > 0.0 {
            un.abs()
        } else {
            (-un).max(0.0)
        };
        let cap = row.mu * row.pn;
        let tangent = if row.pn <= 0.0 {
            0.0
        } else if row.pt.abs() < cap {
            ut.abs()
        } else {
            (ut * row.pt.signum()).max(0.0)
        };
        worst = worst.max(normal).max(tangent);
    }
    worst
}

/// Stage 4: the new velocities and positions, the impulses kept on the contacts (as forces
/// `p / h` for the readers of `normal_force`, `shear` and `sliding`), and the rest measures
/// (`World::unbalanced`: the net force `m (v_{k+1} - v_k) / h` over the load scale).
fn advance(world: &mut World, state: &State, rows: &[Row]) {
    let h = world.dt;
    for pair in &mut world.pairs {
        for c in &mut pair.contacts {
            c.impulse = (0.0, 0.0);
            c.normal_force = 0.0;
            c.shear = 0.0;
            c.sliding = false;
        }
    }
    let slip = world.params.rest_velocity;
    for row in rows {
        let ut = state.relative(row).dot(&row.t);
        let c = &mut world.pairs[row.pair].contacts[row.contact];
        c.impulse = (row.pn, row.pt);
        c.normal_force = row.pn / h;
        c.shear = row.pt / h;
        c.sliding =
            row.pn > 0.0 && row.pt.abs() >= row.mu * row.pn * (1.0 - 1e-9) && ut.abs() > slip;
    }
    for ((body, &(v, w)), net) in world
        .bodies
        .iter_mut()
        .zip(&state.vel)
        .zip(&mut world.force)
    {
        if body.fixed {
            continue;
        }
        *net = (
            body.mass * (v - body.vel) / h,
            body.inertia * (w - body.omega) / h,
        );
        body.vel = v;
        body.omega = w;
        body.pos += v * h;
        body.angle += w * h;
        body.refresh();
    }
}
