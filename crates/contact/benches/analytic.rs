//! Benchmarks of the analytic contact models: F_n evaluation, GW solves, summit responses.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use stiction_contact::gw::{GwModel, GwSurface, ln_f_n};
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch, SummitModel, summit_response};

fn bench_f_n(c: &mut Criterion) {
    for (name, n, h) in [
        ("ln_f_n n=0 h=1.3", 0.0, 1.3),
        ("ln_f_n n=1 h=1.3", 1.0, 1.3),
        ("ln_f_n n=1.5 h=1.3", 1.5, 1.3),
        ("ln_f_n n=1.5 h=-4", 1.5, -4.0),
        ("ln_f_n n=1.5 h=190", 1.5, 190.0),
        ("ln_f_n n=1.5 h=7.7", 1.5, 7.7),
        ("ln_f_n n=0.5 h=1.3", 0.5, 1.3),
        // The same orders a hair off 1/2, 3/2 take the general quadrature (the method F_3/2 used
        // before the Taylor tables, issue 16): the speed-up is the ratio of these to the above.
        ("quadrature ln_f_n n=1.5+1e-12 h=1.3", 1.5 + 1e-12, 1.3),
        ("quadrature ln_f_n n=1.5+1e-12 h=-4", 1.5 + 1e-12, -4.0),
        ("quadrature ln_f_n n=1.5+1e-12 h=7.7", 1.5 + 1e-12, 7.7),
    ] {
        c.bench_function(name, |b| b.iter(|| ln_f_n(black_box(n), black_box(h)).unwrap()));
    }
}

fn bench_gw(c: &mut Criterion) {
    let plain = GwModel::new(None).unwrap();
    c.bench_function("gw solve theta=inf L*=0.01", |b| b.iter(|| plain.solve(black_box(0.01)).unwrap()));
    let adh = GwModel::new(Some(15.0)).unwrap();
    c.bench_function("gw solve theta=15 L*=0.01", |b| b.iter(|| adh.solve(black_box(0.01)).unwrap()));
    c.bench_function("gw model new theta=12432 (pull-off)", |b| {
        b.iter(|| GwModel::new(Some(black_box(12432.0))).unwrap())
    });
}

fn bench_summit(c: &mut Criterion) {
    let p = AsperityParams::table1();
    let z = 1.3e-9;
    c.bench_function("summit_response dmt", |b| {
        b.iter(|| summit_response(AdhesionLaw::Dmt, black_box(&p), black_box(z), Branch::Loading))
    });
    c.bench_function("summit_response jkr", |b| {
        b.iter(|| summit_response(AdhesionLaw::Jkr, black_box(&p), black_box(z), Branch::Loading))
    });
    let md = SummitModel::new(AdhesionLaw::MaugisDugdale, p).unwrap();
    c.bench_function("SummitModel::response maugis-dugdale (table)", |b| {
        b.iter(|| md.response(black_box(z), Branch::Loading))
    });
    c.bench_function("summit_response maugis-dugdale (no table)", |b| {
        b.iter(|| summit_response(AdhesionLaw::MaugisDugdale, black_box(&p), black_box(z), Branch::Loading))
    });
    c.bench_function("SummitModel::new maugis-dugdale", |b| {
        b.iter(|| SummitModel::new(AdhesionLaw::MaugisDugdale, black_box(p)).unwrap())
    });
}

fn bench_gw_capillary(c: &mut Criterion) {
    use stiction_contact::capillary::{Capillarity, Liquid};
    let s = GwSurface::table1();
    let cap = Capillarity::new(Liquid::water(298.15), 298.15, 0.35, 0.0, 0.0).unwrap().unwrap();
    c.bench_function("gw surface solve_load 3 uN (dry)", |b| b.iter(|| s.solve_load(black_box(3e-6), true).unwrap()));
    c.bench_function("gw surface solve_load_wet 3 uN (35 % RH)", |b| {
        b.iter(|| s.solve_load_wet(black_box(3e-6), true, Some(&cap)).unwrap())
    });
    c.bench_function("gw capillary_load_n h=2.5", |b| b.iter(|| s.capillary_load_n(&cap, black_box(2.5)).unwrap()));
}

criterion_group!(benches, bench_f_n, bench_gw, bench_summit, bench_gw_capillary);
criterion_main!(benches);
