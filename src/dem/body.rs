//! Rigid bodies: a convex polygon with its mass and rotational inertia about its centroid,
//! its position (centroid) and rotation, and their rates. Fixed bodies (the ground under the
//! supports) never move.

use crate::geometry::{cross, polygon_area_centroid, Vec2};

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
    /// Axis-aligned bounding box of `world`.
    pub lo: Vec2,
    pub hi: Vec2,
    /// Index of the assembly block (None for ground bodies).
    pub block: Option<usize>,
    /// Centroid in the assembly's geometry (rotation 0 there).
    pub home: Vec2,
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
        };
        body.refresh();
        body
    }

    /// Recompute world vertices, normals and bounding box from the position and rotation.
    pub fn refresh(&mut self) {
        let (s, c) = self.angle.sin_cos();
        let rot = |l: &Vec2| Vec2::new(c * l.x - s * l.y, s * l.x + c * l.y);
        let mut lo = Vec2::repeat(f64::INFINITY);
        let mut hi = Vec2::repeat(f64::NEG_INFINITY);
        for (w, l) in self.world.iter_mut().zip(&self.local) {
            *w = self.pos + rot(l);
            lo = lo.inf(w);
            hi = hi.sup(w);
        }
        for (n, l) in self.normals.iter_mut().zip(&self.local_normals) {
            *n = rot(l);
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
