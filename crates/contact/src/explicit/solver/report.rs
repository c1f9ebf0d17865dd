//! Results: the [`Equilibrium`] of the current state (from the last evaluation's totals or a pass
//! over the members) and the contact state of a prescribed pose.

use nalgebra::Matrix3;

use super::ExplicitSolver;
use super::geometry::State;
use super::pass::evaluate;
use crate::explicit::laws::Resp;
use crate::explicit::types::*;

impl ExplicitSolver {
    /// Contact state for a prescribed pose, without equilibrium: every summit with interference
    /// `z >= z_in` (the approach rule; Hertz/DMT: z > 0 counts, z = 0 carries no area) is in
    /// contact. `load_n` of the result is the total contact force sum P_i (the load this pose
    /// needs), the force residual is 0. Used to compare with GW's integrals at fixed separation.
    pub fn evaluate_pose(&mut self, separation_m: f64, tilt_x_rad: f64, tilt_y_rad: f64) -> Equilibrium {
        let saved = self.state.clone();
        let saved_solid = std::mem::take(&mut self.solid);
        self.solid = vec![0; saved_solid.len()];
        self.state.member.iter_mut().for_each(|w| *w = 0);
        self.state.members = 0;
        self.state.bound = 0;
        // Pose -> q: solve the basis for the plane (A, B, C) with w(x0, y0) = separation.
        let (x0, y0) = self.geom.load_point;
        let a = separation_m - tilt_x_rad * x0 - tilt_y_rad * y0;
        self.state.q = self.q_from_plane(a, tilt_x_rad, tilt_y_rad);
        let mut touch = std::mem::take(&mut self.scratch);
        self.with_law(|g, law| {
            let _ = evaluate(g, law, &State { ..self.state.clone() }, &self.state.q, 0.0, true, false, &mut touch);
        });
        for &i in &touch {
            self.state.set(i as usize);
        }
        self.scratch = touch;
        let mut eq = self.report(0.0, 0);
        eq.load_n -= eq.force_residual_n;
        eq.force_residual_n = 0.0;
        self.state = saved;
        self.solid = saved_solid;
        eq
    }

    fn q_from_plane(&self, a: f64, b: f64, c: f64) -> [f64; 3] {
        // Least squares is not needed: the bases are invertible on their span.
        let g = &self.geom;
        match g.ndof {
            1 => [a + b * g.load_point.0 + c * g.load_point.1, 0.0, 0.0],
            _ => {
                // Solve M q = (a, b, c) for the used columns (tilt basis: exact).
                let m = Matrix3::new(
                    g.basis[0][0],
                    g.basis[1][0],
                    g.basis[2][0],
                    g.basis[0][1],
                    g.basis[1][1],
                    g.basis[2][1],
                    g.basis[0][2],
                    g.basis[1][2],
                    g.basis[2][2],
                );
                let sol = m.pseudo_inverse(1e-30).map(|p| p * nalgebra::Vector3::new(a, b, c));
                match sol {
                    Ok(v) => [v[0], v[1], v[2]],
                    Err(_) => [a, 0.0, 0.0],
                }
            }
        }
    }

    /// Builds the result for the current state (members are the contacts).
    pub(super) fn report(&self, load_n: f64, iterations: usize) -> Equilibrium {
        let q = self.state.q;
        let g = &self.geom;
        let (a, b, c) = g.plane(&q);
        let (x0, y0) = g.load_point;
        let detail = self.config.detail;
        let hardness = self.config.hardness_pa;
        let mut e = Equilibrium {
            load_n,
            separation_m: a + b * x0 + c * y0,
            tilt_x_rad: b,
            tilt_y_rad: c,
            load_point_x_m: x0,
            load_point_y_m: y0,
            contacts: self.state.members,
            contact_indices: Vec::new(),
            real_area_m2: 0.0,
            elastic_load_n: 0.0,
            adhesive_load_n: 0.0,
            capillary_load_n: 0.0,
            wetted_summits: 0,
            friction_capacity_n: 0.0,
            max_pressure_pa: 0.0,
            summits_over_elastic_limit: 0,
            force_residual_n: load_n,
            moment_residual_x_n_m: 0.0,
            moment_residual_y_n_m: 0.0,
            iterations,
            summits: Vec::new(),
        };
        if detail == Detail::Summary
            && let Some((generation, cq, ev)) = &self.state.cache
            && (self.wet.is_none() || !ev.released)
            && *generation == self.state.generation
            && *cq == q
        {
            // The last evaluation of the solve holds every total: no second pass.
            e.real_area_m2 = ev.area;
            e.elastic_load_n = ev.elastic;
            e.max_pressure_pa = ev.q0_max;
            e.summits_over_elastic_limit = ev.over_limit;
            e.moment_residual_x_n_m = ev.moment_x;
            e.moment_residual_y_n_m = ev.moment_y;
            e.force_residual_n = load_n - ev.force;
            e.adhesive_load_n = e.elastic_load_n - ev.force;
            e.friction_capacity_n = self.config.shear_strength_pa * e.real_area_m2;
            if self.wet.is_some() {
                e.capillary_load_n = ev.capillary;
                e.wetted_summits = e.contacts;
                e.contacts = ev.solid;
            }
            return e;
        }
        let mut total = 0.0;
        let (mut capillary, mut solid) = (0.0, 0usize);
        self.with_law(|g, law| {
            for i in 0..self.state.bound {
                if !self.state.is_member(i) {
                    continue;
                }
                let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
                let z = g.hs[i] - (a + b * x + c * y);
                let r: Resp = law.contact(i, z);
                if self.wet.is_some() {
                    capillary += law.capillary_n(i, z);
                    solid += usize::from(r.radius > 0.0);
                }
                total += r.load_n;
                e.real_area_m2 += std::f64::consts::PI * r.radius * r.radius;
                e.elastic_load_n += r.elastic_n;
                e.moment_residual_x_n_m += r.load_n * (x - x0);
                e.moment_residual_y_n_m += r.load_n * (y - y0);
                e.max_pressure_pa = e.max_pressure_pa.max(r.q0);
                let over = hardness.is_some_and(|h| r.q0 > h);
                e.summits_over_elastic_limit += usize::from(over);
                if detail != Detail::Summary {
                    e.contact_indices.push(g.original_index(i));
                }
                if detail == Detail::Full {
                    e.summits.push(SummitContact {
                        index: g.original_index(i),
                        x_m: x,
                        y_m: y,
                        height_m: g.hs[i],
                        radius_m: g.radius(i),
                        interference_m: z,
                        load_n: r.load_n,
                        contact_radius_m: r.radius,
                        max_pressure_pa: r.q0,
                        over_elastic_limit: over,
                    });
                }
            }
        });
        e.contact_indices.sort_unstable();
        e.summits.sort_unstable_by_key(|s| s.index);
        e.force_residual_n = load_n - total;
        e.adhesive_load_n = e.elastic_load_n - total;
        if self.wet.is_some() {
            e.capillary_load_n = capillary;
            e.wetted_summits = e.contacts;
            e.contacts = solid;
        }
        e.friction_capacity_n = self.config.shear_strength_pa * e.real_area_m2;
        e
    }
}
