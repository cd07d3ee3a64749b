//! `matte brdf` and `matte albedo`: one model, evaluated by the kernels, printed as JSON.
//! Schema in docs/usage.md.

use clap::Args;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, frame::spherical_direction};
use serde::Serialize;
use std::collections::BTreeMap;

#[derive(Args, Debug)]
pub struct BsdfSpec {
    /// Plugin name (`matte types` lists them).
    #[arg(long = "bsdf", value_name = "TYPE")]
    pub kind: String,
    /// Model parameter NAME=VALUE (repeatable), e.g. sigma=0.3, model=full, int_ior=bk7.
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
}

impl BsdfSpec {
    /// The model, built as every front end builds one ([`DiffuseModel::with`]).
    pub fn build(&self) -> Result<DiffuseModel, String> {
        let mut params: Vec<(&str, ParamValue)> = Vec::new();
        for p in &self.params {
            let (name, value) = p.split_once('=').ok_or_else(|| format!("--param \"{p}\": expected NAME=VALUE"))?;
            params.push((name.trim(), ParamValue::parse(value)));
        }
        DiffuseModel::with(&self.kind, &params).map_err(|e| format!("bsdf \"{}\": {e}", self.kind))
    }
}

#[derive(Args, Debug)]
pub struct BrdfArgs {
    #[command(flatten)]
    pub spec: BsdfSpec,
    /// Reflectance (albedo parameter) in [0, 1].
    #[arg(long, default_value_t = 0.5)]
    pub reflectance: f64,
    /// Polar angle of wi (towards the light), degrees.
    #[arg(long = "theta-i", required_unless_present_any = ["grid", "pairs"], allow_negative_numbers = true)]
    pub theta_i: Option<f64>,
    /// Polar angle of wo (towards the viewer), degrees.
    #[arg(long = "theta-o", required_unless_present_any = ["grid", "pairs"], allow_negative_numbers = true)]
    pub theta_o: Option<f64>,
    /// Azimuth difference φo − φi, degrees (0: viewer on the light's side).
    #[arg(long, required_unless_present_any = ["grid", "pairs"], allow_negative_numbers = true)]
    pub phi: Option<f64>,
    /// Evaluate on an N×N×N grid instead: θ in [0, 90) step 90/N, φ in [0, 180] in N steps.
    #[arg(long, conflicts_with_all = ["theta_i", "theta_o", "phi", "pairs"])]
    pub grid: Option<usize>,
    /// Evaluate at direction pairs read from a file ("-": stdin), one pair per line as six
    /// numbers `wi.x wi.y wi.z wo.x wo.y wo.z` (local frame, unit vectors).
    #[arg(long, value_name = "PATH", conflicts_with_all = ["theta_i", "theta_o", "phi"])]
    pub pairs: Option<String>,
}

#[derive(Args, Debug)]
pub struct AlbedoArgs {
    #[command(flatten)]
    pub spec: BsdfSpec,
    /// Polar angle of incidence, degrees.
    #[arg(long = "theta-i", allow_negative_numbers = true)]
    pub theta_i: f64,
    /// Reflectance in [0, 1]; 1 gives the white-furnace value.
    #[arg(long, default_value_t = 1.0)]
    pub reflectance: f64,
}

fn check_reflectance(r: f64) -> Result<f32, String> {
    if (0.0..=1.0).contains(&r) { Ok(r as f32) } else { Err(format!("--reflectance must lie in [0, 1] (got {r})")) }
}

fn check_angle(name: &str, deg: f64, max: f64) -> Result<f64, String> {
    if deg.is_finite() && (0.0..=max).contains(&deg) {
        Ok(deg)
    } else {
        Err(format!("--{name} must lie in [0, {max}] degrees (got {deg})"))
    }
}

/// The model as the JSON output names it: plugin, effective parameters, reflectance.
#[derive(Serialize)]
struct Header {
    bsdf: &'static str,
    params: BTreeMap<&'static str, ParamValue>,
    reflectance: f64,
}

fn header(bsdf: &DiffuseModel, reflectance: f64) -> Header {
    Header { bsdf: bsdf.kind(), params: bsdf.parameters().into_iter().collect(), reflectance }
}

/// `matte brdf` output: the header and one of three forms of values.
#[derive(Serialize)]
struct BrdfOutput {
    #[serde(flatten)]
    header: Header,
    #[serde(flatten)]
    values: BrdfValues,
}

#[derive(Serialize)]
#[serde(untagged)]
enum BrdfValues {
    /// `--pairs`: f and pdf per direction pair.
    Pairs { f: Vec<f32>, pdf: Vec<f32> },
    /// `--grid N`: f and pdf indexed [θi][θo][φ].
    Grid {
        grid: usize,
        theta_i: Vec<f64>,
        theta_o: Vec<f64>,
        phi: Vec<f64>,
        f: Vec<Vec<Vec<f32>>>,
        pdf: Vec<Vec<Vec<f32>>>,
    },
    /// One direction pair given by its angles (degrees).
    Point { theta_i: f64, theta_o: f64, phi: f64, f: f32, f_cos: f32, pdf: f32 },
}

/// `matte albedo` output.
#[derive(Serialize)]
struct AlbedoOutput {
    #[serde(flatten)]
    header: Header,
    theta_i: f64,
    albedo: f64,
    method: &'static str,
}

fn print_json(value: &impl Serialize) -> Result<(), String> {
    println!("{}", serde_json::to_string(value).map_err(|e| format!("JSON output: {e}"))?);
    Ok(())
}

/// wi at azimuth 0, wo at azimuth φ (degrees in, local-frame directions out).
fn directions(theta_i: f64, theta_o: f64, phi: f64) -> (glam::Vec3, glam::Vec3) {
    (
        spherical_direction(theta_i.to_radians() as f32, 0.0),
        spherical_direction(theta_o.to_radians() as f32, phi.to_radians() as f32),
    )
}

pub fn run_brdf(a: &BrdfArgs) -> Result<(), String> {
    let bsdf = a.spec.build()?;
    let rho = check_reflectance(a.reflectance)?;
    let values = if let Some(path) = &a.pairs {
        let (wi, wo) = read_pairs(path)?;
        let f: Vec<f32> = wi.iter().zip(&wo).map(|(a, b)| bsdf.eval(*a, *b, [rho])[0]).collect();
        let pdf: Vec<f32> = wi.iter().zip(&wo).map(|(a, b)| bsdf.pdf(*a, *b)).collect();
        BrdfValues::Pairs { f, pdf }
    } else if let Some(n) = a.grid {
        if !(1..=256).contains(&n) {
            return Err(format!("--grid must lie in [1, 256] (got {n})"));
        }
        let thetas: Vec<f64> = (0..n).map(|k| 90.0 * k as f64 / n as f64).collect();
        let phis: Vec<f64> = (0..n).map(|k| if n == 1 { 0.0 } else { 180.0 * k as f64 / (n - 1) as f64 }).collect();
        let mut f = Vec::with_capacity(n);
        let mut pdf = Vec::with_capacity(n);
        for &ti in &thetas {
            let (mut f_i, mut p_i) = (Vec::with_capacity(n), Vec::with_capacity(n));
            for &to in &thetas {
                let (mut f_o, mut p_o) = (Vec::with_capacity(n), Vec::with_capacity(n));
                for &ph in &phis {
                    let (wi, wo) = directions(ti, to, ph);
                    f_o.push(bsdf.eval(wi, wo, [rho])[0]);
                    p_o.push(bsdf.pdf(wi, wo));
                }
                f_i.push(f_o);
                p_i.push(p_o);
            }
            f.push(f_i);
            pdf.push(p_i);
        }
        BrdfValues::Grid { grid: n, theta_i: thetas.clone(), theta_o: thetas, phi: phis, f, pdf }
    } else {
        let (ti, to, ph) = (a.theta_i.unwrap_or(0.0), a.theta_o.unwrap_or(0.0), a.phi.unwrap_or(0.0));
        let ti = check_angle("theta-i", ti, 180.0)?;
        let to = check_angle("theta-o", to, 180.0)?;
        if !ph.is_finite() {
            return Err(format!("--phi must be a finite angle (got {ph})"));
        }
        let (wi, wo) = directions(ti, to, ph);
        let f = bsdf.eval(wi, wo, [rho])[0];
        BrdfValues::Point { theta_i: ti, theta_o: to, phi: ph, f, f_cos: f * wo.z.max(0.0), pdf: bsdf.pdf(wi, wo) }
    };
    print_json(&BrdfOutput { header: header(&bsdf, a.reflectance), values })
}

/// Reads `wi.x wi.y wi.z wo.x wo.y wo.z` lines; errors name the line.
fn read_pairs(path: &str) -> Result<(Vec<glam::Vec3>, Vec<glam::Vec3>), String> {
    let text = if path == "-" {
        std::io::read_to_string(std::io::stdin()).map_err(|e| format!("--pairs: reading stdin: {e}"))?
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("--pairs: {path}: {e}"))?
    };
    let (mut wi, mut wo) = (Vec::new(), Vec::new());
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let v: Vec<f32> = line
            .split_whitespace()
            .map(|t| t.parse::<f32>().map_err(|_| format!("--pairs: {path}:{}: \"{t}\" is not a number", k + 1)))
            .collect::<Result<_, _>>()?;
        if v.len() != 6 || v.iter().any(|x| !x.is_finite()) {
            return Err(format!("--pairs: {path}:{}: expected six finite numbers, got \"{}\"", k + 1, line.trim()));
        }
        wi.push(glam::Vec3::new(v[0], v[1], v[2]));
        wo.push(glam::Vec3::new(v[3], v[4], v[5]));
    }
    Ok((wi, wo))
}

pub fn run_albedo(a: &AlbedoArgs) -> Result<(), String> {
    let bsdf = a.spec.build()?;
    let rho = check_reflectance(a.reflectance)?;
    let ti = check_angle("theta-i", a.theta_i, 180.0)?;
    let albedo = bsdf.albedo(ti.to_radians().cos(), rho);
    print_json(&AlbedoOutput {
        header: header(&bsdf, a.reflectance),
        theta_i: ti,
        albedo: albedo.value,
        method: albedo.method.as_str(),
    })
}
