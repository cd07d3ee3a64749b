//! An isotropic BRDF given as a table (`docs/microgeometry.md#the-tabulated-ground-truth-brdf`):
//! `f/ρ` on nodes of the facet reflectance ρ, the zenith angles θi and θo and the azimuth
//! difference Δφ ∈ [0°, 180°], multilinear interpolation between nodes (clamped at the ends),
//! cosine-weighted sampling (the trait's default) and the albedo by quadrature of the
//! interpolant. Built from a simulated microsurface by `matte microgeometry --table`, or from
//! any function (a closed-form model, for tests).
//!
//! Two evaluations of the same interpolant:
//! - [`BrdfTable`]'s own ([`BrdfTable::eval_angles`], its [`DiffuseBrdf`]): angles in f64
//!   degrees, nodes located by search. The reference, and what the microgeometry tools use.
//! - [`Tabulated`]: the kernel written over [`Real`] ([`TableKernel`]), branch-free, which
//!   `matte render`'s `tabulated_brdf` runs in f32 and the Mitsuba plugin runs in f32 (scalar
//!   variants) and traced into Dr.Jit (JIT variants, the values a gathered table, gradients
//!   with respect to the reflectance through the interpolation weights).
//!
//! `f/ρ` rather than `f` is stored because a microsurface's BRDF is not linear in its facet
//! albedo (interreflections go as ρ², ρ³ …) but `f/ρ` is smooth and finite down to ρ = 0
//! (where it is the single-scattering BRDF of a white surface), so a few ρ nodes interpolate it.

use crate::DiffuseBrdf;
use crate::approx::{acos_unit, angle};
use crate::kernel::Kernel;
use crate::real::{Nodes, Real, V3};
use crate::params::{ParamError, ParamValue};
use crate::registry::{
    Evaluation, Gradients, KernelBrdf, ModelSpec, NoValues, ParamSpec, Registered, Values, param, parameter_values,
};
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::sync::Arc;

/// The plugin name of a table file as a BSDF (`<bsdf type="tabulated_brdf">`, in every front
/// end).
pub const PLUGIN_NAME: &str = "tabulated_brdf";

/// Zenith nodes of the ground-truth tables (`matte microgeometry --table` writes them; degrees).
pub const TABLE_THETA: [f64; 12] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 75.0, 80.0, 85.0, 89.0];
/// Azimuth-difference nodes (degrees).
pub const TABLE_DELTA_PHI: [f64; 7] = [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0];
/// Facet-reflectance nodes.
pub const TABLE_REFLECTANCE: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// The file's `format` value.
pub const FORMAT: &str = "matte-tabulated-brdf";
/// The file format's version.
pub const VERSION: u32 = 1;

/// The table and its file format (JSON; `docs/microgeometry.md#file-format`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BrdfTable {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// What the table is (free text, e.g. the surface and the photon count).
    pub description: String,
    /// Zenith-angle nodes in degrees, increasing, within [0, 90); shared by θi and θo.
    pub theta_deg: Vec<f64>,
    /// Azimuth-difference nodes in degrees, increasing, within [0, 180] (0: wo on the side of wi).
    pub delta_phi_deg: Vec<f64>,
    /// Facet-reflectance nodes, increasing, within [0, 1].
    pub reflectance: Vec<f64>,
    /// `f/ρ` (1/sr), flattened with Δφ fastest: index `((r·Nθ + i)·Nθ + o)·NΔφ + p` for
    /// reflectance node r, θi node i, θo node o, Δφ node p.
    pub f_over_reflectance: Vec<f32>,
    /// Optional 99 % half-widths of `f_over_reflectance` (same layout), from the simulation.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub half_width_over_reflectance: Vec<f32>,
}

/// Where `x` falls between `nodes`: the lower index and the weight of the upper node, clamped
/// to the first and last node.
fn locate(nodes: &[f64], x: f64) -> (usize, f32) {
    let n = nodes.len();
    if n == 1 || x <= nodes[0] {
        return (0, 0.0);
    }
    if x >= nodes[n - 1] {
        return (n - 2, 1.0);
    }
    let k = nodes.partition_point(|&v| v <= x).clamp(1, n - 1) - 1;
    (k, ((x - nodes[k]) / (nodes[k + 1] - nodes[k])) as f32)
}

fn increasing_within(name: &str, v: &[f64], lo: f64, hi: f64, hi_open: bool) -> Result<(), String> {
    if v.is_empty() {
        return Err(format!("`{name}` is empty"));
    }
    if v.iter().any(|x| !x.is_finite() || *x < lo || *x > hi || (hi_open && *x >= hi)) {
        return Err(format!("`{name}` must lie within [{lo}, {hi}{}", if hi_open { ")" } else { "]" }));
    }
    if v.windows(2).any(|w| w[1] <= w[0]) {
        return Err(format!("`{name}` must be strictly increasing"));
    }
    Ok(())
}

impl BrdfTable {
    /// A table of `f(wi, wo, ρ)/ρ` for a function `f` of (θi, θo, Δφ in radians, ρ), sampled on
    /// the nodes. At ρ = 0 the function is called with ρ = 1e-6.
    pub fn from_fn(
        description: &str,
        theta_deg: Vec<f64>,
        delta_phi_deg: Vec<f64>,
        reflectance: Vec<f64>,
        f: impl Fn(f64, f64, f64, f64) -> f64,
    ) -> Result<Self, String> {
        let mut values = Vec::with_capacity(reflectance.len() * theta_deg.len().pow(2) * delta_phi_deg.len());
        for &rho in &reflectance {
            let rho = rho.max(1e-6);
            for &ti in &theta_deg {
                for &to in &theta_deg {
                    for &p in &delta_phi_deg {
                        values.push((f(ti.to_radians(), to.to_radians(), p.to_radians(), rho) / rho) as f32);
                    }
                }
            }
        }
        Self::new(description, theta_deg, delta_phi_deg, reflectance, values, Vec::new())
    }

    /// A checked table (`f_over_reflectance` in the documented layout).
    pub fn new(
        description: &str,
        theta_deg: Vec<f64>,
        delta_phi_deg: Vec<f64>,
        reflectance: Vec<f64>,
        f_over_reflectance: Vec<f32>,
        half_width_over_reflectance: Vec<f32>,
    ) -> Result<Self, String> {
        let t = BrdfTable {
            format: FORMAT.into(),
            version: VERSION,
            description: description.into(),
            theta_deg,
            delta_phi_deg,
            reflectance,
            f_over_reflectance,
            half_width_over_reflectance,
        };
        t.check()?;
        Ok(t)
    }

    /// Reads and checks a table file.
    pub fn read(path: &std::path::Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let t: BrdfTable = serde_json::from_str(&text).map_err(|e| format!("{}:{}: {e}", path.display(), e.line()))?;
        t.check().map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(t)
    }

    /// Writes the table as JSON.
    pub fn write(&self, path: &std::path::Path) -> Result<(), String> {
        let text = serde_json::to_string(self).map_err(|e| format!("tabulated BRDF: {e}"))?;
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
    }

    fn check(&self) -> Result<(), String> {
        if self.format != FORMAT || self.version != VERSION {
            return Err(format!(
                "not a {FORMAT} file of version {VERSION} (format \"{}\", version {})",
                self.format, self.version
            ));
        }
        increasing_within("theta_deg", &self.theta_deg, 0.0, 90.0, true)?;
        increasing_within("delta_phi_deg", &self.delta_phi_deg, 0.0, 180.0, false)?;
        increasing_within("reflectance", &self.reflectance, 0.0, 1.0, false)?;
        let n = self.reflectance.len() * self.theta_deg.len().pow(2) * self.delta_phi_deg.len();
        if self.f_over_reflectance.len() != n {
            return Err(format!(
                "`f_over_reflectance` has {} values, the nodes need {n}",
                self.f_over_reflectance.len()
            ));
        }
        if !self.half_width_over_reflectance.is_empty() && self.half_width_over_reflectance.len() != n {
            return Err(format!(
                "`half_width_over_reflectance` has {} values, expected 0 or {n}",
                self.half_width_over_reflectance.len()
            ));
        }
        if let Some(k) = self.f_over_reflectance.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!(
                "`f_over_reflectance`[{k}] = {} is not a finite value ≥ 0",
                self.f_over_reflectance[k]
            ));
        }
        Ok(())
    }

    fn index(&self, r: usize, i: usize, o: usize, p: usize) -> usize {
        let nt = self.theta_deg.len();
        ((r * nt + i) * nt + o) * self.delta_phi_deg.len() + p
    }

    /// Interpolated `f/ρ` at reflectance node `r`.
    fn at_node(&self, r: usize, ti: (usize, f32), to: (usize, f32), dp: (usize, f32)) -> f32 {
        let last =
            |n: usize, (k, w): (usize, f32)| if n == 1 { [(0, 1.0), (0, 0.0)] } else { [(k, 1.0 - w), (k + 1, w)] };
        let nt = self.theta_deg.len();
        let mut sum = 0.0;
        for (i, wi) in last(nt, ti) {
            for (o, wo) in last(nt, to) {
                for (p, wp) in last(self.delta_phi_deg.len(), dp) {
                    let w = wi * wo * wp;
                    if w != 0.0 {
                        sum += w * self.f_over_reflectance[self.index(r, i, o, p)];
                    }
                }
            }
        }
        sum
    }

    /// `f` for zenith angles and azimuth difference in degrees and one reflectance.
    pub fn eval_angles(&self, theta_i: f64, theta_o: f64, delta_phi: f64, rho: f32) -> f32 {
        let (ti, to, dp) = (
            locate(&self.theta_deg, theta_i),
            locate(&self.theta_deg, theta_o),
            locate(&self.delta_phi_deg, delta_phi),
        );
        let (r, w) = locate(&self.reflectance, rho as f64);
        let lo = self.at_node(r, ti, to, dp);
        let per_rho = if self.reflectance.len() == 1 || w == 0.0 {
            lo
        } else {
            (1.0 - w) * lo + w * self.at_node(r + 1, ti, to, dp)
        };
        rho * per_rho
    }

    /// The largest `E(θi)/ρ` over the θi and reflectance nodes (quadrature of the interpolant):
    /// at most 1 for a surface whose light leaves after at least one facet bounce.
    pub fn max_albedo_over_reflectance(&self) -> f64 {
        let mut worst: f64 = 0.0;
        for &rho in &self.reflectance {
            let rho = rho.max(1e-3) as f32;
            for &t in &self.theta_deg {
                worst = worst.max(self.albedo(t.to_radians().cos(), rho).value / rho as f64);
            }
        }
        worst
    }

    /// Multiplies every entry by `s` (the half-widths too).
    pub fn scale(&mut self, s: f32) {
        self.f_over_reflectance.iter_mut().for_each(|v| *v *= s);
        self.half_width_over_reflectance.iter_mut().for_each(|v| *v *= s);
    }
}

/// Zenith angle of a unit vector in degrees.
fn theta_deg(w: Vec3) -> f64 {
    (w.z as f64).clamp(-1.0, 1.0).acos().to_degrees()
}

/// Azimuth difference of two directions in degrees within [0, 180]; 0 when either is the normal.
fn delta_phi_deg(a: Vec3, b: Vec3) -> f64 {
    let (ax, ay, bx, by) = (a.x as f64, a.y as f64, b.x as f64, b.y as f64);
    let (la, lb) = ((ax * ax + ay * ay).sqrt(), (bx * bx + by * by).sqrt());
    if la < 1e-7 || lb < 1e-7 {
        return 0.0;
    }
    ((ax * bx + ay * by) / (la * lb)).clamp(-1.0, 1.0).acos().to_degrees()
}

impl DiffuseBrdf for BrdfTable {
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return [0.0; N];
        }
        let (ti, to, dp) = (theta_deg(wi), theta_deg(wo), delta_phi_deg(wi, wo));
        reflectance.map(|rho| self.eval_angles(ti, to, dp, rho))
    }
}

/// One axis of the table as the kernel locates a coordinate on it: the cells' lower nodes and
/// inverse widths (f64, rounded to the kernel's type when used).
#[derive(Clone, Debug, PartialEq)]
struct Axis {
    lower: Vec<f64>,
    inv_width: Vec<f64>,
}

impl Axis {
    fn new(nodes: &[f64], scale: f64) -> Self {
        let n: Vec<f64> = nodes.iter().map(|x| x * scale).collect();
        Axis { lower: n.windows(2).map(|w| w[0]).collect(), inv_width: n.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect() }
    }

    /// The number of cells (one for a single-node axis, whose upper node is its only node).
    fn cells(&self) -> usize {
        self.lower.len().max(1)
    }

    /// `(k, w)`: the cell of `x` and the weight of its upper node, clamped to the first and
    /// last node (NaN gives the first). Branch-free: each interior node `x` reaches moves the
    /// cell up one (a compare and three selects of constants), and the weight is
    /// `clamp((x − xₖ)/(xₖ₊₁ − xₖ), 0, 1)`, differentiable in `x` (the reflectance axis).
    #[inline(always)]
    fn locate<T: Real>(&self, x: T) -> (T, T) {
        let mut k = T::c(0.0);
        let w = self.weight(x, |reached, j| k = T::select(reached, T::c(j as f64), k));
        (k, w)
    }

    /// `v` (one value per node) interpolated at `x`: `(1 − w)·v[k] + w·v[k + 1]` with `(k, w)`
    /// of [`Axis::locate`] (the same compares and weight), the two values picked by selects.
    #[inline(always)]
    fn interpolate<T: Real>(&self, x: T, v: &[T]) -> T {
        let (mut lo, mut hi) = (v[0], v[v.len().min(2) - 1]);
        let w = self.weight(x, |reached, j| {
            lo = T::select(reached, v[j], lo);
            hi = T::select(reached, v[j + 1], hi);
        });
        (T::c(1.0) - w) * lo + w * hi
    }

    /// The weight of the upper node of `x`'s cell; `reached(mask, j)` is called for each
    /// interior node `j` with the lanes whose `x` reaches it (the cell is the last reached).
    /// Zero on a single-node axis.
    #[inline(always)]
    fn weight<T: Real>(&self, x: T, mut reached: impl FnMut(T::Mask, usize)) -> T {
        let Some((&first, &first_inv)) = self.lower.first().zip(self.inv_width.first()) else {
            return T::c(0.0);
        };
        let (mut lower, mut inv) = (T::c(first), T::c(first_inv));
        for (j, (&a, &w)) in self.lower.iter().zip(&self.inv_width).enumerate().skip(1) {
            let at = x.ge(T::c(a));
            reached(at, j);
            lower = T::select(at, T::c(a), lower);
            inv = T::select(at, T::c(w), inv);
        }
        ((x - lower) * inv).clamp_to(0.0, 1.0)
    }
}

/// The most reflectance nodes whose packets [`TableKernel`] gathers once for all channels.
const SHARED_NODES: usize = 8;

/// The corners of every (θi, θo, Δφ) cell at every reflectance node, eight consecutive values
/// (one packet gather) per cell and node: packet `((i·Cθ + o)·CΔφ + p)·Nρ + r` for cell
/// `(i, o, p)` (`Cθ`, `CΔφ` the axes' cell counts) at reflectance node `r` holds the corner
/// `(a, b, c)` ∈ {0, 1}³ (the cell's lower or upper θi, θo, Δφ node) at `4a + 2b + c`. A
/// single-node axis has one cell whose upper node is its lower one (weight 0).
fn corner_packets(table: &BrdfTable) -> Vec<f32> {
    let (nt, np, nr) = (table.theta_deg.len(), table.delta_phi_deg.len(), table.reflectance.len());
    let (ct, cp) = ((nt - 1).max(1), (np - 1).max(1));
    let upper = |k: usize, n: usize| (k + 1).min(n - 1);
    let mut out = Vec::with_capacity(ct * ct * cp * nr * 8);
    for i in 0..ct {
        for o in 0..ct {
            for p in 0..cp {
                for r in 0..nr {
                    for a in [i, upper(i, nt)] {
                        for b in [o, upper(o, nt)] {
                            for c in [p, upper(p, np)] {
                                out.push(table.f_over_reflectance[table.index(r, a, b, c)]);
                            }
                        }
                    }
                }
            }
        }
    }
    out
}

/// A table ready for evaluation: the values and the kernel's view of the nodes. `tabulated_brdf`
/// in `matte render` and in the Mitsuba plugin.
///
/// Shared (`Arc`): cloning a model or a scene's BSDF copies a pointer, and the registry's
/// `DiffuseModel` stays as small as its analytic models.
#[derive(Clone, Debug)]
pub struct Tabulated(Arc<TabulatedData>);

/// What a [`Tabulated`] holds.
#[derive(Debug)]
pub struct TabulatedData {
    table: BrdfTable,
    /// The kernel's view of the values ([`corner_packets`]).
    packets: Vec<f32>,
    /// The file it was read from (empty for a table built in memory).
    path: std::path::PathBuf,
    theta: Axis,
    delta_phi: Axis,
    reflectance: Axis,
}

impl Tabulated {
    /// The model of a checked table.
    pub fn new(table: BrdfTable) -> Self {
        Self::with_path(table, std::path::PathBuf::new())
    }

    fn with_path(table: BrdfTable, path: std::path::PathBuf) -> Self {
        let rad = PI / 180.0;
        Tabulated(Arc::new(TabulatedData {
            theta: Axis::new(&table.theta_deg, rad),
            delta_phi: Axis::new(&table.delta_phi_deg, rad),
            reflectance: Axis::new(&table.reflectance, 1.0),
            packets: corner_packets(&table),
            table,
            path,
        }))
    }

    /// Reads and checks a table file ([`BrdfTable::read`]).
    pub fn read(path: &std::path::Path) -> Result<Self, String> {
        BrdfTable::read(path).map(|t| Self::with_path(t, path.to_path_buf()))
    }

    /// The file the table was read from (empty if built in memory).
    pub fn path(&self) -> &std::path::Path {
        &self.path
    }

    pub fn table(&self) -> &BrdfTable {
        &self.table
    }

    /// The values the kernel gathers from: [`BrdfTable::f_over_reflectance`] as the corners
    /// of each interpolation cell, eight per cell and reflectance node ([`corner_packets`]).
    pub fn table_values(&self) -> &[f32] {
        &self.packets
    }

    /// The kernel reading `values` (the CPU's slice of [`Self::table_values`], or the plugin's
    /// registered Dr.Jit buffer).
    pub fn kernel<'t, T: Real + 't>(&'t self, values: T::Table<'t>) -> TableKernel<'t, T> {
        TableKernel { model: self, values }
    }
}

impl std::ops::Deref for Tabulated {
    type Target = TabulatedData;
    fn deref(&self) -> &TabulatedData {
        &self.0
    }
}

/// Two models are the same table read from the same place.
impl PartialEq for Tabulated {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path && self.table.f_over_reflectance == other.table.f_over_reflectance
    }
}

/// `tabulated_brdf` in the registry: its one parameter is the file; its one table, the
/// values the kernel gathers from (a registered Dr.Jit array in the traced plugin). No
/// numeric parameters, so no kernel constants and no textured parameters.
impl Registered for Tabulated {
    const SPEC: ModelSpec = ModelSpec {
        name: PLUGIN_NAME,
        label: "Tabulated",
        summary: "a BRDF table file, `f/ρ` on (ρ, θi, θo, Δφ) nodes, multilinear: the simulated surfaces of `matte microgeometry --table` ([docs](docs/microgeometry.md#the-tabulated-ground-truth-brdf))",
        params: &[ParamSpec::file(
            "filename",
            "the table file; the package's are `ground_truth/<table>.json`",
        )],
        examples: &[],
        in_study: false,
    };
    type Lane<'t, T: Real + 't> = TableKernel<'t, T>;

    fn build(values: &Values) -> Result<Self, ParamError> {
        Tabulated::read(std::path::Path::new(values.file(param!("filename")))).map_err(|e| {
            let line = e.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>().join(" ");
            ParamError::new("filename", line)
        })
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(filename: self.path.display().to_string())
    }

    type Parameters<T: Real> = NoValues;
    type Coefficients<T: Real> = NoValues;

    fn constant_coefficients<T: Real>(&self, _: NoValues, _: Gradients) -> NoValues {
        NoValues
    }

    fn kernel_from<'t, T: Real + 't>(
        &'t self,
        _: NoValues,
        tables: &[T::Table<'t>],
        _: Evaluation,
    ) -> Option<TableKernel<'t, T>> {
        Some(self.kernel(*tables.first()?))
    }

    /// The values, for either evaluation (a table has no numeric parameters to vary per lane).
    fn tables(&self, _: Evaluation) -> Vec<&[f32]> {
        vec![self.table_values()]
    }
}

/// The renderer's and the scalar plugin's f32 kernel; [`DiffuseBrdf`] through it.
impl KernelBrdf for Tabulated {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        // `check` guarantees at least one value.
        self.kernel(Nodes::from_slice(self.table_values()).expect("a checked table has values"))
    }
}

/// The interpolation over [`Real`]: θi, θo and Δφ from the directions (`acos` and `atan2` by
/// the polynomials of [`crate::approx`]), the cells located on the nodes ([`Axis::locate`]),
/// the eight corners of the (θi, θo, Δφ) cell gathered as one packet per reflectance node:
/// at the two nodes around each channel's ρ (two packet gathers per channel), or at every
/// node once for all channels when the table has fewer nodes than that (RGB with the
/// ground-truth tables' five: five packet gathers). Either way an RGB lookup needs up to 40
/// values (8 corners × 5 nodes) and a packet holds 8, Dr.Jit's largest.
#[derive(Clone, Copy)]
pub struct TableKernel<'t, T: Real + 't> {
    model: &'t Tabulated,
    values: T::Table<'t>,
}

impl<'t, T: Real + 't> Kernel<T> for TableKernel<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        let m = self.model;
        let (i, wti) = m.theta.locate(acos_unit(wi.z));
        let (o, wto) = m.theta.locate(acos_unit(wo.z));
        // Δφ = atan2(|wi × wo|_z, wi·wo in the plane): 0 when either direction is the normal.
        let cross = wi.x * wo.y - wi.y * wo.x;
        let (p, wp) = m.delta_phi.locate(angle(cross.abs(), wi.x * wo.x + wi.y * wo.y));
        // The cell's first packet (reflectance node 0), in `corner_packets`' order.
        let nr = m.table.reflectance.len();
        let cell = (i.scale(m.theta.cells() as f64) + o).fma(T::c(m.delta_phi.cells() as f64), p);
        let base = cell.scale(nr as f64);
        let one = T::c(1.0);
        // The corners' weights, in the packet's order (corner (a, b, c) at 4a + 2b + c).
        let weights = [one - wti, wti].map(|a| [one - wto, wto].map(|b| [one - wp, wp].map(|c| a * b * c)));
        let at = |packet: T| {
            let v = T::gather8(self.values, packet);
            let mut sum = T::c(0.0);
            for (w, v) in weights.iter().flatten().flatten().zip(v) {
                sum = w.fma(v, sum);
            }
            sum
        };
        // Every reflectance node's packet once, shared by the channels, when that is fewer
        // gathers than two per channel (RGB and a table's five nodes: five instead of six).
        if nr < 2 * N && nr <= SHARED_NODES {
            let mut at_node = [T::c(0.0); SHARED_NODES];
            for (r, a) in at_node.iter_mut().enumerate().take(nr) {
                *a = at(base + T::c(r as f64));
            }
            return rho.map(|x| x * m.reflectance.interpolate(x, &at_node[..nr]) * T::c(PI));
        }
        let upper = if nr > 1 { one } else { T::c(0.0) };
        rho.map(|x| {
            let (r, wr) = m.reflectance.locate(x);
            let packet = base + r;
            let f_over_rho = (one - wr) * at(packet) + wr * at(packet + upper);
            x * f_over_rho * T::c(PI)
        })
    }
}
