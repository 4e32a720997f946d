//! What an operation hands back for judging ([`Out`]: numeric fields with
//! the power of the length unit each scales with, and any broken invariant)
//! and the comparison of a scaled mesh's result with the unscaled one.

/// How a field changes when every coordinate is multiplied by `s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scaling {
    /// Multiplied by `s^p` (distances 1, areas 2, curvature -1, Gaussian
    /// curvature and eigenvalues -2, angles and normalized UVs 0).
    Power(i32),
    /// Unchanged, exactly (counts).
    Exact,
}

/// One numeric output of an operation.
#[derive(Debug, Clone)]
pub struct Field {
    /// What it is.
    pub name: &'static str,
    /// How it scales.
    pub scaling: Scaling,
    /// `+infinity` is a legitimate value (unreachable vertices).
    pub infinite_ok: bool,
    /// Stored as `f32` on the way (a file format's precision): its range
    /// decides what is representable, its precision the comparison.
    pub single: bool,
    /// The values.
    pub values: Vec<f64>,
}

/// An operation's result, reduced to what the matrix checks.
#[derive(Debug, Clone, Default)]
pub struct Out {
    /// Numeric outputs.
    pub fields: Vec<Field>,
    /// An invariant the result breaks (a silent wrong answer), if any.
    pub wrong: Option<String>,
}

impl Out {
    /// Adds a field that scales with `s^power`.
    pub fn field(mut self, name: &'static str, power: i32, values: Vec<f64>) -> Self {
        self.fields.push(Field { name, scaling: Scaling::Power(power), infinite_ok: false, single: false, values });
        self
    }

    /// Adds values that went through `f32` and scale with `s^power`.
    pub fn single(mut self, name: &'static str, power: i32, values: Vec<f64>) -> Self {
        self.fields.push(Field { name, scaling: Scaling::Power(power), infinite_ok: false, single: true, values });
        self
    }

    /// Adds a distance field: power 1, `+infinity` allowed.
    pub fn distances(mut self, name: &'static str, values: Vec<f64>) -> Self {
        self.fields.push(Field { name, scaling: Scaling::Power(1), infinite_ok: true, single: false, values });
        self
    }

    /// Adds counts, which no scaling may change.
    pub fn counts(mut self, name: &'static str, values: Vec<f64>) -> Self {
        self.fields.push(Field { name, scaling: Scaling::Exact, infinite_ok: false, single: false, values });
        self
    }

    /// Records a broken invariant when `condition` fails.
    pub fn require(mut self, condition: bool, what: impl FnOnce() -> String) -> Self {
        if !condition && self.wrong.is_none() {
            self.wrong = Some(what());
        }
        self
    }

    /// The first NaN (or infinity where not allowed), if any.
    pub fn non_finite(&self) -> Option<String> {
        self.fields.iter().find_map(|f| {
            let i = f.values.iter().position(|x| x.is_nan() || (x.is_infinite() && !(f.infinite_ok && *x > 0.0)))?;
            Some(format!("{}[{i}] = {}", f.name, f.values[i]))
        })
    }
}

/// Flattens points into coordinates.
pub fn xyz(points: &[mesh_kernel::glam::DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

/// Flattens 2D points into coordinates.
pub fn uv(points: &[mesh_kernel::glam::DVec2]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

/// Relative agreement required between a scaled mesh's result and the
/// unscaled one (the target).
pub const SCALE_TOLERANCE: f64 = 1e-9;

/// Largest finite magnitude of a field.
fn magnitude(values: &[f64]) -> f64 {
    values.iter().filter(|x| x.is_finite()).fold(0.0, |m, x| m.max(x.abs()))
}

/// `true` when every field of `reference`, rescaled by `scale`, has a
/// representable answer: its largest magnitude below the largest finite
/// number, and large enough that subnormal rounding of its small entries
/// stays within the comparison's tolerance (f64: at least 1e-314; for
/// fields stored as `f32`, the normal range of f32).
pub fn representable(reference: &Out, scale: f64) -> bool {
    reference.fields.iter().all(|f| match f.scaling {
        Scaling::Exact => true,
        Scaling::Power(p) => {
            let (low, high) = if f.single { (-37.9, 38.5) } else { (-314.0, 308.2) };
            let m = magnitude(&f.values);
            m == 0.0 || (low..high).contains(&(m.log10() + p as f64 * scale.log10()))
        }
    })
}

/// Distance between two points without overflow or underflow of the
/// squares (the difference is scaled by its largest component first).
pub fn distance(a: mesh_kernel::glam::DVec3, b: mesh_kernel::glam::DVec3) -> f64 {
    let d = a - b;
    let k = d.abs().max_element();
    if k == 0.0 || !k.is_finite() {
        k
    } else {
        (d / k).length() * k
    }
}

/// Compares a scaled mesh's result with the unscaled one: each field's
/// largest magnitude equal to the unscaled one times `scale^p` (to
/// [`SCALE_TOLERANCE`] relative, compared in logarithms so nothing
/// overflows), and every value, relative to its field's largest, equal to
/// [`SCALE_TOLERANCE`]; infinities in the same places; counts equal.
pub fn same_up_to_scale(result: &Out, reference: &Out, scale: f64) -> Result<(), String> {
    if !representable(reference, scale) {
        return Err(format!("the answer lies outside the range of f64 at scale {scale:e}, yet a result came back"));
    }
    for (r, u) in result.fields.iter().zip(&reference.fields) {
        if r.values.len() != u.values.len() {
            return Err(format!("{}: {} values, unscaled {}", r.name, r.values.len(), u.values.len()));
        }
        let p = match r.scaling {
            Scaling::Exact => {
                if r.values != u.values {
                    return Err(format!("{}: {:?} vs unscaled {:?}", r.name, r.values, u.values));
                }
                continue;
            }
            Scaling::Power(p) => p,
        };
        if let Some(i) = (0..r.values.len()).find(|&i| r.values[i].is_infinite() != u.values[i].is_infinite()) {
            return Err(format!("{}[{i}] = {:e}, unscaled {:e}", r.name, r.values[i], u.values[i]));
        }
        let (mr, mu) = (magnitude(&r.values), magnitude(&u.values));
        if mu == 0.0 || mr == 0.0 {
            if mu != mr {
                return Err(format!("{}: largest |value| {mr:e}, unscaled {mu:e}", r.name));
            }
            continue;
        }
        let tolerance = if r.single { 2.0 * f64::from(f32::EPSILON) } else { SCALE_TOLERANCE };
        let log_error = (mr.ln() - mu.ln() - p as f64 * scale.ln()).abs();
        if log_error > tolerance {
            let expected = 10f64.powf(mu.log10() + p as f64 * scale.log10());
            return Err(format!(
                "{}: largest |value| {mr:e}, expected {expected:e} (unscaled {mu:e} x scale^{p})",
                r.name
            ));
        }
        let worst = (0..r.values.len())
            .filter(|&i| r.values[i].is_finite())
            .map(|i| (i, (r.values[i] / mr - u.values[i] / mu).abs()))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        if worst.1 > tolerance {
            let i = worst.0;
            return Err(format!(
                "{}[{i}] = {:e}, unscaled {:e}: relative difference {:.1e}",
                r.name, r.values[i], u.values[i], worst.1
            ));
        }
    }
    Ok(())
}

/// Compares, value by value, a scaled mesh's result whose answer leaves the
/// range of f64 with the unscaled one: where `u * scale^p` overflows the
/// result must be the infinity of its sign, where it falls below the
/// smallest subnormal it must be zero (the correctly rounded answers), and
/// elsewhere equal to [`SCALE_TOLERANCE`] relative (or tiny, in the
/// subnormal range); never NaN.
pub fn saturated(result: &Out, reference: &Out, scale: f64) -> Result<(), String> {
    for (r, u) in result.fields.iter().zip(&reference.fields) {
        if r.values.len() != u.values.len() {
            return Err(format!("{}: {} values, unscaled {}", r.name, r.values.len(), u.values.len()));
        }
        let p = match r.scaling {
            Scaling::Exact if r.values != u.values => {
                return Err(format!("{}: {:?} vs unscaled {:?}", r.name, r.values, u.values))
            }
            Scaling::Exact => continue,
            Scaling::Power(p) => p,
        };
        let (high, low) = if r.single { (38.5, -45.0) } else { (308.2, -323.0) };
        let largest = magnitude(&u.values);
        for (i, (&x, &y)) in r.values.iter().zip(&u.values).enumerate() {
            let bad = |why: &str| Err(format!("{}[{i}] = {x:e}, unscaled {y:e}: {why}", r.name));
            if x.is_nan() {
                return bad("NaN");
            }
            if y.is_infinite() {
                if x != y {
                    return bad("not the unscaled infinity");
                }
                continue;
            }
            // Back to the unit scale one factor at a time.
            let back = (0..p.unsigned_abs()).fold(x, |v, _| if p > 0 { v / scale } else { v * scale });
            let noise = y.abs() <= SCALE_TOLERANCE * largest;
            let log = if y == 0.0 { f64::NEG_INFINITY } else { y.abs().log10() + p as f64 * scale.log10() };
            let ok = if noise {
                // A value at the rounding-noise level of its field: any
                // number (its noise may saturate either way), never NaN.
                !x.is_nan()
            } else if log > high {
                x.is_infinite() && x.signum() == y.signum()
            } else if log < low {
                x == 0.0
            } else {
                // Within the tolerance of the field's largest value.
                x.is_finite() && (back - y).abs() <= SCALE_TOLERANCE * largest
            };
            if !ok {
                return bad("not the correctly rounded rescaled value");
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_comparison() {
        let u = Out::default().field("d", 1, vec![0.0, 1.0, 2.0]).counts("n", vec![3.0]);
        let r = Out::default().field("d", 1, vec![0.0, 1e300, 2e300]).counts("n", vec![3.0]);
        assert!(same_up_to_scale(&r, &u, 1e300).is_ok());
        let wrong = Out::default().field("d", 1, vec![0.0, 1e300, 2.1e300]).counts("n", vec![3.0]);
        assert!(same_up_to_scale(&wrong, &u, 1e300).is_err());
        let zero = Out::default().field("d", 1, vec![0.0, 0.0, 0.0]).counts("n", vec![3.0]);
        assert!(same_up_to_scale(&zero, &u, 1e-300).is_err());
        // Eigenvalues (power -2) of a mesh scaled by 1e300 underflow.
        let k = Out::default().field("k", -2, vec![2.0]);
        assert!(!representable(&k, 1e300));
        assert!(representable(&k, 1e100));
        // Past the range: the correctly rounded values (0 and infinity) pass.
        assert!(saturated(&Out::default().field("k", -2, vec![0.0]), &k, 1e300).is_ok());
        assert!(saturated(&Out::default().field("k", -2, vec![1e-300]), &k, 1e300).is_err());
        let a = Out::default().field("a", 2, vec![2.0, 0.0]);
        assert!(saturated(&Out::default().field("a", 2, vec![f64::INFINITY, 0.0]), &a, 1e300).is_ok());
        assert!(saturated(&Out::default().field("a", 2, vec![f64::NAN, 0.0]), &a, 1e300).is_err());
    }
}
