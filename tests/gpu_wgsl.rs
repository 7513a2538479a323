//! The WGSL sources of `diffraction::gpu`: every module parses and validates (naga, no device),
//! the WGSL structs have the sizes and offsets of their Rust twins, and the kernels' algorithm,
//! emulated in Rust f32 with every operation the WGSL spec leaves free pushed to its worst
//! case, stays inside the bound derived in docs/gpu.md. The reference values are the crate's
//! f64 kernels (tested against 100-digit mpmath in tests/kernel_reference.rs, 1e-12).
#![cfg(feature = "gpu")]

#[path = "support/gpu_cases.rs"]
mod gpu_cases;
#[path = "support/gpu_tolerance.rs"]
mod gpu_tolerance;
#[cfg(feature = "presets")]
#[path = "support/tensor_cd.rs"]
mod tensor_cd;

use diffraction::gpu::{
    bsdf_bindings, color_table_bindings, efficiency_table_bindings, incidence_bindings,
    shading_source, GpuBsdf, GpuGrating, GpuIllumination, GpuTableBlock, GpuTableHeader,
    GpuTableNode, BSDF_WGSL, COLOR_TABLE_WGSL, INCIDENCE_WGSL, KERNEL_WGSL, SHADING_WGSL,
    TABULATED_WGSL, TYPES_WGSL,
};
use diffraction::kernel::{n_slit_cycles, single_slit_cycles};
use gpu_cases::{stiff_phases, ulps, Mix, SLITS};
use gpu_tolerance::*;

fn validate(name: &str, source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

#[test]
fn every_module_validates() {
    validate("KERNEL_WGSL", KERNEL_WGSL);
    validate("TYPES_WGSL", TYPES_WGSL);
    let table = [TYPES_WGSL, &color_table_bindings(0, 0), COLOR_TABLE_WGSL].join("\n");
    validate("COLOR_TABLE_WGSL", &table);
    validate(
        "INCIDENCE_WGSL",
        &[&table, &incidence_bindings(0, 3), INCIDENCE_WGSL].join("\n"),
    );
    let shading = [
        TYPES_WGSL,
        &color_table_bindings(3, 4),
        COLOR_TABLE_WGSL,
        SHADING_WGSL,
    ]
    .join("\n");
    validate("SHADING_WGSL", &shading);
    validate(
        "BSDF_WGSL",
        &[TYPES_WGSL, KERNEL_WGSL, &bsdf_bindings(0, 0), BSDF_WGSL].join("\n"),
    );
    validate(
        "TABULATED_WGSL",
        &[
            TYPES_WGSL,
            KERNEL_WGSL,
            &bsdf_bindings(0, 0),
            BSDF_WGSL,
            &efficiency_table_bindings(0, 1),
            TABULATED_WGSL,
        ]
        .join("\n"),
    );
    let all = validate("shading_source", &shading_source(1, 0));
    for f in [
        "diffraction_n_slit_cycles",
        "diffraction_single_slit_cycles",
        "diffraction_intensity_cycles",
        "diffraction_table_lookup",
        "diffraction_table_colour",
        "diffraction_shade",
        "diffraction_shade_grating",
        "diffraction_bsdf_f",
        "diffraction_bsdf_pdf",
        "diffraction_bsdf_sample",
        "diffraction_bsdf_tabulated_f",
        "diffraction_bsdf_tabulated_pdf",
        "diffraction_bsdf_tabulated_sample",
        "diffraction_eta",
    ] {
        assert!(
            all.functions
                .iter()
                .any(|(_, g)| g.name.as_deref() == Some(f)),
            "{f} missing"
        );
    }
    // The sampler's defensive share is the CPU's.
    #[cfg(feature = "relief")]
    {
        let share = diffraction::grating_bsdf::TABULATED_DEFENSIVE_SHARE;
        let line = format!("const DIFFRACTION_DEFENSIVE_SHARE: f32 = {share:?};");
        assert!(TABULATED_WGSL.contains(&line), "{line}");
    }
}

/// (size, member offsets) of the WGSL struct `name`.
fn wgsl_layout(module: &naga::Module, name: &str) -> (usize, Vec<(String, usize)>) {
    let ty = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name}"))
        .1;
    match &ty.inner {
        naga::TypeInner::Struct { members, span } => (
            *span as usize,
            members
                .iter()
                .map(|m| (m.name.clone().unwrap(), m.offset as usize))
                .collect(),
        ),
        other => panic!("{name} is {other:?}"),
    }
}

#[test]
fn structs_match_their_rust_twins() {
    use core::mem::{offset_of, size_of};
    let module = validate("TYPES_WGSL", TYPES_WGSL);
    let check = |name: &str, size: usize, offsets: &[(&str, usize)]| {
        let (wsize, woffsets) = wgsl_layout(&module, name);
        assert_eq!(wsize, size, "{name}: size");
        let want: Vec<(String, usize)> = offsets.iter().map(|(n, o)| (n.to_string(), *o)).collect();
        assert_eq!(woffsets, want, "{name}: members");
    };
    check(
        "DiffractionGrating",
        size_of::<GpuGrating>(),
        &[
            ("period_nm", offset_of!(GpuGrating, period_nm)),
            ("slit_width_nm", offset_of!(GpuGrating, slit_width_nm)),
            ("slits", offset_of!(GpuGrating, slits)),
            ("pad", offset_of!(GpuGrating, pad)),
        ],
    );
    check(
        "DiffractionIllumination",
        size_of::<GpuIllumination>(),
        &[
            ("ambient", offset_of!(GpuIllumination, ambient)),
            ("diffuse", offset_of!(GpuIllumination, diffuse)),
            ("diffraction", offset_of!(GpuIllumination, diffraction)),
            ("pad", offset_of!(GpuIllumination, pad)),
        ],
    );
    check(
        "DiffractionTableHeader",
        size_of::<GpuTableHeader>(),
        &[
            ("u_lo", offset_of!(GpuTableHeader, u_lo)),
            ("base_key", offset_of!(GpuTableHeader, base_key)),
            ("block_count", offset_of!(GpuTableHeader, block_count)),
            ("node_count", offset_of!(GpuTableHeader, node_count)),
        ],
    );
    check(
        "DiffractionTableBlock",
        size_of::<GpuTableBlock>(),
        &[
            ("u0", offset_of!(GpuTableBlock, u0)),
            ("h", offset_of!(GpuTableBlock, h)),
            ("inv_h", offset_of!(GpuTableBlock, inv_h)),
            ("first", offset_of!(GpuTableBlock, first)),
            ("n", offset_of!(GpuTableBlock, n)),
        ],
    );
    check(
        "DiffractionBsdf",
        size_of::<GpuBsdf>(),
        &[
            ("period_nm", offset_of!(GpuBsdf, period_nm)),
            ("slit_width_nm", offset_of!(GpuBsdf, slit_width_nm)),
            ("slits", offset_of!(GpuBsdf, slits)),
            ("groove", offset_of!(GpuBsdf, groove)),
            ("groove_param", offset_of!(GpuBsdf, groove_param)),
            ("scale", offset_of!(GpuBsdf, scale)),
            ("atan_n", offset_of!(GpuBsdf, atan_n)),
            ("rho", offset_of!(GpuBsdf, rho)),
            ("first_row", offset_of!(GpuBsdf, first_row)),
            ("table", offset_of!(GpuBsdf, table)),
            ("pad0", offset_of!(GpuBsdf, pad)),
            ("pad1", offset_of!(GpuBsdf, pad) + 4),
        ],
    );
    check(
        "DiffractionTableNode",
        size_of::<GpuTableNode>(),
        &[
            ("f", offset_of!(GpuTableNode, f)),
            ("d", offset_of!(GpuTableNode, d)),
        ],
    );
}

#[test]
fn the_bsdf_upload_matches_the_model() {
    use diffraction::{Grating, GratingBsdf};
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000).unwrap());
    let g = GpuBsdf::new(&b, 130);
    assert_eq!(g.to_bytes().len(), core::mem::size_of::<GpuBsdf>());
    assert_eq!(
        (g.first_row, g.groove, g.groove_param),
        (130, 0, 1000.0 * 1600.0)
    );
    let rows = GpuBsdf::order_rows(&b);
    // ρ = ½: order 0's weight is S(0) = 1 plus the defensive share 0.125·U_0 = 0.125.
    assert_eq!(rows[0][0], 1.125);
    // η_2 = 0 (S(π) = 0) leaves only the defensive share 0.125·3/(3 + (1.5·π/2)²); the second
    // column sums the weights of orders 1..=k.
    let a = 1.5 * core::f64::consts::PI * 0.5;
    let share = 0.125 * 3.0 / (3.0 + a * a);
    assert!((rows[2][0] as f64 - share).abs() <= ORDER_ROW_F32 * share);
    let sum: f64 = rows[1..=64].iter().map(|r| r[0] as f64).sum();
    assert!((rows[64][1] as f64 - sum).abs() < ORDER_ROW_SUM_F32 * sum);
    let ideal = GratingBsdf::new(Grating::infinite(1600.0, 800.0).unwrap());
    assert_eq!(GpuBsdf::new(&ideal, 0).groove, 2); // delta lobes: f = pdf = 0
}

/// The packed efficiency table (src/gpu/tabulated.rs): the header, the nodes, and per order and
/// node q = η·cos θi/cos θm (η the table's value at the node) or −1 where the order does not
/// propagate (cos² θm ≤ 10⁻⁶), then each node's η for the sampler's proposal, for every preset; a second table follows the first at the
/// offset `push` returns, and a tabulated `GpuBsdf` carries the unit lobe's constants.
#[cfg(feature = "presets")]
#[test]
fn the_efficiency_tables_pack_as_documented() {
    use diffraction::gpu::{pack_efficiency_table, GpuEfficiencyTables, NO_TABLE};
    use diffraction::relief::Preset;
    use diffraction::GratingBsdf;
    let mut all = GpuEfficiencyTables::default();
    let (mut grazing, mut values) = (0usize, 0usize);
    for p in Preset::ALL {
        let t = p.table();
        let w = pack_efficiency_table(t).unwrap();
        let at = all.push(t).unwrap() as usize;
        assert_eq!(&all.words()[at..at + w.len()], &w[..]);
        let sin: Vec<f64> = t.sin_theta_i().collect();
        let lam: Vec<f64> = t.lambda_nm().collect();
        let (n_s, n_l, k) = (sin.len(), lam.len(), t.order_count());
        let v = 10 + n_s + n_l;
        assert_eq!(
            &w[..10],
            &[
                t.period_nm() as f32,
                n_s as f32,
                n_l as f32,
                *t.orders().start() as f32,
                k as f32,
                v as f32,
                (v + 3 * k * n_l * n_s) as f32,
                (v + 2 * k * n_l * n_s) as f32,
                0.0,
                0.0
            ]
        );
        let cells = (n_s - 1) * (n_l - 1);
        assert_eq!(w.len(), v + 3 * k * n_l * n_s + cells);
        let eta_plane = v + 2 * k * n_l * n_s;
        // The cells' marks: 0 or 1, and where 1 no query in the cell sums above 1 (the sums the
        // CPU's normalisation would scale; corners, edges and inside).
        let marks = &w[v + 3 * k * n_l * n_s..];
        let mut out = vec![diffraction::relief::Polarised::default(); k];
        let mut marked = 0;
        for (c, &mark) in marks.iter().enumerate() {
            assert!(mark == 0.0 || mark == 1.0, "{p:?} cell {c}: {mark}");
            if mark == 0.0 {
                continue;
            }
            marked += 1;
            let (i, j) = (c % (n_s - 1), c / (n_s - 1));
            for q in 0..25 {
                let (a, b) = ((q % 5) as f64 / 4.0, (q / 5) as f64 / 4.0);
                let s = sin[i] + (sin[i + 1] - sin[i]) * a;
                let l = lam[j] + (lam[j + 1] - lam[j]) * b;
                t.efficiencies(s, l, &mut out);
                let (st, sm) = out
                    .iter()
                    .fold((0.0, 0.0), |(x, y), e| (x + e.te, y + e.tm));
                // A sum the normalisation scaled would be 1 to rounding: a marked cell's stay at
                // most the marks' 1 − 10⁻⁹.
                let most = 1.0 - 1e-9;
                assert!(
                    st <= most && sm <= most,
                    "{p:?} cell {c}, s = {s}, λ = {l}: {st} {sm}"
                );
            }
        }
        assert!(
            marked > 0 || p == Preset::Blazed600,
            "{p:?}: no cell marked"
        );
        for (i, &s) in sin.iter().enumerate() {
            assert_eq!(w[10 + i] as f64, s);
        }
        for (j, &l) in lam.iter().enumerate() {
            assert_eq!(w[10 + n_s + j] as f64, l);
        }
        for (o, m) in t.orders().enumerate() {
            for (j, &l) in lam.iter().enumerate() {
                for (i, &s) in sin.iter().enumerate() {
                    let at = v + 2 * ((o * n_l + j) * n_s + i);
                    let sm = s + m as f64 * l / t.period_nm();
                    let cm2 = 1.0 - sm * sm;
                    if cm2 <= 1e-6 {
                        assert_eq!((w[at], w[at + 1]), (-1.0, -1.0));
                        grazing += 1;
                        continue;
                    }
                    let e = t.efficiency(m, s, l);
                    let g = (1.0 - s * s).sqrt() / cm2.sqrt();
                    for (q, want) in [(w[at], e.te * g), (w[at + 1], e.tm * g)] {
                        assert!(
                            (q as f64 - want).abs() <= ORDER_ROW_F32 * want,
                            "{p:?} m={m} s={s} λ={l}: {q} vs {want}"
                        );
                    }
                    // The proposal's node efficiency: the table's own value at the node (the
                    // presets' node sums stay below 1, so no normalisation).
                    let node = w[eta_plane + (o * n_l + j) * n_s + i] as f64;
                    let want = e.unpolarised();
                    assert!(
                        (node - want).abs() <= ORDER_ROW_F32 * want,
                        "{p:?} m={m} s={s} λ={l}: node {node} vs {want}"
                    );
                    values += 1;
                }
            }
        }
    }
    assert!(grazing > 100 && values > 1000, "{grazing} {values}");
    let amplitude = GpuBsdf::new(
        &GratingBsdf::new(diffraction::Grating::new(1600.0, 800.0, 34).unwrap()),
        0,
    );
    assert_eq!(amplitude.table, NO_TABLE);
    let cd = GratingBsdf::preset(Preset::Cd, 34).unwrap();
    let g = GpuBsdf::new(&cd, 0).with_table(77);
    assert_eq!(
        (g.table, g.slit_width_nm, g.scale),
        (77, 0.0, (34.0 * 1600.0) as f32)
    );
}

/// A table whose packed words would pass 2²⁴ (where their offsets stop being exact in f32) is
/// refused by `pack_efficiency_table` and `GpuEfficiencyTables::push` with an error naming
/// `table`, the count its value, and the buffer is left as it was.
#[cfg(feature = "relief")]
#[test]
fn a_table_too_large_to_pack_is_refused() {
    use diffraction::gpu::{pack_efficiency_table, GpuEfficiencyTables, MAX_PACKED_TABLE_WORDS};
    use diffraction::relief::EfficiencyTable;
    let (n_s, n_l) = (4096, 1100);
    let s: Vec<f64> = (0..n_s)
        .map(|i| -0.99 + 1.98 * i as f64 / (n_s - 1) as f64)
        .collect();
    let l: Vec<f64> = (0..n_l).map(|j| 360.0 + 0.4 * j as f64).collect();
    let big =
        EfficiencyTable::new(1000.0, 0, s, l, vec![0.1; n_s * n_l], vec![0.1; n_s * n_l]).unwrap();
    let words = 10 + n_s + n_l + 3 * n_s * n_l + (n_s - 1) * (n_l - 1);
    assert!(words > MAX_PACKED_TABLE_WORDS);
    let e = pack_efficiency_table(&big).unwrap_err();
    assert_eq!((e.parameter(), e.value()), ("table", words as f64));
    assert!(e.to_string().contains("MAX_PACKED_TABLE_WORDS"), "{e}");
    let small = EfficiencyTable::new(
        1000.0,
        0,
        vec![-0.5, 0.5],
        vec![400.0, 700.0],
        vec![0.5; 4],
        vec![0.5; 4],
    )
    .unwrap();
    let mut tables = GpuEfficiencyTables::default();
    assert_eq!(tables.push(&small).unwrap(), 0);
    let before = tables.words().to_vec();
    assert_eq!(tables.push(&big).unwrap_err().parameter(), "table");
    assert_eq!(tables.words(), &before[..]);
}

/// A reduced conical table (the presets' `conical_table`, what `GratingBsdf::preset` reads)
/// packs its first plane as a classical table, then its own section (src/gpu/tabulated.rs):
/// the planes' |β| and c, their rows and wavelength nodes, per order and node
/// q = η·cos θi/cos θm at the node's conical incidence (α = s′·c_p, β_p, its wavelength) or −1
/// where the order does not propagate (cos² θm ≤ 10⁻⁶), the nodes' unpolarised η, and a 0/1 mark
/// per reduced cell. The node values are the plane's own reading at the node
/// (`plane_efficiencies`, which is the stored values where their sum stays below 1).
#[cfg(feature = "presets")]
#[test]
fn conical_tables_pack_as_documented() {
    use diffraction::gpu::pack_efficiency_table;
    use diffraction::relief::{Polarised, Preset};
    let tensor = tensor_cd::tensor_cd();
    for (p, t) in [
        ("Cd", Preset::Cd.conical_table()),
        ("Foil", Preset::Foil.conical_table()),
        ("the CD's version-2 tensor grid", &tensor),
    ] {
        let reduced = t.is_reduced();
        let w = pack_efficiency_table(t).unwrap();
        let word = |i: usize| w[i] as f64;
        let sin: Vec<f64> = t.sin_theta_i().collect();
        let bet: Vec<f64> = t.abs_beta().collect();
        let (n_s, n_b, k) = (sin.len(), bet.len(), t.order_count());
        assert_eq!(word(8) as usize, n_b, "{p}");
        let r = word(9) as usize;
        let (q, e, m) = (word(r) as usize, word(r + 1) as usize, word(r + 2) as usize);
        let band = t.lambda_range_nm();
        assert_eq!(
            (word(r + 3), word(r + 4)),
            (band.0 as f32 as f64, band.1 as f32 as f64)
        );
        let planes: Vec<Vec<f64>> = (0..n_b).map(|b| t.plane_lambda_nm(b).collect()).collect();
        let rows: usize = planes.iter().map(Vec::len).sum();
        // A reduced table is format 0, a tensor grid 1.
        assert_eq!(word(r + 5), if reduced { 0.0 } else { 1.0 });
        let (bn, cn, rn, ln) = (r + 6, r + 6 + n_b, r + 6 + 2 * n_b, r + 7 + 3 * n_b);
        assert_eq!(q, ln + rows);
        assert_eq!(e, q + 2 * k * rows * n_s);
        assert_eq!(m, e + k * rows * n_s);
        let mut first = 0;
        for (b, nodes) in planes.iter().enumerate() {
            assert_eq!(word(bn + b), bet[b] as f32 as f64);
            assert_eq!(word(cn + b), (1.0 - bet[b] * bet[b]).sqrt() as f32 as f64);
            assert_eq!(word(rn + b) as usize, first);
            for (j, &l) in nodes.iter().enumerate() {
                assert_eq!(word(ln + first + j), l as f32 as f64);
            }
            first += nodes.len();
        }
        assert_eq!(word(rn + n_b) as usize, rows);
        // The cells: (n_s − 1)·(n_p + n_p+1 − 3) per slab between planes p and p + 1 of a
        // reduced table, (n_s − 1)·(n_λ − 1) of a tensor grid.
        let cells: usize = planes
            .windows(2)
            .map(|x| {
                if reduced {
                    (n_s - 1) * (x[0].len() + x[1].len() - 3)
                } else {
                    (n_s - 1) * (x[0].len() - 1)
                }
            })
            .sum();
        assert_eq!(w.len(), m + cells, "{p}");
        let marked = w[m..].iter().filter(|&&x| x == 1.0).count();
        assert!(w[m..].iter().all(|&x| x == 0.0 || x == 1.0));
        assert!(marked > 0, "{p}: no cell marked");
        let d = t.period_nm();
        let mut out = vec![Polarised::default(); k];
        let (mut grazing, mut values) = (0usize, 0usize);
        let mut row = 0;
        for (b, nodes) in planes.iter().enumerate() {
            let cp = (1.0 - bet[b] * bet[b]).sqrt();
            for &l in nodes {
                for (i, &sn) in sin.iter().enumerate() {
                    if reduced {
                        t.plane_efficiencies(b, sn, l, &mut out);
                    } else {
                        t.efficiencies_conical(sn * cp, bet[b], l, &mut out);
                    }
                    for (o, order) in t.orders().enumerate() {
                        let at = (o * rows + row) * n_s + i;
                        let am = sn * cp + order as f64 * l / d;
                        let cm2 = 1.0 - am * am - bet[b] * bet[b];
                        if cm2 <= 1e-6 {
                            assert_eq!((w[q + 2 * at], w[q + 2 * at + 1]), (-1.0, -1.0));
                            grazing += 1;
                            continue;
                        }
                        let g = cp * (1.0 - sn * sn).sqrt() / cm2.sqrt();
                        let x = out[o];
                        for (got, want) in
                            [(w[q + 2 * at], x.te * g), (w[q + 2 * at + 1], x.tm * g)]
                        {
                            assert!(
                                (got as f64 - want).abs() <= ORDER_ROW_F32 * want + 1e-12,
                                "{p} plane {b} m={order} s′={sn} λ={l}: {got} vs {want}"
                            );
                        }
                        let node = w[e + at] as f64;
                        let want = x.unpolarised();
                        assert!(
                            (node - want).abs() <= ORDER_ROW_F32 * want + 1e-12,
                            "{p} plane {b} m={order} s′={sn} λ={l}: node {node} vs {want}"
                        );
                        values += 1;
                    }
                }
                row += 1;
            }
        }
        assert!(grazing > 100 && values > 10_000, "{p}: {grazing} {values}");
        println!(
            "{p}'s conical table: {} words ({r} before its section), {marked} of {cells} cells \
             marked",
            w.len()
        );
    }
}

/// The freedoms the WGSL spec leaves an implementation in the kernels, each pushed one way:
/// a division's result `div` ulps off the correctly rounded one (|div| ≤ 2: within 2.5 ulp), an
/// inexact integer-to-float conversion `conv` ulps off (|conv| ≤ 1), Horner steps fused or not.
#[derive(Clone, Copy)]
struct Freedom {
    div: i32,
    conv: i32,
    fused: bool,
}

impl Freedom {
    fn all() -> Vec<Freedom> {
        let mut out = Vec::new();
        for div in [-2, 0, 2] {
            for conv in [-1, 0, 1] {
                for fused in [false, true] {
                    out.push(Freedom { div, conv, fused });
                }
            }
        }
        out
    }
    fn div(&self, a: f32, b: f32) -> f32 {
        ulps(a / b, self.div)
    }
    fn conv(&self, v: u32) -> f32 {
        let f = v as f32;
        if f as f64 == v as f64 {
            f
        } else {
            ulps(f, self.conv)
        }
    }
    fn step(&self, p: f32, t: f32, c: f32) -> f32 {
        if self.fused {
            p.mul_add(t, c)
        } else {
            p * t + c
        }
    }
    // The WGSL functions of src/gpu/kernel.wgsl, line by line.
    fn sinpi_over(&self, t: f32) -> f32 {
        // The literals of kernel.wgsl, (-1)^k π^(2k+1)/(2k+1)!, rounded to f32.
        const C: [f64; 7] = [
            0.000_466_302_805_767_612_3,
            -0.007_370_430_945_714_348,
            0.082_145_886_611_128_19,
            -0.599_264_529_320_791_9,
            2.550_164_039_877_345,
            -5.167_712_780_049_969,
            core::f64::consts::PI,
        ];
        let mut p = C[0] as f32;
        for c in &C[1..] {
            p = self.step(p, t, *c as f32);
        }
        p
    }
    fn sinpi(&self, z: f32) -> f32 {
        z * self.sinpi_over(z * z)
    }
    fn single_slit(&self, y: f32) -> f32 {
        let q = if y.abs() <= 0.5 {
            self.sinpi_over(y * y) * core::f32::consts::FRAC_1_PI
        } else {
            let r = y - y.round_ties_even();
            self.div(self.sinpi(r), core::f32::consts::PI * y)
        };
        (q * q).min(1.0)
    }
    fn n_phase(&self, r: f32, n: u32) -> f32 {
        let bits = r.to_bits();
        let m = (bits & 0x7f_ffff) | 0x80_0000;
        let k = 150 - ((bits >> 23) & 0xff);
        let p = n as u64 * m as u64; // the two u32 words of the WGSL code
        let (lo, hi) = (p as u32, (p >> 32) as u32);
        let ldexp = |v: f32, e: i32| (v as f64 * 2f64.powi(e)) as f32; // exact here
        if k >= 32 {
            let hi_m = hi & ((1u32 << (k - 32)) - 1);
            ldexp(self.conv(hi_m), 32 - k as i32) + ldexp(self.conv(lo), -(k as i32))
        } else {
            let lo_m = lo & ((1u32 << k) - 1);
            ldexp(self.conv(lo_m), -(k as i32))
        }
    }
    fn n_slit(&self, x: f32, n: u32) -> f32 {
        if n <= 1 {
            return n as f32;
        }
        let r = x - x.round_ties_even();
        let nf = self.conv(n);
        let q = if nf * r.abs() <= 0.5 {
            let s = nf * r;
            self.div(self.sinpi_over(s * s), self.sinpi_over(r * r))
        } else {
            let f = self.n_phase(r, n);
            let s = f - f.round_ties_even();
            self.div(self.sinpi(s), nf * self.sinpi(r.abs()))
        };
        (q * q).min(1.0)
    }
}

/// A `GpuColorTable` of tabulated efficiencies stores each grid's nodes once: where a node's
/// grid over u ≤ 0 is its grid over u ≥ 0 (a mirror-symmetric preset, the CD) the second
/// grid's blocks are the first's, node indices included, and the node buffer holds one set a
/// node; a preset without that symmetry (`blazed600`) keeps two.
#[cfg(feature = "presets")]
#[test]
fn mirror_symmetric_colour_tables_store_their_nodes_once() {
    use diffraction::gpu::GpuColorTable;
    use diffraction::grating_bsdf::OrderEfficiency;
    use diffraction::relief::Preset;
    use diffraction::spectrum::{Illuminant, Spectral};
    use diffraction::{ColorTable, GratingBsdf, GrooveSpread};
    let spectral = Spectral::new(Illuminant::D65);
    for (preset, mirrored) in [(Preset::Cd, true), (Preset::Blazed600, false)] {
        // The classical reading, and the conical one (`GratingBsdf::preset`), whose GPU table
        // starts with the same words, blocks and nodes (its plane β = 0 is the classical
        // table) and holds its other planes after them.
        let conical = GratingBsdf::preset(preset, 8)
            .unwrap()
            .with_groove(GrooveSpread::gaussian(0.02).unwrap());
        let b = conical
            .with_efficiency(OrderEfficiency::from_static(preset.table()).unwrap())
            .unwrap();
        let table = ColorTable::new(&spectral, &b, 1e-1).unwrap();
        let t = GpuColorTable::new(&table);
        let from_conical = ColorTable::new(&spectral, &conical, 1e-1).unwrap();
        assert!(from_conical.node_count() > table.node_count(), "{preset}");
        let c = GpuColorTable::new(&from_conical);
        let count = t.header.block_count as usize;
        let k = t.incidence[0] as usize;
        let head = 2 + t.incidence[1] as usize + 2 * k;
        assert_eq!(t.incidence.len(), head + 1, "{preset}");
        assert_eq!(
            t.incidence[head], 0,
            "{preset}: a classical table has no planes"
        );
        assert_eq!(c.incidence[..head], t.incidence[..head], "{preset}");
        assert_eq!(c.blocks[..t.blocks.len()], t.blocks[..], "{preset}");
        assert_eq!(c.nodes[..t.nodes.len()], t.nodes[..], "{preset}");
        assert_eq!(c.header.block_count, t.header.block_count, "{preset}");
        let nodes = |t: &GpuColorTable, g: usize| {
            let b = &t.blocks[g * count..(g + 1) * count];
            (b[count - 1].first + b[count - 1].n + 1 - b[0].first) as usize
        };
        assert_eq!(t.blocks.len(), (1 + 2 * k) * count, "{preset}");
        let stored = stored_after(&t, count, 1, k, mirrored, nodes(&t, 0));
        assert_eq!(t.nodes.len(), stored, "{preset}");
        // The grid of normal incidence and as many as the CPU's incidence nodes keep (one grid
        // a node where mirror symmetric).
        assert_eq!(t.nodes.len(), nodes(&t, 0) + table.node_count(), "{preset}");
        // The planes: |wi.y| rising, c = √(1 − wi.y²), each plane's words where its entry
        // says and its grids after the previous plane's, every node stored once.
        let planes = c.incidence[head] as usize;
        assert_eq!(planes, 8, "{preset}");
        let (mut next_word, mut next_grid) = (head + 1 + 4 * planes, 1 + 2 * k);
        let mut stored = stored_after(&c, count, 1, k, mirrored, nodes(&c, 0));
        let mut last_beta = 0.0f32;
        for p in 0..planes {
            let e = &c.incidence[head + 1 + 4 * p..head + 5 + 4 * p];
            let (beta, cp) = (f32::from_bits(e[0]), f32::from_bits(e[1]));
            assert!(beta > last_beta, "{preset} plane {p}");
            assert!(
                (cp - (1.0 - beta * beta).sqrt()).abs() < 1e-6,
                "{preset} plane {p}"
            );
            last_beta = beta;
            assert_eq!(
                (e[2] as usize, e[3] as usize),
                (next_word, next_grid),
                "{preset} plane {p}"
            );
            let kp = c.incidence[next_word] as usize;
            let bins = c.incidence[next_word + 1] as usize;
            assert!(kp >= 2 && bins >= 1, "{preset} plane {p}");
            stored = stored_after(&c, count, next_grid, kp, mirrored, stored);
            next_word += 2 + bins + 2 * kp;
            next_grid += 2 * kp;
        }
        assert_eq!(c.incidence.len(), next_word, "{preset}");
        assert_eq!(c.blocks.len(), next_grid * count, "{preset}");
        assert_eq!(c.nodes.len(), stored, "{preset}");
        assert_eq!(
            c.nodes.len(),
            nodes(&c, 0) + from_conical.node_count(),
            "{preset}"
        );
        println!(
            "{preset}: {k} incidence nodes, {} GPU nodes; conical: {planes} more planes, {} GPU \
             nodes",
            t.nodes.len(),
            c.nodes.len()
        );
    }
}

/// `stored` plus the nodes of `k` incidence nodes' grids from grid `first` on (one grid a node
/// where `mirrored`, whose grid over u ≤ 0 repeats the blocks of the one over u ≥ 0).
fn stored_after(
    c: &diffraction::gpu::GpuColorTable,
    count: usize,
    first: usize,
    k: usize,
    mirrored: bool,
    stored: usize,
) -> usize {
    let grid = |g: usize| &c.blocks[g * count..(g + 1) * count];
    let nodes = |g: usize| {
        let b = grid(g);
        (b[count - 1].first + b[count - 1].n + 1 - b[0].first) as usize
    };
    let mut stored = stored;
    for node in 0..k {
        let (pos, neg) = (first + 2 * node, first + 1 + 2 * node);
        assert_eq!(
            grid(pos) == grid(neg),
            mirrored,
            "node {node} from grid {first}"
        );
        stored += nodes(pos) + if mirrored { 0 } else { nodes(neg) };
    }
    stored
}

#[test]
fn kernels_stay_inside_the_spec_bound_in_the_worst_case() {
    let mut rng = Mix(7);
    let freedoms = Freedom::all();
    let mut worst_f: f64 = 0.0;
    for n in SLITS {
        for x in stiff_phases(n, 6000, &mut rng) {
            let exact = n_slit_cycles(x as f64, n);
            for fr in &freedoms {
                let e = (fr.n_slit(x, n) as f64 - exact).abs();
                assert!(
                    e <= N_SLIT_SPEC,
                    "F_N x={x} n={n}: {e:e} > the spec bound {N_SLIT_SPEC:e}"
                );
                worst_f = worst_f.max(e);
            }
        }
    }
    let mut worst_s: f64 = 0.0;
    for y in stiff_phases(1000, 40_000, &mut rng) {
        let exact = single_slit_cycles(y as f64);
        for fr in &freedoms {
            let e = (fr.single_slit(y) as f64 - exact).abs();
            assert!(e <= SINGLE_SLIT_SPEC, "S y={y}: {e:e}");
            worst_s = worst_s.max(e);
        }
    }
    println!(
        "worst case over the spec's freedoms: F_N {worst_f:.2e} (spec bound {N_SLIT_SPEC:.2e}), \
         S {worst_s:.2e} (spec bound {SINGLE_SLIT_SPEC:.2e})"
    );
    assert!(worst_f <= N_SLIT_WORST_MEASURED, "F_N {worst_f:e}");
    assert!(worst_s <= SINGLE_SLIT_WORST_MEASURED, "S {worst_s:e}");
}

#[test]
fn the_builtin_sin_would_not_do() {
    // Why the kernels carry their own sin(πz): WGSL allows `sin` an absolute error of 2⁻¹¹ on
    // [−π, π]. Near a peak the ratio sin(πNr)/(N·sin(πr)) divides two small sines, so that error
    // is amplified: at N = 1000, r = 10⁻⁵ (s = N·r = 0.01) the textbook formula with a sine
    // perturbed by 2⁻¹¹ is off by far more than the whole bound of the polynomial kernel.
    let (n, r) = (1000u32, 1e-5f32);
    let s = n as f32 * r;
    let sin_worst = (core::f32::consts::PI * s).sin() + 2f32.powi(-11);
    let naive = sin_worst / (n as f32 * (core::f32::consts::PI * r).sin());
    let e = (naive as f64 * naive as f64 - n_slit_cycles(r as f64, n)).abs();
    assert!(e > 100.0 * N_SLIT_SPEC, "{e:e}");
}
