//! The direct solve of one Moreau-Jean step's contact problem ([`super::moreau`]): a
//! primal-dual active set on the contacts' statuses, each iterate a sparse direct solve of the
//! Delassus operator restricted to the closed contacts.
//!
//! **The problem.** With `b = J v_free - target` (the contact velocities of the free motion
//! less the normal velocities the contacts must reach) and `W = J M^-1 J^T` (the Delassus
//! operator), the contact velocities after the step are `u = W p + b`, and every contact's
//! impulses `(p_n, p_t)` and velocities `(u_n, u_t)` must satisfy Signorini's law
//! `0 <= p_n _|_ u_n >= 0` and Coulomb's, `|p_t| <= mu p_n`, `u_t = 0` where `|p_t| < mu p_n`,
//! `p_t = -mu p_n sign(u_t)` where it slips (Moreau 1988; Jean 1999, CMAME 177:235-257, §3;
//! Acary & Brogliato 2008, "Numerical methods for nonsmooth dynamical systems", §13.3).
//!
//! **The active set.** Each contact has a status: open (`p = 0`), sticking (`u_n = u_t = 0`)
//! or slipping with the sign `s` of its friction (`u_n = 0`, `p_t = s mu p_n`). Given the
//! statuses the laws are linear: the unknowns are `p_n` of the closed contacts and `p_t` of the
//! sticking ones, one equation `u = 0` for each, and a slipping contact's `p_t = s mu p_n`
//! enters through its `p_n` (its tangent's column of `W`, times `s mu`, added to its normal's:
//! the matrix is `W_FF` made unsymmetric by friction). After each solve the statuses are
//! updated from the laws the iterate breaks: a closed contact pulling (`p_n < 0`) opens, an
//! open one closing (`u_n < -tol`) closes sticking, a sticking one beyond its cone
//! (`|p_t| > mu p_n`) slips toward its friction, a slipping one that moves with its friction
//! (`s u_t > tol`) sticks. All at once, this is the primal-dual active set strategy, a
//! semi-smooth Newton method on the complementarity functions `p_n - max(0, p_n - c u_n)` and
//! `p_t - proj_[-mu p_n, mu p_n](p_t - c u_t)` of Alart & Curnier (1991, CMAME 92:353-375)
//! (Hintermüller, Ito & Kunisch 2002, SIAM J. Optim. 13:865-888; Hüeber & Wohlmuth 2005,
//! CMAME 194:3147-3166 with friction); warm-started from the last step's statuses, a step
//! whose contacts do not change takes one solve. Started far from the answer (an impact on
//! an arch closes joints whose neighbours then pull), all at once may overshoot and cycle, so
//! as soon as an iterate breaks no fewer laws than the last, the statuses change one at a
//! time, the most broken law (in velocity: the impulse over `W`'s diagonal) first, a
//! principal pivoting step (Murty 1988, "Linear complementarity, linear and nonlinear
//! programming", ch. 4), skipping a change that leads back to statuses already tried in the
//! step (with friction the pivoting can cycle: the cone makes the problem non-monotone).
//!
//! **The linear solve.** The matrix is sparse: two rows are coupled only through a body both
//! touch. With the contacts numbered pair by pair (`World::pairs`, sorted by body), the
//! coupling of a chain of blocks (an arch) lies in a narrow band about the diagonal, and its
//! `L D U` factors in envelope (skyline) storage cost `O(n b^2)` for `n` rows of half-bandwidth
//! `b` (George & Liu 1981, "Computer solution of large sparse positive definite systems",
//! ch. 4; the pattern is symmetric, so the upper factor has the lower one's envelope), a few
//! microseconds for the 20-voussoir arch. No pivoting: without friction the matrix is positive
//! definite, and a folded friction column changes a pivot by at most `mu` times the
//! coupling; a pivot that is not finite or under `1e-12` of its row's scale gives up. An
//! assembly in rigid contact is statically indeterminate (two contact points at each end of
//! every joint are more constraints than the blocks' degrees of freedom), so `W` is singular:
//! its diagonal is raised by [`REGULARISATION`] of itself (a contact compliance: the impulses
//! of the redundant constraints are shared as elastic contacts of equal stiffness would share
//! them). Each solve is followed by up to [`REFINEMENTS`] steps of iterative refinement of
//! the equations without the regularisation, their residual measured on the velocities
//! themselves (iterated Tikhonov regularisation: it removes the regularisation's velocity
//! error `REGULARISATION W_ii p_i` wherever `W` is not singular, and the round-off of a matrix
//! as ill-conditioned as the regularisation is small), a step kept only if it halves the
//! largest residual (where the Baumgarte targets of redundant contacts disagree no impulse
//! meets them all, and refining would only grow the self-equilibrated impulses).
//!
//! It gives up (and the caller's projected Gauss-Seidel solves the step from the last step's
//! impulses, as it would alone) when the statuses have not settled in [`MAX_ITERATIONS`],
//! settle with a law broken beyond the tolerance, a pivot fails, or the envelope is larger
//! than [`MAX_ENVELOPE`] entries.

use super::moreau::{Row, State};
use crate::geometry::{cross, Vec2};

/// Most active-set iterations (one factorisation each) in one step.
pub const MAX_ITERATIONS: usize = 200;

/// Share of the Delassus operator's diagonal added to it (module docs). One solve changes a
/// contact velocity by this share of `W_ii p_i`, the velocity the contact's impulse alone
/// would make (up to about 0.2 m/s at the springings of the 20-voussoir arch of
/// `benches/dynamic.rs`), against a tolerance of 1e-3 `rest_velocity` (3e-8 m/s there); the
/// refinement then removes that error wherever `W` is not singular. Chosen on that arch under
/// the record at scale 2.1 when the refinement still kept the regularisation (and before the
/// rule against cycling): 1e-7 broke the laws by its own error in 90 % of the steps, 1e-8 left
/// 90 steps of 21,610 unsettled, 1e-9 and 1e-10 about 225 (a matrix that ill-conditioned
/// defeats the refinement). With both, 20 steps.
pub const REGULARISATION: f64 = 1e-8;

/// Steps of iterative refinement after each solve.
pub const REFINEMENTS: usize = 3;

/// Largest envelope of the factor (entries) the direct solve takes on; above it the projected
/// Gauss-Seidel solves the step alone.
pub const MAX_ENVELOPE: usize = 4_000_000;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Status {
    Open,
    Stick,
    /// Slipping, with the sign of its friction impulse `p_t = s mu p_n`.
    Slip(f64),
}

/// One row of `J` (a contact's normal or tangent) on one body: its signed direction and
/// signed moment arm `cross(r, d)` (the body's inverse mass and inertia are applied where `W`
/// is assembled).
#[derive(Clone, Copy)]
struct Entry {
    row: usize,
    d: Vec2,
    c: f64,
}

/// Statuses from the last step's impulses: closed where the contact pushed, sticking inside
/// the cone; a new row (no impulse) starts sticking if the free motion closes it (`b`: the
/// free contact velocities less the targets, normal and tangent per row).
fn initial_statuses(rows: &[Row], b: &[f64]) -> Vec<Status> {
    rows.iter()
        .zip(b.chunks_exact(2))
        .map(|(row, bk)| {
            if row.pn > 0.0 {
                if row.pt.abs() < row.mu * row.pn * (1.0 - 1e-9) {
                    Status::Stick
                } else {
                    Status::Slip(row.pt.signum())
                }
            } else if bk[0] < 0.0 {
                Status::Stick
            } else {
                Status::Open
            }
        })
        .collect()
}

/// Solve the contact problem of `rows` (module docs) from the free velocities `free`,
/// leaving the impulses in `rows` and the velocities they give in `state`. Returns whether
/// it found the statuses that break no law by more than `tolerance` (m/s, as
/// [`super::moreau::residual`] measures); either way `rows` and `state` hold a consistent
/// iterate (impulses in their cones and the velocities they give).
pub(super) fn solve(
    rows: &mut [Row],
    state: &mut State,
    free: &[(Vec2, f64)],
    tolerance: f64,
) -> bool {
    let m = rows.len();
    if m == 0 {
        return true;
    }
    // J's entries per body (2k: the normal of row k, 2k + 1: its tangent), with M^-1.
    let nb = state.vel.len();
    let mut by_body: Vec<Vec<Entry>> = vec![Vec::new(); nb];
    for (k, row) in rows.iter().enumerate() {
        for (body, r, sign) in [(row.a, row.ra, 1.0), (row.b, row.rb, -1.0)] {
            if state.inv[body].0 == 0.0 && state.inv[body].1 == 0.0 {
                continue;
            }
            for (j, d) in [(2 * k, row.n), (2 * k + 1, row.t)] {
                by_body[body].push(Entry {
                    row: j,
                    d: sign * d,
                    c: sign * cross(r, d),
                });
            }
        }
    }
    let touched: Vec<usize> = (0..nb).filter(|&i| !by_body[i].is_empty()).collect();
    // The free contact velocities less the targets.
    state.vel.copy_from_slice(free);
    let b: Vec<f64> = rows
        .iter()
        .flat_map(|row| {
            let u = state.relative(row);
            [u.dot(&row.n) - row.target, u.dot(&row.t)]
        })
        .collect();
    let mut status = initial_statuses(rows, &b);
    let mut p = vec![0.0; 2 * m];
    for (k, row) in rows.iter().enumerate() {
        p[2 * k] = row.pn.max(0.0);
    }
    let mut local = vec![usize::MAX; 2 * m];
    // Per row of J: the column of the unknowns it multiplies (its own, or for a slipping
    // contact's tangent its normal's) and the factor (1, or s mu).
    let mut column = vec![(usize::MAX, 0.0); 2 * m];
    let mut lu = Envelope::default();
    let (mut one_at_a_time, mut last_broken) = (false, usize::MAX);
    let mut tried = std::collections::HashSet::new();
    for _ in 0..MAX_ITERATIONS {
        tried.insert(key(&status));
        // Unknowns F (in row order): p_n of the closed contacts, p_t of the sticking ones;
        // a slipping contact's p_t = s mu p_n enters through its p_n's column.
        let mut unknowns = Vec::with_capacity(2 * m);
        for (k, s) in status.iter().enumerate() {
            match *s {
                Status::Open => {}
                Status::Stick => unknowns.extend([2 * k, 2 * k + 1]),
                Status::Slip(_) => unknowns.push(2 * k),
            }
        }
        local.iter_mut().for_each(|l| *l = usize::MAX);
        for (i, &j) in unknowns.iter().enumerate() {
            local[j] = i;
        }
        for (k, s) in status.iter().enumerate() {
            let (n, t) = (2 * k, 2 * k + 1);
            column[n] = (local[n], 1.0);
            column[t] = match *s {
                Status::Slip(sign) => (local[n], sign * rows[k].mu),
                _ => (local[t], 1.0),
            };
        }
        let mut rhs: Vec<f64> = unknowns.iter().map(|&j| -b[j]).collect();
        if !lu.assemble(&local, &column, &by_body, &touched, state) || !lu.factor() {
            return finish(rows, state, free, &p, &status, tolerance, false);
        }
        lu.solve(&mut rhs);
        let mut x = rhs;
        let mut r = Vec::with_capacity(x.len());
        spread(&x, &local, &status, rows, &mut p);
        // Iterative refinement of the equations without the regularisation (iterated
        // Tikhonov: each step solves for the residual `-u_F` measured on the velocities with
        // the same factors, so `u_F` goes to 0 wherever `W` is not singular, and the
        // regularisation's own error `REGULARISATION W_ii p_i` goes with it); a step is
        // kept only if it at least halves the largest residual (a residual `W` cannot reach,
        // where the targets of redundant contacts disagree, would only grow the impulses).
        let mut norm = equations(rows, state, free, &p, &unknowns, &mut r);
        for _ in 0..REFINEMENTS {
            if norm <= 1e-3 * tolerance {
                break;
            }
            lu.solve(&mut r);
            let before = x.clone();
            for (xi, d) in x.iter_mut().zip(&r) {
                *xi += d;
            }
            spread(&x, &local, &status, rows, &mut p);
            let next = equations(rows, state, free, &p, &unknowns, &mut r);
            // A NaN residual is no improvement either.
            if next.is_nan() || next > 0.5 * norm {
                x = before;
                spread(&x, &local, &status, rows, &mut p);
                break;
            }
            norm = next;
        }
        // The velocities of this iterate, and the laws it breaks.
        set_velocities(rows, state, free, &p);
        // Each broken law, with its size in velocity (an impulse times W's diagonal).
        let mut broken: Vec<(f64, usize, Status)> = Vec::new();
        for (k, row) in rows.iter().enumerate() {
            let u = state.relative(row);
            let (un, ut) = (u.dot(&row.n) - row.target, u.dot(&row.t));
            let (pn, pt) = (p[2 * k], p[2 * k + 1]);
            let change = match status[k] {
                Status::Open if un < -tolerance => Some((-un, Status::Stick)),
                Status::Open => None,
                _ if pn < 0.0 => Some((-pn / row.kn, Status::Open)),
                Status::Stick if pt.abs() > row.mu * pn => {
                    Some(((pt.abs() - row.mu * pn) / row.kt, Status::Slip(pt.signum())))
                }
                Status::Stick => None,
                Status::Slip(s) if s * ut > tolerance => Some((s * ut, Status::Stick)),
                Status::Slip(_) => None,
            };
            if let Some((size, next)) = change {
                broken.push((size, k, next));
            }
        }
        let changed = !broken.is_empty();
        // All at once while that settles more laws each time (the semi-smooth Newton step);
        // once it does not, one at a time, the most broken first (a principal pivoting
        // step, which cannot cycle on the normal laws: W + REGULARISATION diag(W) is
        // positive definite, a P-matrix; Murty 1988, "Linear complementarity, linear and
        // nonlinear programming", ch. 4).
        if one_at_a_time || broken.len() >= last_broken {
            one_at_a_time = true;
            // The most broken law whose change leads to statuses not tried yet in this
            // step (so the pivoting cannot cycle), else the most broken.
            broken.sort_by(|x, y| y.0.total_cmp(&x.0));
            let fresh = broken.iter().find(|&&(_, k, next)| {
                let old = std::mem::replace(&mut status[k], next);
                let seen = tried.contains(&key(&status));
                status[k] = old;
                !seen
            });
            if let Some(&(_, k, next)) = fresh.or(broken.first()) {
                status[k] = next;
            }
        } else {
            for &(_, k, next) in &broken {
                status[k] = next;
            }
        }
        last_broken = broken.len();
        // Settled: the laws hold to the tolerance, or the solve of these statuses is off.
        if !changed {
            return finish(rows, state, free, &p, &status, tolerance, true);
        }
    }
    finish(rows, state, free, &p, &status, tolerance, false)
}

/// The impulses of every contact from the unknowns `x`: 0 where open, `s mu p_n` for a
/// slipping contact's friction.
fn spread(x: &[f64], local: &[usize], status: &[Status], rows: &[Row], p: &mut [f64]) {
    for (k, s) in status.iter().enumerate() {
        let (pn, pt) = match *s {
            Status::Open => (0.0, 0.0),
            Status::Stick => (x[local[2 * k]], x[local[2 * k + 1]]),
            Status::Slip(sign) => {
                let pn = x[local[2 * k]];
                (pn, sign * rows[k].mu * pn)
            }
        };
        p[2 * k] = pn;
        p[2 * k + 1] = pt;
    }
}

/// The velocities of the impulses `p`, and the residual `-u` of each unknown's equation (its
/// row's velocity less its target) into `r`; returns the largest.
fn equations(
    rows: &[Row],
    state: &mut State,
    free: &[(Vec2, f64)],
    p: &[f64],
    unknowns: &[usize],
    r: &mut Vec<f64>,
) -> f64 {
    set_velocities(rows, state, free, p);
    r.clear();
    r.extend(unknowns.iter().map(|&j| {
        let row = &rows[j / 2];
        let u = state.relative(row);
        if j % 2 == 0 {
            row.target - u.dot(&row.n)
        } else {
            -u.dot(&row.t)
        }
    }));
    r.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The statuses as a key of the set of those tried.
fn key(status: &[Status]) -> Vec<i8> {
    status
        .iter()
        .map(|s| match *s {
            Status::Open => 0,
            Status::Stick => 1,
            Status::Slip(sign) => 2 + i8::from(sign > 0.0),
        })
        .collect()
}

/// `state.vel = free + M^-1 J^T p`.
fn set_velocities(rows: &[Row], state: &mut State, free: &[(Vec2, f64)], p: &[f64]) {
    state.vel.copy_from_slice(free);
    for (k, row) in rows.iter().enumerate() {
        state.apply(row, p[2 * k] * row.n + p[2 * k + 1] * row.t);
    }
}

/// Leave a consistent iterate in `rows` and `state` (impulses inside the cones, the
/// velocities they give), and say whether it solves the step.
fn finish(
    rows: &mut [Row],
    state: &mut State,
    free: &[(Vec2, f64)],
    p: &[f64],
    status: &[Status],
    tolerance: f64,
    settled: bool,
) -> bool {
    for (k, row) in rows.iter_mut().enumerate() {
        let pn = p[2 * k].max(0.0);
        row.pn = pn;
        row.pt = if status[k] == Status::Open {
            0.0
        } else {
            p[2 * k + 1].max(-row.mu * pn).min(row.mu * pn)
        };
    }
    state.impulses_from(free, rows);
    let r = super::moreau::residual(rows, state);
    settled && (r.is_nan() || r <= tolerance)
}

/// The matrix of the unknowns' equations (module docs), `W` with a slipping contact's
/// tangent column folded into its normal's, plus [`REGULARISATION`] of `W`'s diagonal, and
/// its `L D U` factors in envelope storage (the pattern is symmetric, the values not): row
/// `i` of the lower part and column `i` of the upper part hold `first[i]..i`, at `start[i]`.
#[derive(Default)]
struct Envelope {
    first: Vec<usize>,
    start: Vec<usize>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    diag: Vec<f64>,
    /// `W`'s own diagonal of each unknown, the scale of its pivot.
    scale: Vec<f64>,
}

impl Envelope {
    fn at(&self, i: usize, j: usize) -> usize {
        self.start[i] + j - self.first[i]
    }

    /// Assemble the matrix: the equation of row `x` of `J` (`local[x]`) and the column of
    /// row `y` (`column[y]`) sum over the bodies both touch `M^-1`-weighted products of
    /// their directions and arms. False when the envelope is over [`MAX_ENVELOPE`].
    fn assemble(
        &mut self,
        local: &[usize],
        column: &[(usize, f64)],
        by_body: &[Vec<Entry>],
        touched: &[usize],
        state: &State,
    ) -> bool {
        let n = local.iter().filter(|&&l| l != usize::MAX).count();
        self.first.clear();
        self.first.extend(0..n);
        for &body in touched {
            let lowest = by_body[body]
                .iter()
                .map(|e| column[e.row].0.min(local[e.row]))
                .min()
                .unwrap_or(usize::MAX);
            for e in &by_body[body] {
                for l in [local[e.row], column[e.row].0] {
                    if l != usize::MAX {
                        self.first[l] = self.first[l].min(lowest);
                    }
                }
            }
        }
        self.start.clear();
        let mut size = 0;
        for i in 0..n {
            self.start.push(size);
            size += i - self.first[i];
        }
        if size > MAX_ENVELOPE {
            return false;
        }
        self.lower.clear();
        self.lower.resize(size, 0.0);
        self.upper.clear();
        self.upper.resize(size, 0.0);
        self.diag.clear();
        self.diag.resize(n, 0.0);
        self.scale.clear();
        self.scale.resize(n, 0.0);
        for &body in touched {
            let (im, ii) = state.inv[body];
            let entries = &by_body[body];
            for x in entries {
                let i = local[x.row];
                if i == usize::MAX {
                    continue;
                }
                for y in entries {
                    let (j, factor) = column[y.row];
                    if j == usize::MAX {
                        continue;
                    }
                    let w = im * x.d.dot(&y.d) + ii * x.c * y.c;
                    if x.row == y.row {
                        self.scale[i] += w;
                    }
                    let v = factor * w;
                    match j.cmp(&i) {
                        std::cmp::Ordering::Equal => self.diag[i] += v,
                        std::cmp::Ordering::Less => {
                            let at = self.at(i, j);
                            self.lower[at] += v;
                        }
                        std::cmp::Ordering::Greater => {
                            let at = self.at(j, i);
                            self.upper[at] += v;
                        }
                    }
                }
            }
        }
        for (d, s) in self.diag.iter_mut().zip(&self.scale) {
            *d += REGULARISATION * s;
        }
        true
    }

    /// In-place `L D U` (Crout, no pivoting: the pivots of a positive definite matrix, which
    /// the folded friction columns perturb by at most `mu` times the coupling). False at a
    /// pivot that is not finite or under `1e-12` of its scale.
    fn factor(&mut self) -> bool {
        let n = self.first.len();
        for i in 0..n {
            let fi = self.first[i];
            for j in fi..i {
                let fj = self.first[j];
                let k0 = fi.max(fj);
                let (ri, rj) = (self.at(i, k0), self.at(j, k0));
                let mut sl = self.lower[self.at(i, j)];
                let mut su = self.upper[self.at(i, j)];
                for k in 0..(j - k0) {
                    let d = self.diag[k0 + k];
                    sl -= self.lower[ri + k] * d * self.upper[rj + k];
                    su -= self.lower[rj + k] * d * self.upper[ri + k];
                }
                let at = self.at(i, j);
                self.lower[at] = sl / self.diag[j];
                self.upper[at] = su / self.diag[j];
            }
            let ri = self.at(i, fi);
            let mut d = self.diag[i];
            for k in 0..(i - fi) {
                d -= self.lower[ri + k] * self.diag[fi + k] * self.upper[ri + k];
            }
            if !(d.is_finite() && d.abs() > 1e-12 * self.scale[i]) {
                return false;
            }
            self.diag[i] = d;
        }
        true
    }

    /// Solve `L D U x = r` in place.
    fn solve(&self, r: &mut [f64]) {
        let n = r.len();
        for i in 0..n {
            let fi = self.first[i];
            let ri = self.at(i, fi);
            let mut s = r[i];
            for k in 0..(i - fi) {
                s -= self.lower[ri + k] * r[fi + k];
            }
            r[i] = s;
        }
        for (x, d) in r.iter_mut().zip(&self.diag) {
            *x /= d;
        }
        for i in (0..n).rev() {
            let fi = self.first[i];
            let ri = self.at(i, fi);
            let x = r[i];
            for k in 0..(i - fi) {
                r[fi + k] -= self.upper[ri + k] * x;
            }
        }
    }
}
