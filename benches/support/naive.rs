//! The textbook grating formula as a renderer would write it, in `f32` and `f64`: the baseline
//! of the BRDF benchmark and of the accuracy report (one copy for both).

#![allow(dead_code)] // each user takes the precisions it needs

use diffraction::kernel::naive;
use glam::{DVec3, Vec3};

/// S(β)·F_N(α) by the naive formulas in `f32`, at u = wi.x + wo.x (0 below the surface).
#[inline]
pub fn naive_f32(d: f32, w: f32, n: u32, wi: Vec3, wo: Vec3, lambda: f32) -> f32 {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    let k = std::f32::consts::PI * (wi.x + wo.x) / lambda;
    naive::single_slit(k * w) * naive::n_slit(k * d, n)
}

/// The same in `f64`.
#[inline]
pub fn naive_f64(d: f64, w: f64, n: u32, wi: DVec3, wo: DVec3, lambda: f64) -> f64 {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    let k = std::f64::consts::PI * (wi.x + wo.x) / lambda;
    naive::single_slit(k * w) * naive::n_slit(k * d, n)
}
