//! The order efficiencies of a grating, one JSON object per propagating reflected order.
//!
//! ```text
//! cargo run --release --example efficiencies -- --profile sinusoid|lamellar|sawtooth|amplitude \
//!     --period NM --depth NM [--duty F] [--blaze DEG] --metal Al|Ag|Au|Cu|Cr|N+Ki \
//!     --lambda NM --theta DEG [--polarisation te|tm|unpolarised]
//! cargo run --release --example efficiencies -- --table FILE.json|--preset cd|dvd|blazed600|foil \
//!     --lambda NM --theta DEG [--polarisation te|tm|unpolarised]
//! ```
//!
//! prints `{"order": m, "sin_theta": s, "efficiency": η, "te": η_TE, "tm": η_TM}` per order, with
//! sin θm = sin θi + m·λ/d (θi measured so that order 0 is the mirror direction; the crate's
//! u = wi.x + wo.x = m·λ/d), `efficiency` the chosen polarisation's (unpolarised = the mean of
//! TE and TM, the default).
//!
//! * `sinusoid`, `lamellar`, `sawtooth`: the scalar relief model (`diffraction::relief`) on the
//!   metal. `--depth` is the peak-to-valley depth of a sinusoid and the groove depth of a lamellar
//!   profile, `--duty` (lamellar, default 0.5) the raised ridge's share of the period. A sawtooth
//!   takes `--blaze` (its depth is then d·sin θB·cos θB) or `--depth` (then θB = ½·asin(2h/d),
//!   below 45°), or both if they agree. A query outside the model's measured valid region
//!   (`ScalarRelief::is_valid`, docs/validity.md) says so on stderr.
//! * `amplitude`: `GratingBsdf`'s amplitude grating, η_m = ρ²·sinc²(ρm) with ρ = `--duty`
//!   (default 0.5); it has no polarisation (no `te`, `tm` keys) and ignores `--depth` and
//!   `--metal`.
//! * `--table FILE`: a tabulated efficiency file (the JSON of `docs/efficiency_tables.md`, read
//!   with serde_json into `diffraction::relief::EfficiencyTable`), and `--preset NAME`: one of
//!   the crate's rigorous presets. Both print the table's interpolated orders that propagate at
//!   the query (normalised as `EfficiencyTable::efficiency` is: each polarisation's sum ≤ 1);
//!   the grating's flags (`--profile`, `--period`, …) do not go with them.
//!
//! Bad input gets an error naming the flag and exit code 2.

use std::io::Write;
use std::process::ExitCode;

use diffraction::relief::{EfficiencyTable, Metal, Preset, Relief, ScalarRelief};
use diffraction::{Grating, GratingBsdf};

/// The coherently lit periods of the amplitude model's `Grating` (its efficiencies do not depend
/// on it).
const AMPLITUDE_SLITS: u32 = 1000;
/// How closely `--depth` and `--blaze` of a sawtooth must agree (relative).
const SAWTOOTH_AGREEMENT: f64 = 1e-6;
/// Below this magnitude numbers are printed in exponent form (`4.4e-30`, not thirty zeros).
const EXPONENT_BELOW: f64 = 1e-4;
/// The largest `--table` file read (the shipped presets' are 31-124 kB). With feature `serde`
/// the library's reader keeps its memory within the table's bounds whatever the file; without
/// it the example's own reader builds a `serde_json::Value` tree (about ten times the text for
/// arrays of empty arrays), hence the smaller cap.
#[cfg(feature = "serde")]
const MAX_TABLE_BYTES: u64 = 256 << 20;
#[cfg(not(feature = "serde"))]
const MAX_TABLE_BYTES: u64 = 16 << 20;

/// The text of `file`, refused quickly and with bounded memory unless it is a regular file of
/// at most `max` bytes of UTF-8: its type and size are checked before it is opened (a FIFO
/// would block the open, `/dev/zero` never ends), and it is read through a `take` of
/// `max + 1` bytes (a file that grows meanwhile).
fn read_bounded(file: &str, max: u64) -> Result<String, String> {
    use std::io::Read;
    let cannot = |e: std::io::Error| format!("--table: cannot read {file:?}: {e}");
    let meta = std::fs::metadata(file).map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!(
            "--table: {file:?} is not a regular file (a directory, a device or a FIFO)"
        ));
    }
    let too_big =
        |size: u64| format!("--table: {file:?} has {size} bytes, more than the {max} this reads");
    if meta.len() > max {
        return Err(too_big(meta.len()));
    }
    let f = std::fs::File::open(file).map_err(cannot)?;
    if !f.metadata().map_err(cannot)?.is_file() {
        return Err(format!("--table: {file:?} is not a regular file"));
    }
    let mut bytes = Vec::new();
    f.take(max + 1).read_to_end(&mut bytes).map_err(cannot)?;
    if bytes.len() as u64 > max {
        return Err(too_big(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "--table: {file:?} is not UTF-8 (at byte {})",
            e.utf8_error().valid_up_to()
        )
    })
}

/// A finite number as JSON: the shortest round-trip form, in exponent form when tiny.
fn json(x: f64) -> String {
    if x != 0.0 && x.abs() < EXPONENT_BELOW {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Profile {
    Sinusoid,
    Lamellar,
    Sawtooth,
    Amplitude,
    /// `--table` or `--preset`: the grating is the table's.
    Table,
}

/// Where a tabulated model comes from.
#[derive(Debug, Clone, PartialEq)]
enum TableInput {
    Preset(Preset),
    File(String),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Polarisation {
    Te,
    Tm,
    Unpolarised,
}

#[derive(Debug, Clone, PartialEq)]
struct Options {
    profile: Profile,
    period_nm: f64,
    depth_nm: Option<f64>,
    duty: Option<f64>,
    blaze_deg: Option<f64>,
    metal: Metal,
    lambda_nm: f64,
    theta_deg: f64,
    polarisation: Polarisation,
    tabulated: Option<TableInput>,
}

const USAGE: &str = "usage: efficiencies --profile sinusoid|lamellar|sawtooth|amplitude --period NM --depth NM [--duty F] [--blaze DEG] --metal Al|Ag|Au|Cu|Cr|N+Ki --lambda NM --theta DEG [--polarisation te|tm|unpolarised]\n   or: efficiencies --table FILE.json|--preset cd|dvd|blazed600|foil --lambda NM --theta DEG [--polarisation te|tm|unpolarised]";

fn number(flag: &str, value: &str) -> Result<f64, String> {
    match value.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("{flag}: expected a finite number, got {value:?}")),
    }
}

/// `--profile`'s value.
fn profile_named(value: &str) -> Result<Profile, String> {
    Ok(match value {
        "sinusoid" => Profile::Sinusoid,
        "lamellar" => Profile::Lamellar,
        "sawtooth" => Profile::Sawtooth,
        "amplitude" => Profile::Amplitude,
        other => {
            let expected = "sinusoid, lamellar, sawtooth or amplitude";
            return Err(format!("--profile: expected {expected}, got {other:?}"));
        }
    })
}

/// `--polarisation`'s value.
fn polarisation_named(value: &str) -> Result<Polarisation, String> {
    Ok(match value {
        "te" => Polarisation::Te,
        "tm" => Polarisation::Tm,
        "unpolarised" => Polarisation::Unpolarised,
        other => {
            let expected = "te, tm or unpolarised";
            return Err(format!(
                "--polarisation: expected {expected}, got {other:?}"
            ));
        }
    })
}

fn parse(args: &[String]) -> Result<Options, String> {
    let mut seen: Vec<&str> = vec![];
    let (mut profile, mut period, mut depth, mut duty, mut blaze) = (None, None, None, None, None);
    let (mut metal, mut lambda, mut theta) = (None, None, None);
    let mut polarisation = Polarisation::Unpolarised;
    let mut tabulated = None;
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let flag = flag.as_str();
        if flag == "--help" || flag == "-h" {
            return Err(USAGE.to_string());
        }
        if !flag.starts_with("--") {
            return Err(format!("unexpected argument {flag:?}\n{USAGE}"));
        }
        let value = it
            .next()
            .ok_or_else(|| format!("{flag}: missing its value"))?;
        if seen.contains(&flag) {
            return Err(format!("{flag}: given twice"));
        }
        seen.push(flag);
        match flag {
            "--profile" => profile = Some(profile_named(value)?),
            "--period" => period = Some(number(flag, value)?),
            "--depth" => depth = Some(number(flag, value)?),
            "--duty" => duty = Some(number(flag, value)?),
            "--blaze" => blaze = Some(number(flag, value)?),
            "--metal" => {
                metal = Some(
                    value
                        .parse::<Metal>()
                        .map_err(|e| format!("--metal: {e} (got {value:?})"))?,
                )
            }
            "--lambda" => lambda = Some(number(flag, value)?),
            "--theta" => theta = Some(number(flag, value)?),
            "--polarisation" => polarisation = polarisation_named(value)?,
            "--table" => tabulated = Some(TableInput::File(value.clone())),
            "--preset" => {
                let p = value
                    .parse::<Preset>()
                    .map_err(|e| format!("--preset: {e} (got {value:?})"))?;
                tabulated = Some(TableInput::Preset(p));
            }
            other => return Err(format!("{other}: unknown flag\n{USAGE}")),
        }
    }
    let need = |v: Option<f64>, flag: &str| v.ok_or_else(|| format!("{flag}: required"));
    if let Some(t) = tabulated {
        let flag = match t {
            TableInput::File(_) => "--table",
            TableInput::Preset(_) => "--preset",
        };
        if seen.contains(&"--table") && seen.contains(&"--preset") {
            return Err("--table: not with --preset (one tabulated model)".to_string());
        }
        let grating_flags = [
            "--profile",
            "--period",
            "--depth",
            "--duty",
            "--blaze",
            "--metal",
        ];
        if let Some(g) = grating_flags.iter().find(|g| seen.contains(g)) {
            return Err(format!(
                "{flag}: not with {g} (the table holds the grating)"
            ));
        }
        return Ok(Options {
            profile: Profile::Table,
            period_nm: 0.0,
            depth_nm: None,
            duty: None,
            blaze_deg: None,
            metal: Metal::AL,
            lambda_nm: need(lambda, "--lambda")?,
            theta_deg: need(theta, "--theta")?,
            polarisation,
            tabulated: Some(t),
        });
    }
    let profile = profile.ok_or("--profile: required")?;
    let metal = match (metal, profile) {
        (Some(m), _) => m,
        (None, Profile::Amplitude) => Metal::AL,
        (None, _) => return Err("--metal: required".to_string()),
    };
    if duty.is_some() && !matches!(profile, Profile::Lamellar | Profile::Amplitude) {
        return Err("--duty: only for --profile lamellar or amplitude".to_string());
    }
    if blaze.is_some() && profile != Profile::Sawtooth {
        return Err("--blaze: only for --profile sawtooth".to_string());
    }
    if matches!(profile, Profile::Sinusoid | Profile::Lamellar) && depth.is_none() {
        return Err("--depth: required".to_string());
    }
    if profile == Profile::Sawtooth && depth.is_none() && blaze.is_none() {
        return Err("--blaze: required for a sawtooth (or --depth)".to_string());
    }
    Ok(Options {
        profile,
        period_nm: need(period, "--period")?,
        depth_nm: depth,
        duty,
        blaze_deg: blaze,
        metal,
        lambda_nm: need(lambda, "--lambda")?,
        theta_deg: need(theta, "--theta")?,
        polarisation,
        tabulated: None,
    })
}

/// The table of `--table FILE` or `--preset NAME`.
fn load_table(t: &TableInput) -> Result<std::borrow::Cow<'static, EfficiencyTable>, String> {
    let file = match t {
        TableInput::Preset(p) => return Ok(std::borrow::Cow::Borrowed(p.table())),
        TableInput::File(f) => f,
    };
    let text = read_bounded(file, MAX_TABLE_BYTES)?;
    parse_table(file, &text).map(std::borrow::Cow::Owned)
}

/// A JSON table (`EfficiencyTable`'s `Deserialize`, feature `serde`).
#[cfg(feature = "serde")]
fn parse_table(file: &str, text: &str) -> Result<EfficiencyTable, String> {
    serde_json::from_str::<EfficiencyTable>(text).map_err(|e| format!("--table: {file:?}: {e}"))
}

/// Without the `serde` feature: the documented fields read with serde_json's `Value` and
/// checked by `EfficiencyTable::new` (the same checks on load as the library's `Deserialize`).
#[cfg(not(feature = "serde"))]
fn parse_table(file: &str, text: &str) -> Result<EfficiencyTable, String> {
    use serde_json::Value;
    let err = |what: String| format!("--table: {file:?}: {what}");
    let v: Value = serde_json::from_str(text).map_err(|e| err(e.to_string()))?;
    if v["format"] != "diffraction-efficiency-table" {
        return Err(err(
            "format: expected \"diffraction-efficiency-table\"".to_string()
        ));
    }
    if v["version"] != 1 {
        return Err(err(format!("version: expected 1, got {}", v["version"])));
    }
    let number = |x: &Value, name: &str| {
        x.as_f64()
            .ok_or_else(|| err(format!("{name}: expected a number")))
    };
    let list = |name: &str| -> Result<Vec<f64>, String> {
        v[name]
            .as_array()
            .ok_or_else(|| err(format!("{name}: expected an array of numbers")))?
            .iter()
            .map(|x| number(x, name))
            .collect()
    };
    // te[k][j][i]: order k, wavelength j, incidence i, flattened in that order.
    let cube = |name: &str| -> Result<Vec<f64>, String> {
        let mut out = Vec::new();
        let shape = || {
            err(format!(
                "{name}: expected an array [orders][lambda][sin_theta_i]"
            ))
        };
        for order in v[name].as_array().ok_or_else(shape)? {
            for row in order.as_array().ok_or_else(shape)? {
                for x in row.as_array().ok_or_else(shape)? {
                    out.push(number(x, name)?);
                }
            }
        }
        Ok(out)
    };
    let order_min = v["order_min"]
        .as_i64()
        .and_then(|m| i32::try_from(m).ok())
        .ok_or_else(|| err("order_min: expected an integer".to_string()))?;
    let period = number(&v["grating"]["period_nm"], "grating.period_nm")?;
    EfficiencyTable::new(
        period,
        order_min,
        list("sin_theta_i")?,
        list("lambda_nm")?,
        cube("te")?,
        cube("tm")?,
    )
    .map_err(|e| err(e.to_string()))
}

/// The JSON line of one order.
fn order_line(
    order: i32,
    sin_theta: f64,
    e: diffraction::relief::Polarised,
    p: Polarisation,
) -> String {
    let eta = match p {
        Polarisation::Te => e.te,
        Polarisation::Tm => e.tm,
        Polarisation::Unpolarised => e.unpolarised(),
    };
    format!(
        "{{\"order\": {order}, \"sin_theta\": {}, \"efficiency\": {}, \"te\": {}, \"tm\": {}}}",
        json(sin_theta),
        json(eta),
        json(e.te),
        json(e.tm)
    )
}

/// The sawtooth's blaze angle in radians from `--blaze` and/or `--depth`.
fn blaze_rad(o: &Options) -> Result<f64, String> {
    let from_depth = o
        .depth_nm
        .map(|h| {
            let r = 2.0 * h / o.period_nm;
            if !(0.0..=1.0).contains(&r) {
                return Err(format!(
                    "--depth: a 90°-apex sawtooth is at most half its period deep ({} nm), got {h}",
                    0.5 * o.period_nm
                ));
            }
            Ok(0.5 * r.asin())
        })
        .transpose()?;
    match (o.blaze_deg, from_depth) {
        (Some(b), None) => Ok(b.to_radians()),
        (None, Some(b)) => Ok(b),
        (Some(b), Some(_)) => {
            let h = o.period_nm * b.to_radians().sin() * b.to_radians().cos();
            let given = o.depth_nm.unwrap_or(h);
            if (h - given).abs() <= SAWTOOTH_AGREEMENT * h.max(given) {
                Ok(b.to_radians())
            } else {
                Err(format!(
                    "--depth: {given} nm disagrees with --blaze {b}° (depth d·sin θB·cos θB = {h} nm)"
                ))
            }
        }
        (None, None) => Err("--blaze: required for a sawtooth (or --depth)".to_string()),
    }
}

/// One JSON line per propagating order, and a note for stderr (`None` if none is due).
fn run(o: &Options) -> Result<(Vec<String>, Option<String>), String> {
    if !(o.theta_deg > -90.0 && o.theta_deg < 90.0) {
        return Err(format!(
            "--theta: expected an angle in (-90, 90) degrees, got {}",
            o.theta_deg
        ));
    }
    if o.lambda_nm <= 0.0 {
        return Err(format!("--lambda: expected > 0 nm, got {}", o.lambda_nm));
    }
    let s = o.theta_deg.to_radians().sin();
    let flag = |e: diffraction::Error| -> String {
        let name = match e.parameter() {
            "period_nm" => "--period",
            "depth_nm" => "--depth",
            "duty" | "slit_width_nm" => "--duty",
            "blaze_rad" => "--blaze",
            other => other,
        };
        format!("{name}: {e}")
    };
    let mut lines = vec![];
    if let Some(t) = &o.tabulated {
        let table = load_table(t)?;
        let mut out = vec![diffraction::relief::Polarised::default(); table.order_count()];
        table.efficiencies(s, o.lambda_nm, &mut out);
        for (m, e) in table.orders().zip(out) {
            let sm = s + f64::from(m) * o.lambda_nm / table.period_nm();
            if sm.abs() < 1.0 {
                lines.push(order_line(m, sm, e, o.polarisation));
            }
        }
        return Ok((lines, None));
    }
    if o.profile == Profile::Amplitude {
        let rho = o.duty.unwrap_or(0.5);
        if !(rho > 0.0 && rho <= 1.0) {
            return Err(format!("--duty: expected 0 < duty <= 1, got {rho}"));
        }
        let grating =
            Grating::new(o.period_nm, rho * o.period_nm, AMPLITUDE_SLITS).map_err(flag)?;
        let bsdf = GratingBsdf::new(grating);
        let step = o.lambda_nm / o.period_nm;
        let lo = ((-1.0 - s) / step).floor().max(-1e6) as i32;
        let hi = ((1.0 - s) / step).ceil().min(1e6) as i32;
        for m in lo..=hi {
            let sm = s + f64::from(m) * step;
            if sm.abs() < 1.0 {
                lines.push(format!(
                    "{{\"order\": {m}, \"sin_theta\": {}, \"efficiency\": {}}}",
                    json(sm),
                    json(bsdf.efficiency(m))
                ));
            }
        }
        return Ok((lines, None));
    }
    let relief = match o.profile {
        Profile::Sinusoid => Relief::sinusoid(o.depth_nm.unwrap_or(0.0)),
        Profile::Lamellar => Relief::lamellar(o.depth_nm.unwrap_or(0.0), o.duty.unwrap_or(0.5)),
        _ => Relief::sawtooth(blaze_rad(o)?),
    }
    .map_err(flag)?;
    let grating = ScalarRelief::new(relief, o.metal, o.period_nm).map_err(flag)?;
    for order in grating.orders(s, o.lambda_nm) {
        lines.push(order_line(
            order.order,
            order.sin_theta,
            order.efficiency,
            o.polarisation,
        ));
    }
    let note = (!grating.is_valid(s, o.lambda_nm)).then(|| {
        "note: outside the scalar model's measured valid region (ScalarRelief::is_valid, docs/validity.md); use a rigorous table there".to_string()
    });
    Ok((lines, note))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match parse(&args).and_then(|o| run(&o)) {
        Ok((lines, note)) => {
            if let Some(n) = note {
                eprintln!("{n}");
            }
            let mut out = std::io::stdout().lock();
            for l in lines {
                // A closed pipe (`| head`) ends the output quietly.
                if writeln!(out, "{l}").is_err() {
                    break;
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
#[path = "efficiencies/tests.rs"]
mod tests;
