//! Rigid bodies: a convex polygon with its mass and rotational inertia about its centroid,
//! its position (centroid) and rotation, and their rates, and the loads it carries
//! ([`BodyLoads`]). Fixed bodies (the ground under the supports) never move.

use crate::geometry::{cross, polygon_area_centroid, Vec2};

/// The loads a block carries, in its own frame (they move and turn with it).
///
/// The block's own weight `m0 g` acts at its centroid, as a permanent force `(0, -m0 g)` and
/// as a seismic weight. The other loads of the load case (point, line, fill) are forces `F_k`
/// at body-fixed points whose offset from the centroid is `r_k` at rotation 0, and seismic
/// weights `S_k` at the same points. Turned by `th`, a force `F` at `r` has the moment
/// `cross(R r, F) = cos(th) cross(r, F) - sin(th) dot(r, F)` about the centroid, so the
/// permanent ones reduce to their resultant and two scalars, and the (parallel) seismic ones
/// to their total weight at their centre.
#[derive(Debug, Clone, Default)]
pub(crate) struct BodyLoads {
    /// Own weight `m0 g` (N) of the block (its polygon), at the centroid.
    pub weight: f64,
    /// The other loads, `None` when the block carries none (self-weight only: the
    /// arithmetic is then exactly that of the self-weight model).
    pub extra: Option<ExtraLoads>,
    /// Force scale of the block (N) for the rest test: its own weight plus the magnitude of
    /// every other load it carries.
    pub scale: f64,
}

/// The loads of a block other than its own weight (see [`BodyLoads`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct ExtraLoads {
    /// Resultant permanent force `sum F_k` (N).
    pub force: Vec2,
    /// `sum cross(r_k, F_k)` and `-sum dot(r_k, F_k)` (N m): the moment of the permanent
    /// forces about the centroid at rotation `th` is `cos(th) a + sin(th) b`.
    pub a: f64,
    pub b: f64,
    /// Total seismic weight `sum S_k` (N) and the offset of its centre from the centroid at
    /// rotation 0.
    pub seismic_weight: f64,
    pub seismic_offset: Vec2,
    /// The forces lambda multiplies (live loads under a live action,
    /// `crate::model::Action::Live`), reduced like the permanent ones: resultant, and the
    /// two scalars of their moment.
    pub live_force: Vec2,
    pub live_a: f64,
    pub live_b: f64,
}

impl ExtraLoads {
    /// Add a permanent force `force` and a seismic weight `seismic` (N) at offset `r`.
    pub fn add(&mut self, r: Vec2, force: Vec2, seismic: f64) {
        self.force += force;
        self.a += cross(r, force);
        self.b -= r.dot(&force);
        let w = self.seismic_weight + seismic;
        if seismic > 0.0 && w > 0.0 {
            self.seismic_offset = (self.seismic_weight * self.seismic_offset + seismic * r) / w;
            self.seismic_weight = w;
        }
    }

    /// Add a force `force` at offset `r` that lambda multiplies (a live load).
    pub fn add_live(&mut self, r: Vec2, force: Vec2) {
        self.live_force += force;
        self.live_a += cross(r, force);
        self.live_b -= r.dot(&force);
    }

    /// Moment (N m) of the forces lambda multiplies, at unit lambda, about the centroid with
    /// the body turned by `(sin, cos)` of its rotation.
    #[inline]
    pub fn live_moment(&self, sin: f64, cos: f64) -> f64 {
        cos * self.live_a + sin * self.live_b
    }

    /// `sum F_k . (R r_k)` (N m) of the forces lambda multiplies, at unit lambda.
    #[inline]
    pub fn live_lever(&self, sin: f64, cos: f64) -> f64 {
        sin * self.live_a - cos * self.live_b
    }

    /// Moment (N m) of the permanent forces about the centroid with the body turned by
    /// `(sin, cos)` of its rotation.
    #[inline]
    pub fn moment(&self, sin: f64, cos: f64) -> f64 {
        cos * self.a + sin * self.b
    }

    /// `sum F_k . (R r_k)` (N m): the potential of the permanent forces is
    /// `-(F . pos + this)`.
    #[inline]
    pub fn lever(&self, sin: f64, cos: f64) -> f64 {
        sin * self.a - cos * self.b
    }
}

/// A rigid convex polygon block.
#[derive(Debug, Clone)]
pub(crate) struct Body {
    /// Vertices relative to the centroid, counter-clockwise, at rotation 0.
    pub local: Vec<Vec2>,
    /// Mass (kg); unused for fixed bodies.
    pub mass: f64,
    /// Rotational inertia about the centroid (kg m^2).
    pub inertia: f64,
    /// Distance from the centroid to the farthest vertex (m).
    pub radius: f64,
    pub fixed: bool,
    /// Centroid position and rotation (rad, counter-clockwise).
    pub pos: Vec2,
    pub angle: f64,
    pub vel: Vec2,
    pub omega: f64,
    /// World vertices and outward unit edge normals (edge k runs from vertex k to k + 1),
    /// refreshed after every move.
    pub world: Vec<Vec2>,
    pub normals: Vec<Vec2>,
    /// Outward unit edge normals at rotation 0.
    local_normals: Vec<Vec2>,
    /// Axis-aligned bounding box of `world`, as of the last [`Body::bound`]: only the contact
    /// search reads it, so it is not kept up to date every step.
    pub lo: Vec2,
    pub hi: Vec2,
    /// Index of the assembly block (None for ground bodies).
    pub block: Option<usize>,
    /// Centroid in the assembly's geometry (rotation 0 there).
    pub home: Vec2,
    /// The loads it carries (none for ground bodies).
    pub loads: BodyLoads,
}

impl Body {
    /// A body from a convex polygon (either orientation) with the given area density
    /// (mass per unit area, kg/m^2): mass and inertia are those of the uniform polygon.
    pub fn new(polygon: &[Vec2], density: f64, fixed: bool, block: Option<usize>) -> Body {
        let (area, centroid) = polygon_area_centroid(polygon);
        let mut local: Vec<Vec2> = polygon.iter().map(|p| p - centroid).collect();
        // Counter-clockwise order, so edge normals (e_y, -e_x) point outward.
        let signed: f64 = (0..local.len())
            .map(|k| cross(local[k], local[(k + 1) % local.len()]))
            .sum();
        if signed < 0.0 {
            local.reverse();
        }
        // Polar moment of a polygon about its centroid, by triangles from the centroid.
        let mut j = 0.0;
        for k in 0..local.len() {
            let a = local[k];
            let b = local[(k + 1) % local.len()];
            let w = cross(a, b);
            j += w * (a.dot(&a) + a.dot(&b) + b.dot(&b));
        }
        let mass = density * area;
        let inertia = density * j / 12.0;
        let radius = local.iter().map(|p| p.norm()).fold(0.0, f64::max);
        let local_normals = (0..local.len())
            .map(|k| {
                let e = local[(k + 1) % local.len()] - local[k];
                Vec2::new(e.y, -e.x).normalize()
            })
            .collect();
        let mut body = Body {
            world: local.clone(),
            normals: vec![Vec2::zeros(); local.len()],
            local_normals,
            local,
            mass,
            inertia,
            radius,
            fixed,
            pos: centroid,
            angle: 0.0,
            vel: Vec2::zeros(),
            omega: 0.0,
            lo: Vec2::zeros(),
            hi: Vec2::zeros(),
            block,
            home: centroid,
            loads: BodyLoads::default(),
        };
        body.refresh();
        body.bound();
        body
    }

    /// Add `mass` (kg) carried with the body (the seismic mass of the loads on it), scaling
    /// the rotational inertia in the same proportion.
    pub fn add_mass(&mut self, mass: f64) {
        if mass > 0.0 && self.mass > 0.0 {
            let total = self.mass + mass;
            self.inertia *= total / self.mass;
            self.mass = total;
        }
    }

    /// Recompute world vertices and normals from the position and rotation (every step; the
    /// bounding box waits for [`Body::bound`]).
    pub fn refresh(&mut self) {
        let (s, c) = self.angle.sin_cos();
        let rot = |l: &Vec2| Vec2::new(c * l.x - s * l.y, s * l.x + c * l.y);
        for (w, l) in self.world.iter_mut().zip(&self.local) {
            *w = self.pos + rot(l);
        }
        for (n, l) in self.normals.iter_mut().zip(&self.local_normals) {
            *n = rot(l);
        }
    }

    /// Recompute the bounding box from the world vertices (before a broad phase or a
    /// contact search, the only readers of it).
    pub fn bound(&mut self) {
        let mut lo = Vec2::repeat(f64::INFINITY);
        let mut hi = Vec2::repeat(f64::NEG_INFINITY);
        for w in &self.world {
            lo = lo.inf(w);
            hi = hi.sup(w);
        }
        self.lo = lo;
        self.hi = hi;
    }

    /// Velocity of the material point at world position `p`.
    #[inline]
    pub fn point_velocity(&self, p: Vec2) -> Vec2 {
        let r = p - self.pos;
        self.vel + self.omega * Vec2::new(-r.y, r.x)
    }

    /// Where the body-fixed point that was at `p0` in the assembly's geometry is now.
    pub fn carry(&self, p0: Vec2) -> Vec2 {
        self.pos + self.rotate(p0 - self.home)
    }

    /// A vector of the assembly's geometry turned with the body.
    pub fn rotate(&self, r: Vec2) -> Vec2 {
        let (s, c) = self.angle.sin_cos();
        Vec2::new(c * r.x - s * r.y, s * r.x + c * r.y)
    }

    /// Kinetic energy (J).
    pub fn kinetic_energy(&self) -> f64 {
        if self.fixed {
            0.0
        } else {
            0.5 * (self.mass * self.vel.norm_squared() + self.inertia * self.omega * self.omega)
        }
    }
}
