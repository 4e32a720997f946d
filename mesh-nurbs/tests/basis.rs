//! Invariants of the B-spline basis (eq. 2.1-2.2): partition of unity,
//! non-negativity, local support, and the Bernstein basis as the special case
//! of a clamped knot vector without interior knots.

use mesh_nurbs::basis::{basis_derivatives, basis_function, basis_values};
use mesh_nurbs::KnotVector;
use proptest::prelude::*;

/// Random valid knot vectors: clamped ends and sorted interior knots.
fn knot_vector() -> impl Strategy<Value = KnotVector> {
    (1usize..=6, prop::collection::vec(0.0f64..1.0, 0..10)).prop_map(|(p, mut interior)| {
        interior.sort_by(f64::total_cmp);
        // Keep multiplicities <= p by dropping excess repeats (rare with floats).
        let mut knots = vec![0.0; p + 1];
        knots.extend(interior.into_iter().filter(|&t| t > 0.0 && t < 1.0));
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        KnotVector::new(p, knots).expect("valid by construction")
    })
}

proptest! {
    #[test]
    fn partition_of_unity_and_non_negativity(kv in knot_vector(), u in 0.0f64..=1.0) {
        let p = kv.degree();
        let span = kv.span(u);
        let n = basis_values(&kv, span, u);
        let sum: f64 = n[..=p].iter().sum();
        prop_assert!((sum - 1.0).abs() < 1e-13);
        prop_assert!(n[..=p].iter().all(|&x| x >= -1e-15));
        // The reference recursion agrees, and is zero outside the span (local support).
        let mut total = 0.0;
        for i in 0..kv.control_count() {
            let value = basis_function(&kv, i, u);
            prop_assert!(value >= -1e-15);
            if i + p < span || i > span {
                prop_assert_eq!(value, 0.0);
            } else {
                prop_assert!((value - n[i + p - span]).abs() < 1e-13);
            }
            total += value;
        }
        prop_assert!((total - 1.0).abs() < 1e-13);
    }

    #[test]
    fn derivatives_of_the_partition_vanish(kv in knot_vector(), u in 0.0f64..=1.0) {
        let p = kv.degree();
        let d = basis_derivatives::<3>(&kv, kv.span(u), u);
        for k in 1..3 {
            let sum: f64 = d[k][..=p].iter().sum();
            let scale: f64 = d[k][..=p].iter().map(|x| x.abs()).sum::<f64>().max(1.0);
            prop_assert!(sum.abs() < 1e-10 * scale, "order {} sum {}", k, sum);
        }
    }

    #[test]
    fn support_is_local(kv in knot_vector(), i in 0usize..16, u in 0.0f64..=1.0) {
        let p = kv.degree();
        let t = kv.knots();
        prop_assume!(i < kv.control_count());
        // N_{i,p} vanishes outside [t_i, t_{i+p+1}).
        if u < t[i] || (u >= t[i + p + 1] && u < 1.0) {
            prop_assert_eq!(basis_function(&kv, i, u), 0.0);
        }
    }
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

/// Bernstein polynomial `B_{i,n}(u)` and its first two derivatives.
fn bernstein(n: usize, i: usize, u: f64) -> [f64; 3] {
    let b = |n: usize, i: isize| -> f64 {
        if i < 0 || i as usize > n {
            0.0
        } else {
            binomial(n, i as usize) * u.powi(i as i32) * (1.0 - u).powi((n - i as usize) as i32)
        }
    };
    let i = i as isize;
    let d1 = n as f64 * (b(n - 1, i - 1) - b(n - 1, i));
    let d2 = (n * (n - 1)) as f64 * (b(n - 2, i - 2) - 2.0 * b(n - 2, i - 1) + b(n - 2, i));
    [b(n, i), d1, d2]
}

#[test]
fn clamped_cubic_is_bernstein() {
    let kv = KnotVector::clamped_uniform(3, 4).expect("valid knots");
    for s in 0..=100 {
        let u = s as f64 / 100.0;
        let span = kv.span(u);
        assert_eq!(span, 3);
        let d = basis_derivatives::<4>(&kv, span, u);
        for i in 0..4 {
            let b = bernstein(3, i, u);
            for k in 0..3 {
                assert!((d[k][i] - b[k]).abs() < 1e-12, "u {u} i {i} order {k}: {} vs {}", d[k][i], b[k]);
            }
            assert!((basis_function(&kv, i, u) - b[0]).abs() < 1e-14);
        }
        // Third derivative of a cubic Bernstein polynomial is constant: 6 (-1)^(3-i) C(3,i).
        for i in 0..4 {
            let sign = if (3 - i) % 2 == 0 { 1.0 } else { -1.0 };
            assert!((d[3][i] - 6.0 * sign * binomial(3, i)).abs() < 1e-10);
        }
    }
}

#[test]
fn last_knot_is_the_limit_from_the_left() {
    let kv = KnotVector::clamped_uniform(3, 7).expect("valid knots");
    let n = basis_values(&kv, kv.span(1.0), 1.0);
    assert_eq!(&n[..4], &[0.0, 0.0, 0.0, 1.0]);
    assert_eq!(basis_function(&kv, 6, 1.0), 1.0);
    assert_eq!(basis_function(&kv, 5, 1.0), 0.0);
}

#[test]
fn wrong_spans_do_not_panic() {
    let kv = KnotVector::clamped_uniform(3, 6).expect("valid knots");
    for span in [0, 1, 2, 100, usize::MAX] {
        let n = basis_values(&kv, span, 0.5);
        assert!(n.iter().all(|x| x.is_finite()));
        let d = basis_derivatives::<3>(&kv, span, f64::NAN);
        assert!(d.len() == 3);
    }
}
